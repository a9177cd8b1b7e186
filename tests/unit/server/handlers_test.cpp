// Every route's handler as a pure function of its request, through a recording Exchange: no
// socket, no session, no worker pool. The integration tests run the same routes over loopback;
// these pin down what each handler answers for each kind of request.

#include "handlers.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "corpus.hpp"
#include "ncpost/pipeline/process.hpp"
#include "xml_check.hpp"

namespace ncpost::server {
namespace {

using json = nlohmann::json;

// What a handler produced: one response, or a stream of chunks with how it ended.
struct Recorded {
  [[nodiscard]] json problem() const { return json::parse(body); }
  [[nodiscard]] std::string first_code() const {
    const json j = problem();
    return j["diagnostics"].empty() ? "" : j["diagnostics"][0]["code"].get<std::string>();
  }

  bool answered = false, streamed = false, ended = false, complete = false;
  unsigned status = 0;
  std::map<std::string, std::string> headers, trailer;
  std::string body;
};

class RecordingExchange final : public Exchange {
 public:
  void respond(Response r) override {
    ASSERT_FALSE(out.answered) << "a handler answers once";
    out.answered = true;
    out.status = r.result_int();
    for (const auto& field : r) out.headers[std::string(field.name_string())] = field.value();
    out.body = std::move(r.body());
  }
  bool begin_stream(StreamHead head) override {
    EXPECT_FALSE(out.answered) << "a handler answers once";
    out.answered = out.streamed = true;
    out.status = head.result_int();
    for (const auto& field : head) out.headers[std::string(field.name_string())] = field.value();
    return true;
  }
  bool write(std::string_view piece) override {
    EXPECT_TRUE(out.streamed && !out.ended);
    out.body.append(piece);
    return true;
  }
  void end_stream(bool whole, http::fields trailer_fields) override {
    EXPECT_TRUE(out.streamed && !out.ended);
    out.ended = true;
    out.complete = whole;
    for (const auto& field : trailer_fields)
      out.trailer[std::string(field.name_string())] = field.value();
  }
  [[nodiscard]] const std::atomic<bool>* cancel_flag() const noexcept override { return &cancel; }
  [[nodiscard]] bool timed_out() const noexcept override { return false; }

  std::atomic<bool> cancel{false};
  Recorded out;
};

class Handlers : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { pipeline::initialise_process(); }

  void SetUp() override {
    services_.profiles = &profiles_;
    services_.schemas = &schemas_;
    services_.metrics = &metrics_;
    services_.web_root = test::source_dir() / "web";
    services_.openapi_file = test::source_dir() / "openapi/openapi.yaml";
    services_.engine_version = "test";
  }

  // Runs the handler that the router chooses for `method target`, as the session would.
  Recorded run(http::verb method, std::string target, std::string body = {},
               std::map<std::string, std::string> fields = {}, bool cancelled = false) {
    Request request{method, target, 11};
    for (const auto& [name, value] : fields) request.set(name, value);
    request.body() = std::move(body);
    request.prepare_payload();
    RecordingExchange exchange;
    exchange.cancel = cancelled;
    const RouteMatch match = match_route(method, target);
    if (match.route == nullptr) {
      exchange.out.status = match.status;
      return exchange.out;
    }
    exchange.path_id = match.id;
    match.route->handler(request, services_, exchange);
    EXPECT_TRUE(exchange.out.answered) << target;
    EXPECT_TRUE(!exchange.out.streamed || exchange.out.ended) << target << ": stream never ended";
    return std::move(exchange.out);
  }

  static std::string example() {
    return test::read_file(test::source_dir() / "tests/golden/trace/cases/executables.stp");
  }

