// The HTTP contract both ways: every route of the server's route table is described in
// openapi/openapi.yaml, and every path and method the description names is answered by the real
// ncpostd (anything but the router's 404 / 405). The description's own validity is
// ctest openapi_lint (openapi_lint.sh, with the pinned @redocly/cli).

#include <gtest/gtest.h>

#include <fstream>
#include <regex>
#include <set>

#include "corpus.hpp"
#include "handlers.hpp"
#include "server_process.hpp"

namespace ncpost::test {
namespace {

namespace fs = std::filesystem;
using Operation = std::pair<std::string, std::string>;  // METHOD, path template

// The operations of the description: the keys under `paths:` (two spaces in) and their
// methods (four spaces in). openapi.yaml keeps that layout (block style, two-space indents);
// the check below fails loudly if it finds no paths at all.
std::set<Operation> spec_operations(const std::string& yaml) {
  std::set<Operation> out;
  std::istringstream in(yaml);
  std::string line, path;
  bool in_paths = false;
  const std::regex path_line(R"(^  (/[^:\s]*):\s*$)");
  const std::regex method_line(R"(^    (get|put|post|delete|patch|head|options|trace):\s*$)");
  std::smatch m;
  while (std::getline(in, line)) {
    if (!line.empty() && line[0] != ' ' && line[0] != '#') {
      in_paths = line.rfind("paths:", 0) == 0;
      path.clear();
      continue;
    }
    if (!in_paths) continue;
    if (std::regex_match(line, m, path_line)) {
      path = m[1];
    } else if (!path.empty() && std::regex_match(line, m, method_line)) {
      std::string method = m[1];
      for (char& c : method) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
      out.insert({method, path});
    }
  }
  return out;
}

std::set<Operation> server_operations() {
  std::set<Operation> out;
  for (const auto& route : server::routes())
    out.insert({std::string(server::http::to_string(route.method)), std::string(route.pattern)});
  return out;
}

std::string spec_text() {
  return read_file(source_dir() / "openapi/openapi.yaml");
}

TEST(OpenApi, EveryServerRouteIsDescribed) {
  const auto spec = spec_operations(spec_text());
  ASSERT_GE(spec.size(), 10u) << "no paths found: has openapi.yaml's layout changed?";
  for (const auto& op : server_operations())
    EXPECT_TRUE(spec.count(op)) << op.first << " " << op.second
                                << " is served but not in openapi/openapi.yaml";
}

TEST(OpenApi, EveryDescribedRouteIsInTheRouteTable) {
  const auto served = server_operations();
  for (const auto& op : spec_operations(spec_text()))
    EXPECT_TRUE(served.count(op)) << op.first << " " << op.second
                                  << " is in openapi/openapi.yaml but not in server::routes()";
}

// The parser above must see what a reader sees: a path added in the file shows up.
TEST(OpenApi, SpecParserFindsAddedOperations) {
  const auto ops = spec_operations(
      "openapi: 3.1.0\npaths:\n  /x/{id}:\n    parameters: []\n"
      "    get:\n      summary: a\n    delete:\n      summary: b\n"
      "components:\n  /not-a-path:\n    get:\n");
  EXPECT_EQ(ops, (std::set<Operation>{{"GET", "/x/{id}"}, {"DELETE", "/x/{id}"}}));
}

// A minimal, valid request for each described operation.
struct Call {
  std::vector<std::string> args;  // curl arguments besides the URL
  std::string target;             // path and query
};

Call call_for(const Operation& op, const fs::path& program, const fs::path& schema,
              const fs::path& profile_json, const fs::path& stylesheet) {
  const auto& [method, path] = op;
  const std::string auth = "Authorization: Bearer openapi-test-token-0123456789";
  if (path == "/v1/profiles/{id}") {
    if (method == "GET") return {{}, "/v1/profiles/linuxcnc"};
    if (method == "PUT")
      return {{"-X", "PUT", "-H", auth, "-F", "profile=<" + profile_json.string(), "-F",
               "stylesheet=<" + stylesheet.string()},
              "/v1/profiles/openapi-probe"};
    if (method == "DELETE") return {{"-X", "DELETE", "-H", auth}, "/v1/profiles/openapi-probe"};
  }
  if (method == "GET") return {{}, path};
  if (method == "POST") {
    static const std::map<std::string, std::string, std::less<>> query = {
        {"/v1/posts", "?profile=linuxcnc"},
        {"/v1/conversions", "?to=p28"},
        {"/v1/nc/parse", "?dialect=fanuc-0i"},
        {"/v1/nc/translate", "?from=fanuc-0i&to=linuxcnc"}};
    const auto q = query.find(path);
    const std::string body = path == "/v1/schemas"           ? schema.string()
                             : path.rfind("/v1/nc/", 0) == 0 ? std::string()
                                                             : program.string();
    std::vector<std::string> args = {"--data-binary",
                                     body.empty() ? "G21 G90\nG0 X0\nM30\n" : "@" + body};
    return {args, path + (q == query.end() ? "" : q->second)};
  }
  return {};
}

TEST(OpenApi, EveryDescribedRouteIsAnswered) {
  TempDir dir;
  fs::create_directories(dir.path() / "web");
  std::ofstream(dir.path() / "web" / "index.html") << "<!doctype html><title>ncpost</title>\n";
  auto json = read_file(source_dir() / "stylesheets/linuxcnc/profile.json");
  json.replace(json.find("\"id\": \"linuxcnc\""), 16, "\"id\": \"openapi-probe\"");
  std::ofstream(dir.path() / "profile.json") << json;
  ServerOptions options;
  options.args = {"--profiles", (dir.path() / "profiles").string(), "--web-root",
                  (dir.path() / "web").string()};
  options.env = {{"NCPOST_ADMIN_TOKEN", "openapi-test-token-0123456789"}};
  ServerProcess server(options);
  ASSERT_TRUE(server.started()) << server.log();

  const fs::path program = source_dir() / "tests/golden/trace/cases/curves.stp";
  const fs::path schema = source_dir() / "schemas/iso14649.exp";
  const fs::path stylesheet = source_dir() / "stylesheets/linuxcnc/post.xsl";
  // PUT before DELETE, so that the DELETE finds the profile the PUT made.
  const auto served = server_operations();
  std::vector<Operation> ops(served.begin(), served.end());
  for (const auto& op : spec_operations(spec_text()))
    if (!std::count(ops.begin(), ops.end(), op)) ops.push_back(op);
  std::stable_sort(ops.begin(), ops.end(), [](const Operation& a, const Operation& b) {
    return (a.first == "DELETE") < (b.first == "DELETE");
  });
  const auto described = spec_operations(spec_text());
  int called = 0;
  for (const auto& op : ops) {
    if (!described.count(op)) continue;  // reported by the tests above
    const Call c = call_for(op, program, schema, dir.path() / "profile.json", stylesheet);
    ASSERT_FALSE(c.target.empty()) << "openapi_test.cpp has no request for " << op.first << " "
                                   << op.second << "; add one to call_for()";
    auto args = c.args;
    args.push_back(server.url(c.target));
    const auto r = curl(args);
    ++called;
    EXPECT_NE(r.status, 0) << op.first << " " << c.target << ": no answer (curl " << r.exit_code
                           << ")";
    EXPECT_NE(r.status, 405) << op.first << " " << c.target << "\n" << r.body;
    EXPECT_FALSE(r.status == 404 && r.body.find("no route for") != std::string::npos)
        << op.first << " " << c.target << " is not routed\n"
        << r.body;
    // A valid minimal request gets a real answer.
    EXPECT_LT(r.status, 500)
        << op.first << " " << c.target << ": " << r.status << "\n"
        << r.body.substr(0, 2000);
  }
  EXPECT_GE(called, 16);
}

// The server serves the file this test reads.
TEST(OpenApi, ServedDescriptionIsTheFile) {
  ServerProcess server;
  ASSERT_TRUE(server.started()) << server.log();
  const auto r = curl({server.url("/openapi.yaml")});
  EXPECT_EQ(r.status, 200);
  EXPECT_EQ(r.body, spec_text());
  EXPECT_NE(r.header("Content-Type").find("yaml"), std::string::npos);
}

}  // namespace
}  // namespace ncpost::test