  pipeline::Profiles profiles_;
  pipeline::Schemas schemas_;
  Metrics metrics_;
  Services services_;
};

TEST_F(Handlers, HealthAndReadiness) {
  const auto health = run(http::verb::get, "/healthz");
  EXPECT_EQ(health.status, 200u);
  EXPECT_EQ(json::parse(health.body)["status"], "ok");
  const auto ready = run(http::verb::get, "/readyz");
  EXPECT_EQ(ready.status, 200u);
  EXPECT_EQ(json::parse(ready.body)["status"], "ready");
  services_.saturated = [] { return true; };
  const auto full = run(http::verb::get, "/readyz");
  EXPECT_EQ(full.status, 503u);
  EXPECT_EQ(full.headers.at("Retry-After"), "1");
}

TEST_F(Handlers, MetricsOpenApiAndIndex) {
  EXPECT_EQ(run(http::verb::get, "/metrics").status, 200u);
  const auto spec = run(http::verb::get, "/openapi.yaml");
  EXPECT_EQ(spec.status, 200u);
  EXPECT_NE(spec.body.find("openapi:"), std::string::npos);
  const auto index = run(http::verb::get, "/");
  EXPECT_EQ(index.status, 200u);
  EXPECT_EQ(index.headers.at("Content-Type"), "text/html; charset=utf-8");
  services_.openapi_file = "/nonexistent/openapi.yaml";
  EXPECT_EQ(run(http::verb::get, "/openapi.yaml").status, 404u);
}

TEST_F(Handlers, ProfilesListAndGet) {
  const auto list = run(http::verb::get, "/v1/profiles");
  EXPECT_EQ(list.status, 200u);
  const json profiles = json::parse(list.body)["profiles"];
  EXPECT_GE(profiles.size(), 11u);
  const auto fanuc = run(http::verb::get, "/v1/profiles/fanuc-0i");
  ASSERT_EQ(fanuc.status, 200u) << fanuc.body;
  EXPECT_EQ(json::parse(fanuc.body)["id"], "fanuc-0i");
  const std::string etag = fanuc.headers.at("ETag");
  EXPECT_EQ(run(http::verb::get, "/v1/profiles/fanuc-0i", {}, {{"If-None-Match", etag}}).status,
            304u);
  const auto unknown = run(http::verb::get, "/v1/profiles/no-such-machine");
  EXPECT_EQ(unknown.status, 404u);
  EXPECT_EQ(unknown.problem()["type"], "urn:ncpost:problem:PROFILE-003");
}

TEST_F(Handlers, ProfileChangesNeedTheTokenAndAWritableStore) {
  const auto anonymous = run(http::verb::delete_, "/v1/profiles/fanuc-0i");
  EXPECT_EQ(anonymous.status, 401u);
  EXPECT_TRUE(anonymous.headers.count("WWW-Authenticate"));
  services_.admin_token = "secret";
  EXPECT_EQ(
      run(http::verb::delete_, "/v1/profiles/fanuc-0i", {}, {{"Authorization", "Bearer wrong"}})
          .status,
      403u);
  EXPECT_EQ(
      run(http::verb::delete_, "/v1/profiles/fanuc-0i", {}, {{"Authorization", "Bearer secret"}})
          .status,
      409u);
  const std::string multipart =
      "--B\r\nContent-Disposition: form-data; name=\"profile\"\r\n\r\n{}\r\n"
      "--B\r\nContent-Disposition: form-data; name=\"stylesheet\"\r\n\r\n<x/>\r\n--B--\r\n";
  const auto put = run(
      http::verb::put, "/v1/profiles/mine", multipart,
      {{"Authorization", "Bearer secret"}, {"Content-Type", "multipart/form-data; boundary=B"}});
  EXPECT_EQ(put.status, 409u) << put.body;
  EXPECT_EQ(put.problem()["type"], "urn:ncpost:problem:PROFILE-006");
  EXPECT_EQ(run(http::verb::put, "/v1/profiles/mine", "{}",
                {{"Authorization", "Bearer secret"}, {"Content-Type", "application/json"}})
                .status,
            400u);
}

// Issue 23 (2): the store replaces only profiles, and /readyz fails while a profile does not
// compile instead of letting every post answer 500.
TEST_F(Handlers, ReservedNamesAndBrokenProfiles) {
  namespace fs = std::filesystem;
  const fs::path dir =
      fs::temp_directory_path() / ("ncpost-handlers-" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir / "keepme");
  std::ofstream(dir / "keepme" / "notes.txt") << "notes\n";
  auto store = pipeline::Profiles::writable_over_builtins(dir);
  services_.profiles = store.get();
  services_.admin_token = "secret";
  EXPECT_EQ(run(http::verb::get, "/readyz").status, 200u);
  const std::string profile_json =
      test::read_file(test::source_dir() / "stylesheets/linuxcnc/profile.json");
  const auto multipart = [&](const std::string& id) {
    std::string renamed = profile_json;
    renamed.replace(renamed.find("\"linuxcnc\""), 10, "\"" + id + "\"");
    return "--B\r\nContent-Disposition: form-data; name=\"profile\"\r\n\r\n" + renamed +
           "\r\n--B\r\nContent-Disposition: form-data; name=\"stylesheet\"\r\n\r\n" +
           test::read_file(test::source_dir() / "stylesheets/linuxcnc/post.xsl") + "\r\n--B--\r\n";
  };
  const std::map<std::string, std::string> admin = {
      {"Authorization", "Bearer secret"}, {"Content-Type", "multipart/form-data; boundary=B"}};
  for (const char* id : {"common", "keepme"}) {
    const auto put = run(http::verb::put, std::string("/v1/profiles/") + id, multipart(id), admin);
    EXPECT_EQ(put.status, 409u) << id << put.body;
    EXPECT_EQ(put.problem()["type"], "urn:ncpost:problem:PROFILE-009") << put.body;
  }
  EXPECT_TRUE(fs::exists(dir / "keepme" / "notes.txt"));
  EXPECT_EQ(run(http::verb::post, "/v1/posts?profile=linuxcnc", example()).status, 200u);

  // A profile placed by hand whose stylesheet does not compile: not ready, and named.
  fs::create_directories(dir / "broken");
  std::string broken_json = profile_json;
  broken_json.replace(broken_json.find("\"linuxcnc\""), 10, "\"broken\"");
  std::ofstream(dir / "broken" / "profile.json") << broken_json;
  std::ofstream(dir / "broken" / "post.xsl") << "<xsl:stylesheet";
  const auto ready = run(http::verb::get, "/readyz");
  EXPECT_EQ(ready.status, 503u) << ready.body;
  EXPECT_EQ(json::parse(ready.body)["broken_profiles"], json::array({"broken"})) << ready.body;
  services_.profiles = &profiles_;
  fs::remove_all(dir);
}

// Issue 23 (6, 7, 12): Accept by media ranges and q-values, If-None-Match by weak comparison,
// and a download name that keeps the upload's non-ASCII characters.
TEST_F(Handlers, ContentNegotiationFollowsTheRfcs) {
  const auto text = run(http::verb::post, "/v1/posts?profile=linuxcnc", example(),
                        {{"Accept", "application/json;q=0.1, text/plain"}});
  ASSERT_EQ(text.status, 200u) << text.body;
  EXPECT_TRUE(text.streamed);
  const auto upper = run(http::verb::post, "/v1/posts?profile=linuxcnc", example(),
                         {{"Accept", "APPLICATION/JSON"}});
  ASSERT_EQ(upper.status, 200u) << upper.body;
  EXPECT_TRUE(json::parse(upper.body).contains("program"));

  const auto fanuc = run(http::verb::get, "/v1/profiles/fanuc-0i");
  const std::string etag = fanuc.headers.at("ETag");
  for (const std::string& condition : {"W/" + etag, "\"other\", " + etag, std::string("*")})
    EXPECT_EQ(
        run(http::verb::get, "/v1/profiles/fanuc-0i", {}, {{"If-None-Match", condition}}).status,
        304u)
        << condition;
  EXPECT_EQ(
      run(http::verb::get, "/v1/profiles/fanuc-0i", {}, {{"If-None-Match", "\"other\""}}).status,
      200u);

  const auto named =
      run(http::verb::post, "/v1/posts?profile=linuxcnc&name=Teil%20%C3%98%2050.stp", example());
  ASSERT_EQ(named.status, 200u) << named.body;
  EXPECT_EQ(named.headers.at("Content-Disposition"),
            "attachment; filename=\"Teil___50.ngc\"; filename*=UTF-8''Teil%20%C3%98%2050.ngc");
}

// Issue 23 (13): what openapi.yaml documents. An id no profile can have is 400 on every route
// that takes one; the JSON form of a post carries the headers its 200 lists for it.
TEST_F(Handlers, InvalidProfileIdsAndTheJsonPostsHeaders) {
  services_.admin_token = "secret";
  const std::map<std::string, std::string> admin = {{"Authorization", "Bearer secret"}};
  for (const auto& [method, target] : std::vector<std::pair<http::verb, std::string>>{
           {http::verb::get, "/v1/profiles/UPPER"},
           {http::verb::delete_, "/v1/profiles/a~b"},
           {http::verb::put, "/v1/profiles/.hidden"},
           {http::verb::post, "/v1/posts?profile=..%2Fetc"},
           {http::verb::post, "/v1/nc/translate?from=Fanuc&to=linuxcnc"}}) {
    const auto r = run(method, target, example(), admin);
    EXPECT_EQ(r.status, 400u) << target << r.body;
    if (r.status == 400u) {
      EXPECT_EQ(r.problem()["type"], "urn:ncpost:problem:PROFILE-008");
    }
  }
  // Issue 23 (10): two programs in one request: which one was meant cannot be guessed.
  const std::string two_files =
      "--B\r\nContent-Disposition: form-data; name=\"file\"; filename=\"a.stp\"\r\n\r\n" +
      example() +
      "\r\n--B\r\nContent-Disposition: form-data; name=\"file\"; filename=\"b.stp\"\r\n\r\n" +
      example() + "\r\n--B--\r\n";
  const auto twice = run(http::verb::post, "/v1/traces", two_files,
                         {{"Content-Type", "multipart/form-data; boundary=B"}});
  EXPECT_EQ(twice.status, 400u) << twice.body;
  const auto posted = run(http::verb::post, "/v1/posts?profile=linuxcnc", example(),
                          {{"Accept", "application/json"}});
  ASSERT_EQ(posted.status, 200u) << posted.body;
  EXPECT_EQ(posted.headers.at("ETag").size(), 34u);
  EXPECT_EQ(posted.headers.at("X-Ncpost-Profile-Version"),
            json::parse(posted.body)["profile_version"]);
  EXPECT_EQ(posted.headers.at("Vary"), "Accept");
}

TEST_F(Handlers, PostStreamsTheProgramWithItsTrailer) {
  const auto posted =
      run(http::verb::post, "/v1/posts?profile=linuxcnc&name=bracket.stp", example());
  ASSERT_EQ(posted.status, 200u) << posted.body;
  EXPECT_TRUE(posted.streamed);
  EXPECT_TRUE(posted.complete);
  EXPECT_EQ(posted.headers.at("Content-Disposition"), "attachment; filename=\"bracket.ngc\"");
  EXPECT_TRUE(posted.headers.count("ETag"));
  EXPECT_NE(posted.body.find("M2"), std::string::npos);
  const std::string warnings = posted.trailer.at("Ncpost-Warnings");
  EXPECT_FALSE(warnings.empty());
  EXPECT_EQ(warnings.find_first_not_of("0123456789"), std::string::npos) << warnings;
  // The same input again, with its ETag: nothing to send.
  const auto again = run(http::verb::post, "/v1/posts?profile=linuxcnc", example(),
                         {{"If-None-Match", posted.headers.at("ETag")}});
  EXPECT_EQ(again.status, 304u);
}

TEST_F(Handlers, PostAsJsonMapsBlocksToWorkingsteps) {
  const auto posted = run(http::verb::post, "/v1/posts?profile=fanuc-0i", example(),
                          {{"Accept", "application/json"}});
  ASSERT_EQ(posted.status, 200u) << posted.body;
  const json body = json::parse(posted.body);
  EXPECT_EQ(body["profile"], "fanuc-0i");
  EXPECT_FALSE(body["program"].get<std::string>().empty());
  EXPECT_FALSE(body["workingsteps"].empty());
  EXPECT_FALSE(body["blocks"].empty());
}

// Each motion's lines in the JSON post: as many entries as the trace has motions, in order,
// each [first, last] within the program, never going back.
TEST_F(Handlers, PostAsJsonGivesEachMotionsLines) {
  const auto posted = run(http::verb::post, "/v1/posts?profile=linuxcnc&motions=true", example(),
                          {{"Accept", "application/json"}});
  ASSERT_EQ(posted.status, 200u) << posted.body;
  const json body = json::parse(posted.body);
  // Only when asked: it costs a transform per call.
  EXPECT_FALSE(json::parse(run(http::verb::post, "/v1/posts?profile=linuxcnc", example(),
                               {{"Accept", "application/json"}})
                               .body)
                   .contains("motions"));
  EXPECT_EQ(run(http::verb::post, "/v1/posts?profile=linuxcnc&motions=maybe", example()).status,
            400u);
  const auto trace = run(http::verb::post, "/v1/traces?format=json", example());
  std::size_t motions = 0;
  for (std::size_t at = 0; (at = trace.body.find("\"call\":\"", at)) != std::string::npos; ++at) {
    const std::string_view rest = std::string_view(trace.body).substr(at + 8);
    for (const char* m : {"STRAIGHT_", "ARC_FEED", "NURBS_FEED", "DRILL_CYCLE", "BORE_CYCLE"})
      if (rest.substr(0, std::string_view(m).size()) == m) ++motions;
  }
  ASSERT_GT(motions, 3u);
  ASSERT_EQ(body["motions"].size(), motions);
  const std::string program = body["program"];
  const auto program_lines =
      static_cast<std::size_t>(std::count(program.begin(), program.end(), '\n'));
  std::size_t previous = 0;
  for (const auto& m : body["motions"]) {
    if (m.is_null()) continue;
    EXPECT_LE(previous, m[0].get<std::size_t>());
    EXPECT_LE(m[0].get<std::size_t>(), m[1].get<std::size_t>());
    EXPECT_LE(m[1].get<std::size_t>(), program_lines);
    previous = m[1];
  }
  // The streamed program is the same text.
  EXPECT_EQ(run(http::verb::post, "/v1/posts?profile=linuxcnc", example()).body, body["program"]);
}

TEST_F(Handlers, TraceAsJson) {
  const auto lines = run(http::verb::post, "/v1/traces?format=json", example());
  ASSERT_EQ(lines.status, 200u) << lines.body;
  EXPECT_TRUE(lines.streamed && lines.complete);
  EXPECT_EQ(lines.headers.at("Content-Type"), "application/x-ndjson");
  std::vector<json> records;
  std::istringstream in(lines.body);
  for (std::string line; std::getline(in, line);) records.push_back(json::parse(line));
  ASSERT_GE(records.size(), 3u);
  EXPECT_EQ(records.front()["format"], "ncpost-trace");
  EXPECT_TRUE(records.front()["stock"].is_array());
  EXPECT_EQ(records.back()["end"], true);
  EXPECT_EQ(records.back()["ok"], true);
  EXPECT_EQ(records.back()["call_count"], records.size() - 2);
  EXPECT_EQ(records[1]["call"], "PROJECT_BEGIN");
  // The text trace has the same calls, line for line.
  const auto text = run(http::verb::post, "/v1/traces", example());
  EXPECT_EQ(static_cast<std::size_t>(std::count(text.body.begin(), text.body.end(), '\n')),
            records.size() - 2);
  // Accept chooses the form when format= is absent; format= wins.
  const auto ndjson =
      run(http::verb::post, "/v1/traces", example(), {{"Accept", "application/x-ndjson"}});
  EXPECT_EQ(ndjson.body, lines.body);
  const auto document =
      run(http::verb::post, "/v1/traces", example(), {{"Accept", "application/json"}});
  EXPECT_EQ(document.headers.at("Content-Type"), "application/json");
  const json whole = json::parse(document.body);
  EXPECT_EQ(whole["calls"].size(), records.size() - 2);
  EXPECT_EQ(whole["calls"][0], records[1]);
  EXPECT_EQ(whole["ok"], true);
  EXPECT_EQ(
      run(http::verb::post, "/v1/traces?format=text", example(), {{"Accept", "application/json"}})
          .body,
      text.body);
  // Unreadable: a problem, not a stream.
  const auto unreadable = run(http::verb::post, "/v1/traces?format=json", "hello\n");
  EXPECT_EQ(unreadable.status, 422u);
  EXPECT_FALSE(unreadable.streamed);
}

TEST_F(Handlers, PostRefusals) {
  EXPECT_EQ(run(http::verb::post, "/v1/posts", example()).status, 400u);
  EXPECT_EQ(run(http::verb::post, "/v1/posts?profile=no-such", example()).status, 404u);
  EXPECT_EQ(run(http::verb::post, "/v1/posts?profile=linuxcnc&strict=maybe", example()).status,
            400u);
  EXPECT_EQ(run(http::verb::post, "/v1/posts?profile=linuxcnc", "").status, 400u);
  const auto unreadable = run(http::verb::post, "/v1/posts?profile=linuxcnc", "hello\n");
  EXPECT_EQ(unreadable.status, 422u);
  EXPECT_EQ(unreadable.first_code(), "IO-002");
  const auto broken = run(
      http::verb::post, "/v1/posts?profile=linuxcnc",
      test::read_file(test::source_dir() / "tests/golden/p21-malformed/dangling-reference.stp"));
  EXPECT_EQ(broken.status, 422u);
  EXPECT_EQ(broken.problem()["type"], "urn:ncpost:problem:input-rejected");
  EXPECT_EQ(broken.first_code(), "P21-040");
}

TEST_F(Handlers, TraceInspectConvertVerify) {
  const auto trace = run(http::verb::post, "/v1/traces", example());
  ASSERT_EQ(trace.status, 200u) << trace.body;
  EXPECT_EQ(trace.body.rfind("PROJECT_BEGIN", 16), 6u);
  const auto xml = run(http::verb::post, "/v1/traces?format=xml", example());
  EXPECT_EQ(xml.status, 200u);
  EXPECT_TRUE(test::well_formed(xml.body));
  EXPECT_EQ(run(http::verb::post, "/v1/traces?format=yaml", example()).status, 400u);

  const auto inspection = run(http::verb::post, "/v1/inspections", example());
  ASSERT_EQ(inspection.status, 200u) << inspection.body;
  EXPECT_EQ(json::parse(inspection.body)["project"]["name"], "EXECUTABLES");

  const auto converted = run(http::verb::post, "/v1/conversions?to=p28", example());
  ASSERT_EQ(converted.status, 200u);
  EXPECT_TRUE(converted.complete);
  EXPECT_TRUE(test::well_formed(converted.body));
  EXPECT_EQ(run(http::verb::post, "/v1/conversions?to=p21&binding=early", example()).status, 400u);
  EXPECT_EQ(run(http::verb::post, "/v1/conversions?to=p21", "hello").status, 422u);

  const auto verified = run(http::verb::post, "/v1/verifications", example());
  ASSERT_EQ(verified.status, 200u) << verified.body;
  EXPECT_TRUE(json::parse(verified.body).contains("features"));
  EXPECT_EQ(run(http::verb::post, "/v1/verifications?tolerance=-1", example()).status, 400u);
}

TEST_F(Handlers, InspectionOfABrokenFileCarriesWhatCouldBeRead) {
  const auto inspection = run(
      http::verb::post, "/v1/inspections",
      test::read_file(test::source_dir() / "tests/golden/p21-malformed/dangling-reference.stp"));
  EXPECT_EQ(inspection.status, 422u);
  const json body = inspection.problem();
  EXPECT_TRUE(body.contains("inspection"));
  EXPECT_EQ(body["diagnostics"][0]["code"], "P21-040");
}

TEST_F(Handlers, SchemaAsExpressX) {
  const auto schema = run(http::verb::post, "/v1/schemas",
                          "SCHEMA s; ENTITY e; a : INTEGER; END_ENTITY; END_SCHEMA;");
  ASSERT_EQ(schema.status, 200u) << schema.body;
  EXPECT_TRUE(test::well_formed(schema.body));
  EXPECT_EQ(run(http::verb::post, "/v1/schemas", "SCHEMA s; ENTITY").status, 422u);
}

TEST_F(Handlers, CancelledJobsStopWithoutAProgram) {
  // The client went away before the job ran: no program, a 499 for the access log.
  for (const char* target : {"/v1/traces", "/v1/posts?profile=linuxcnc", "/v1/inspections"}) {
    const auto cancelled = run(http::verb::post, target, example(), {}, true);
    EXPECT_EQ(cancelled.status, 499u) << target;
    EXPECT_FALSE(cancelled.streamed) << target;
  }
}

}  // namespace
}  // namespace ncpost::server
