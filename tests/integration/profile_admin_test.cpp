// Profiles over the API against the real ncpostd: reading is open, writing needs the bearer
// token (401 without, 403 with a wrong one, 409 on a read-only store), an invalid upload is
// refused with diagnostics while the old version keeps serving posts, a valid one is used by
// the next post (its version and ETag change), DELETE, reload on SIGHUP or change, and a
// server killed with SIGKILL while uploads are under way restarts with one complete version.

#include <gtest/gtest.h>
#include <sys/mount.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstring>
#include <fstream>
#include <random>
#include <regex>
#include <thread>

#include "corpus.hpp"
#include "server_helpers.hpp"
#include "server_process.hpp"

namespace ncpost::test {
namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;

constexpr const char* kToken = "profile-admin-test-token-0123456789";

std::string bearer(std::string_view token = kToken) {
  return "Authorization: Bearer " + std::string(token);
}

// The linuxcnc profile under another id; `edit` changes the JSON text.
std::string profile_json(const std::string& id, const std::string& name,
                         const std::string& line_ending = "lf") {
  std::string json = read_file(source_dir() / "stylesheets/linuxcnc/profile.json");
  json = std::regex_replace(json, std::regex(R"("id": "linuxcnc")"), "\"id\": \"" + id + "\"");
  json = std::regex_replace(json, std::regex(R"("name": "[^"]*")"), "\"name\": \"" + name + "\"");
  json = std::regex_replace(json, std::regex(R"("line_ending": "lf")"),
                            "\"line_ending\": \"" + line_ending + "\"");
  json = std::regex_replace(json, std::regex(R"("\$schema": "[^"]*",)"), "");
  return json;
}

std::string stylesheet() {
  return read_file(source_dir() / "stylesheets/linuxcnc/post.xsl");
}

fs::path write(const fs::path& file, const std::string& text) {
  std::ofstream(file, std::ios::binary | std::ios::trunc) << text;
  return file;
}

fs::path program() {
  return source_dir() / "tests/golden/trace/cases/curves.stp";
}

// A PUT of the two files, as multipart/form-data.
CurlResult put(const ServerProcess& server, const std::string& id, const fs::path& json,
               const fs::path& xsl, const std::string& auth = bearer()) {
  std::vector<std::string> args = {
      "-X", "PUT", "-F", "profile=<" + json.string(), "-F", "stylesheet=<" + xsl.string()};
  if (!auth.empty()) {
    args.push_back("-H");
    args.push_back(auth);
  }
  args.push_back(server.url("/v1/profiles/" + id));
  return curl(args);
}

CurlResult post(const ServerProcess& server, const std::string& id) {
  return curl({"--data-binary", "@" + program().string(), server.url("/v1/posts?profile=" + id)});
}

std::string unquote(std::string etag) {
  if (etag.size() >= 2 && etag.front() == '"' && etag.back() == '"')
    etag = etag.substr(1, etag.size() - 2);
  return etag;
}

ServerOptions options(std::vector<std::string> args,
                      std::vector<std::pair<std::string, std::string>> env = {}) {
  ServerOptions o;
  o.args = std::move(args);
  o.env = std::move(env);
  return o;
}

class ProfileAdmin : public ::testing::Test {
 protected:
  void SetUp() override {
    files_ = dir_.path() / "files";
    profiles_ = dir_.path() / "profiles";
    fs::create_directories(files_);
  }
  ServerOptions writable() const {
    return options({"--profiles", profiles_.string()}, {{"NCPOST_ADMIN_TOKEN", kToken}});
  }
  TempDir dir_;
  fs::path files_, profiles_;
};

TEST_F(ProfileAdmin, ReadingIsOpenWritingNeedsTheToken) {
  ServerProcess server(writable());
  ASSERT_TRUE(server.started()) << server.log();
  const auto list = curl({server.url("/v1/profiles")});
  EXPECT_EQ(list.status, 200);
  EXPECT_NE(list.body.find("\"linuxcnc\""), std::string::npos) << list.body;
  const auto one = curl({server.url("/v1/profiles/linuxcnc")});
  EXPECT_EQ(one.status, 200);
  EXPECT_FALSE(one.header("ETag").empty());

  const auto json = write(files_ / "profile.json", profile_json("shop-mill", "Shop mill"));
  const auto xsl = write(files_ / "post.xsl", stylesheet());
  const auto none = put(server, "shop-mill", json, xsl, "");
  EXPECT_EQ(none.status, 401) << none.body;
  EXPECT_NE(none.header("WWW-Authenticate").find("Bearer"), std::string::npos);
  EXPECT_NE(none.header("Content-Type").find("application/problem+json"), std::string::npos);
  const auto wrong = put(server, "shop-mill", json, xsl, bearer("not-the-token-0123456789"));
  EXPECT_EQ(wrong.status, 403) << wrong.body;
  const auto basic =
      put(server, "shop-mill", json, xsl, "Authorization: Basic " + std::string(kToken));
  EXPECT_EQ(basic.status, 403) << basic.body;
  const auto del = curl({"-X", "DELETE", "-H", bearer("wrong-token-0123456789"),
                         server.url("/v1/profiles/linuxcnc")});
  EXPECT_EQ(del.status, 403);
  EXPECT_EQ(curl({server.url("/v1/profiles/shop-mill")}).status, 404) << "nothing was created";
  EXPECT_EQ(server.log().find(kToken), std::string::npos) << "the token is never logged";
  EXPECT_EQ(curl({server.url("/healthz")}).status, 200);
}

TEST_F(ProfileAdmin, WithoutTokenOrDirectoryNothingIsWritable) {
  const auto json = write(files_ / "profile.json", profile_json("shop-mill", "Shop mill"));
  const auto xsl = write(files_ / "post.xsl", stylesheet());
  {
    // A writable directory but no token configured: every write is refused.
    ServerProcess server(options({"--profiles", profiles_.string()}));
    ASSERT_TRUE(server.started()) << server.log();
    EXPECT_EQ(put(server, "shop-mill", json, xsl).status, 403);
  }
  {
    // The built-ins only: read-only, whatever the token.
    ServerProcess server(options({}, {{"NCPOST_ADMIN_TOKEN", kToken}}));
    ASSERT_TRUE(server.started()) << server.log();
    const auto r = put(server, "shop-mill", json, xsl);
    EXPECT_EQ(r.status, 409) << r.body;
    EXPECT_NE(r.body.find("PROFILE-006"), std::string::npos) << r.body;
    EXPECT_EQ(curl({"-X", "DELETE", "-H", bearer(), server.url("/v1/profiles/linuxcnc")}).status,
              409);
  }
}

TEST_F(ProfileAdmin, UploadValidateActivateDelete) {
  ServerProcess server(writable());
  ASSERT_TRUE(server.started()) << server.log();
  const auto xsl = write(files_ / "post.xsl", stylesheet());

  // Created.
  const auto v1_json = write(files_ / "v1.json", profile_json("shop-mill", "Shop mill v1"));
  const auto created = put(server, "shop-mill", v1_json, xsl);
  ASSERT_EQ(created.status, 201) << created.body;
  EXPECT_EQ(created.header("Location"), "/v1/profiles/shop-mill");
  const std::string v1 = unquote(created.header("ETag"));
  EXPECT_EQ(v1.size(), 64u) << created.headers;
  const auto got = curl({server.url("/v1/profiles/shop-mill")});
  EXPECT_EQ(got.status, 200);
  EXPECT_EQ(unquote(got.header("ETag")), v1);
  EXPECT_NE(got.body.find("Shop mill v1"), std::string::npos);
  const auto first = post(server, "shop-mill");
  ASSERT_EQ(first.status, 200) << first.body;
  EXPECT_EQ(first.header("X-Ncpost-Profile-Version"), v1);
  EXPECT_EQ(first.body.find('\r'), std::string::npos);

  // Refused uploads: diagnostics, and the old version keeps serving.
  const auto not_json = write(files_ / "bad.json", "{\"id\": \"shop-mill\",");
  const auto r1 = put(server, "shop-mill", not_json, xsl);
  EXPECT_EQ(r1.status, 422) << r1.body;
  EXPECT_NE(r1.body.find("PROFILE-001"), std::string::npos) << r1.body;
  EXPECT_NE(r1.body.find("\"file\": \"profile.json\""), std::string::npos) << r1.body;
  const auto bad_xsl = write(files_ / "bad.xsl",
                             "<xsl:stylesheet version=\"1.0\" "
                             "xmlns:xsl=\"http://www.w3.org/1999/XSL/Transform\">\n"
                             "<xsl:template match=\"/\"><xsl:value-of select=\"((\"/>"
                             "</xsl:template>\n</xsl:stylesheet>\n");
  const auto r2 = put(server, "shop-mill", v1_json, bad_xsl);
  EXPECT_EQ(r2.status, 422) << r2.body;
  EXPECT_NE(r2.body.find("PROFILE-004"), std::string::npos) << r2.body;
  EXPECT_NE(r2.body.find("\"file\": \"post.xsl\""), std::string::npos) << r2.body;
  EXPECT_NE(r2.header("Content-Type").find("application/problem+json"), std::string::npos);
  const auto r3 =
      put(server, "shop-mill", write(files_ / "other.json", profile_json("other", "x")), xsl);
  EXPECT_EQ(r3.status, 422) << "the id in profile.json must be the path's\n" << r3.body;
  EXPECT_NE(r3.body.find("PROFILE-002"), std::string::npos) << r3.body;
  EXPECT_EQ(unquote(curl({server.url("/v1/profiles/shop-mill")}).header("ETag")), v1);
  const auto still = post(server, "shop-mill");
  EXPECT_EQ(still.status, 200);
  EXPECT_EQ(still.header("X-Ncpost-Profile-Version"), v1);
  EXPECT_EQ(still.body, first.body);

  // Replaced: the next post uses the new version (CRLF line endings), with a new ETag.
  const auto v2_json = write(files_ / "v2.json", profile_json("shop-mill", "Shop mill v2", "crlf"));
  const auto replaced = put(server, "shop-mill", v2_json, xsl);
  ASSERT_EQ(replaced.status, 200) << replaced.body;
  const std::string v2 = unquote(replaced.header("ETag"));
  EXPECT_NE(v2, v1);
  const auto second = post(server, "shop-mill");
  ASSERT_EQ(second.status, 200) << second.body;
  EXPECT_EQ(second.header("X-Ncpost-Profile-Version"), v2);
  EXPECT_NE(second.header("ETag"), first.header("ETag"));
  EXPECT_NE(second.body.find("\r\n"), std::string::npos);

  // Deleted.
  const auto deleted = curl({"-X", "DELETE", "-H", bearer(), server.url("/v1/profiles/shop-mill")});
  EXPECT_EQ(deleted.status, 204) << deleted.body;
  EXPECT_EQ(curl({server.url("/v1/profiles/shop-mill")}).status, 404);
  EXPECT_EQ(post(server, "shop-mill").status, 404);
  EXPECT_EQ(curl({"-X", "DELETE", "-H", bearer(), server.url("/v1/profiles/shop-mill")}).status,
            404);
  EXPECT_EQ(curl({"-X", "DELETE", "-H", bearer(), server.url("/v1/profiles/linuxcnc")}).status, 409)
      << "a built-in";
  EXPECT_EQ(curl({"-X", "PUT", "-H", bearer(), "-F", "profile=<" + v1_json.string(), "-F",
                  "stylesheet=<" + xsl.string(), server.url("/v1/profiles/..%2Fescape")})
                    .status /
                100,
            4);
  EXPECT_FALSE(fs::exists(dir_.path() / "escape"));
  EXPECT_EQ(curl({server.url("/healthz")}).status, 200);
}

// A post keeps the profile version it started with when the profile is replaced under it: a
// large program streamed to a client that does not read yet (its job is blocked on the full
// socket, so it is still running), then a new version with CRLF line endings; the stream goes
// on to its end with the old version's LF only, and the next post has CRLF.
// A PUT may carry the profile's dialect.json (a `dialect` part): checked against
// stylesheets/dialect.schema.json, and then G-code is read with the new profile's id.
TEST_F(ProfileAdmin, UploadedProfileCarriesItsDialect) {
  ServerProcess server(writable());
  ASSERT_TRUE(server.started()) << server.log();
  const auto json = write(files_ / "profile.json", profile_json("shop-mill", "Shop mill"));
  const auto xsl = write(files_ / "post.xsl", stylesheet());
  std::string dialect = read_file(source_dir() / "stylesheets/linuxcnc/dialect.json");
  dialect = std::regex_replace(dialect, std::regex(R"("id": "linuxcnc")"), R"("id": "shop-mill")");
  dialect = std::regex_replace(dialect, std::regex(R"("\$schema": "[^"]*",)"), "");
  const auto good = write(files_ / "dialect.json", dialect);
  const auto bad = write(files_ / "bad-dialect.json",
                         std::regex_replace(dialect, std::regex(R"("syntax": "word_address")"),
                                            R"("syntax": "no_such_syntax")"));
  const auto put_with = [&](const fs::path& d, std::vector<std::string> more = {}) {
    std::vector<std::string> args = {"-X", "PUT",
                                     "-F", "profile=<" + json.string(),
                                     "-F", "stylesheet=<" + xsl.string(),
                                     "-F", "dialect=<" + d.string(),
                                     "-H", bearer()};
    args.insert(args.end(), more.begin(), more.end());
    args.push_back(server.url("/v1/profiles/shop-mill"));
    return curl(args);
  };
  const std::string gcode = "@" + (source_dir() / "tests/cli/data/gcode/limits.nc").string();
  // Without a dialect, the profile cannot read G-code.
  ASSERT_EQ(put(server, "shop-mill", json, xsl).status, 201);
  const auto unread = curl({"--data-binary", gcode, server.url("/v1/nc/parse?dialect=shop-mill")});
  EXPECT_EQ(unread.status, 422) << unread.body;
  EXPECT_NE(unread.body.find("has no dialect.json"), std::string::npos) << unread.body;
  // A dialect that breaks the schema is refused, naming dialect.json; nothing changes.
  const auto refused = put_with(bad);
  EXPECT_EQ(refused.status, 422) << refused.body;
  EXPECT_NE(refused.body.find("GCODE-002"), std::string::npos) << refused.body;
  EXPECT_NE(refused.body.find("\"file\": \"dialect.json\""), std::string::npos) << refused.body;
  // Two dialect parts: 400.
  EXPECT_EQ(put_with(good, {"-F", "dialect=<" + good.string()}).status, 400);
  // With its dialect: G-code is read by the new profile's id.
  const auto stored = put_with(good);
  EXPECT_EQ(stored.status, 200) << stored.body;
  const auto read = curl({"--data-binary", gcode, server.url("/v1/nc/parse?dialect=shop-mill")});
  EXPECT_EQ(read.status, 200) << read.body;
  EXPECT_NE(read.body.find("STRAIGHT_FEED(900"), std::string::npos) << read.body;
  EXPECT_EQ(curl({server.url("/healthz")}).status, 200);
}

TEST_F(ProfileAdmin, ARunningPostKeepsTheVersionItStartedWith) {
  REQUIRE_LARGE_PROGRAM(large, 24);
  ServerProcess server(writable());
  ASSERT_TRUE(server.started()) << server.log();
  const auto xsl = write(files_ / "post.xsl", stylesheet());
  const auto created =
      put(server, "keep-mill", write(files_ / "v1.json", profile_json("keep-mill", "v1")), xsl);
  ASSERT_EQ(created.status, 201) << created.body;
  const std::string v1 = unquote(created.header("ETag"));

  const std::string body = read_file(large);
  RawConnection stream(server.port());
  ASSERT_TRUE(stream.send(post_head("/v1/posts?profile=keep-mill", body.size()) + body));
  std::string raw = stream.receive_until("\r\n\r\n", 60s);
  ASSERT_NE(raw.find("X-Ncpost-Profile-Version: " + v1), std::string::npos) << raw;

  const auto replaced = put(
      server, "keep-mill", write(files_ / "v2.json", profile_json("keep-mill", "v2", "crlf")), xsl);
  ASSERT_EQ(replaced.status, 200) << replaced.body;
  // The post was still running when the new version became active.
  EXPECT_NE(curl({server.url("/metrics")}).body.find("ncpost_jobs_active 1"), std::string::npos);

  while (!stream.closed() && !decode_chunked(raw).complete) raw += stream.receive(30s, 1 << 20);
  const RawResponse streamed = decode_chunked(raw);
  ASSERT_TRUE(streamed.complete) << streamed.body.size() << " bytes\n" << server.log();
  EXPECT_GT(streamed.body.size(), std::size_t{1} << 20);
  EXPECT_EQ(streamed.body.find('\r'), std::string::npos) << "a line of the new version";

  const auto next = post(server, "keep-mill");
  ASSERT_EQ(next.status, 200) << next.body;
  EXPECT_EQ(next.header("X-Ncpost-Profile-Version"), unquote(replaced.header("ETag")));
  EXPECT_NE(next.body.find("\r\n"), std::string::npos);
}

// An uploaded stylesheet gets the sandbox of the built-ins: imports from elsewhere are refused at
// upload, and reading (document()) or writing (exsl:document) files fails the post.
TEST_F(ProfileAdmin, UploadedStylesheetsAreSandboxed) {
  ServerProcess server(writable());
  ASSERT_TRUE(server.started()) << server.log();
  const auto json = write(files_ / "p.json", profile_json("sandbox", "Sandbox"));
  const std::string head =
      "<xsl:stylesheet version=\"1.0\" xmlns:xsl=\"http://www.w3.org/1999/XSL/Transform\" "
      "xmlns:exsl=\"http://exslt.org/common\" extension-element-prefixes=\"exsl\">\n";
  const auto import = put(server, "sandbox", json,
                          write(files_ / "import.xsl", head + "<xsl:import href=\"/etc/passwd\"/>\n"
                                                              "</xsl:stylesheet>\n"));
  EXPECT_EQ(import.status, 422) << import.body;
  EXPECT_NE(import.body.find("XSLT-004"), std::string::npos) << import.body;

  const auto reads =
      put(server, "sandbox", json,
          write(files_ / "read.xsl", head + "<xsl:template match=\"/\"><xsl:value-of "
                                            "select=\"document('/etc/passwd')\"/></xsl:template>\n"
                                            "</xsl:stylesheet>\n"));
  ASSERT_LT(reads.status, 300) << reads.body;
  const auto read_post = post(server, "sandbox");
  EXPECT_EQ(read_post.body.find("root:"), std::string::npos) << read_post.body;
  EXPECT_EQ(read_post.status, 422) << read_post.body;

  const fs::path target = dir_.path() / "written-by-a-stylesheet.txt";
  const auto writes =
      put(server, "sandbox", json,
          write(files_ / "write.xsl", head + "<xsl:output method=\"text\"/>\n" +
                                          "<xsl:template match=\"/\"><exsl:document href=\"" +
                                          target.string() +
                                          "\" method=\"text\">x</exsl:document></xsl:template>\n"
                                          "</xsl:stylesheet>\n"));
  ASSERT_LT(writes.status, 300) << writes.body;
  const auto write_post = post(server, "sandbox");
  EXPECT_FALSE(fs::exists(target));
  EXPECT_EQ(write_post.status, 422) << write_post.body;
  EXPECT_EQ(curl({server.url("/healthz")}).status, 200);
}

// Wait (bounded) until GET /v1/profiles/{id} reports a name.
bool eventually_named(const ServerProcess& server, const std::string& id, const std::string& name,
                      std::chrono::milliseconds timeout) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  do {
    if (curl({server.url("/v1/profiles/" + id)}).body.find(name) != std::string::npos) return true;
    std::this_thread::sleep_for(100ms);
  } while (std::chrono::steady_clock::now() < deadline);
  return false;
}

TEST_F(ProfileAdmin, DirectoryIsReloadedOnSighupAndOnChange) {
  // A profile placed by hand, as an operator would (with the built-in common templates).
  fs::create_directories(profiles_ / "hand");
  fs::create_directory_symlink(source_dir() / "stylesheets/common", profiles_ / "common");
  write(profiles_ / "hand" / "profile.json", profile_json("hand", "By hand one"));
  write(profiles_ / "hand" / "post.xsl", stylesheet());
  ServerProcess server(writable());
  ASSERT_TRUE(server.started()) << server.log();
  const auto one = curl({server.url("/v1/profiles/hand")});
  ASSERT_EQ(one.status, 200) << one.body;
  EXPECT_NE(one.body.find("By hand one"), std::string::npos);

  write(profiles_ / "hand" / "profile.json", profile_json("hand", "By hand two"));
  server.signal(SIGHUP);
  EXPECT_TRUE(eventually_named(server, "hand", "By hand two", 5s)) << server.log();

  // Without a signal the periodic check finds the change too.
  write(profiles_ / "hand" / "profile.json", profile_json("hand", "By hand three"));
  EXPECT_TRUE(eventually_named(server, "hand", "By hand three", 10s)) << server.log();
  const auto three = curl({server.url("/v1/profiles/hand")});
  EXPECT_NE(unquote(three.header("ETag")), unquote(one.header("ETag")));

  // A folder added by hand appears in the list.
  fs::create_directories(profiles_ / "added");
  write(profiles_ / "added" / "profile.json", profile_json("added", "Added by hand"));
  write(profiles_ / "added" / "post.xsl", stylesheet());
  EXPECT_NE(curl({server.url("/v1/profiles")}).body.find("Added by hand"), std::string::npos);
}

// ncpostd killed with SIGKILL while PUTs alternate two versions: after a restart the profile is
// one of the two, complete (it loads and posts).
TEST_F(ProfileAdmin, KillNineDuringUploadsLeavesOneCompleteVersion) {
  const auto xsl = write(files_ / "post.xsl", stylesheet());
  const fs::path json[2] = {write(files_ / "a.json", profile_json("crash", "Version A")),
                            write(files_ / "b.json", profile_json("crash", "Version B", "crlf"))};
  std::string versions[2];
  {
    ServerProcess server(writable());
    ASSERT_TRUE(server.started()) << server.log();
    for (int i : {0, 1}) {
      const auto r = put(server, "crash", json[i], xsl);
      ASSERT_LT(r.status, 300) << r.body;
      versions[i] = unquote(r.header("ETag"));
    }
  }
  std::mt19937 rng(7);
  std::uniform_int_distribution<int> delay_ms(20, 400);
  int puts_done = 0;
  for (int round = 0; round < 8; ++round) {
    ServerProcess server(writable());
    ASSERT_TRUE(server.started()) << server.log();
    const auto got = curl({server.url("/v1/profiles/crash")});
    ASSERT_EQ(got.status, 200) << "round " << round << ": " << got.body << server.log();
    const std::string version = unquote(got.header("ETag"));
    EXPECT_TRUE(version == versions[0] || version == versions[1]) << version;
    EXPECT_EQ(post(server, "crash").status, 200);

    std::atomic<bool> stop{false};
    std::thread writer([&] {
      for (int i = 0; !stop; ++i) {
        if (put(server, "crash", json[i % 2], xsl).status / 100 == 2) ++puts_done;
      }
    });
    std::this_thread::sleep_for(std::chrono::milliseconds(delay_ms(rng)));
    server.signal(SIGKILL);
    (void)server.wait(5s);
    stop = true;
    writer.join();
  }
  EXPECT_GT(puts_done, 0) << "the kills must interrupt a server that is writing";
  ServerProcess server(writable());
  ASSERT_TRUE(server.started()) << server.log();
  const auto last = curl({server.url("/v1/profiles/crash")});
  ASSERT_EQ(last.status, 200) << last.body;
  const std::string version = unquote(last.header("ETag"));
  EXPECT_TRUE(version == versions[0] || version == versions[1]) << version;
}

// ---- the fault matrix (docs/reliability.md): profiles ----------------------------------------

// The entries of a directory, by name.
std::vector<std::string> entries(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

// A tmpfs of `size` mounted on a folder, unmounted when the object goes away. Needs
// CAP_SYS_ADMIN (root in most containers); mounted() says whether it worked.
class SmallDisk {
 public:
  SmallDisk(fs::path where, const std::string& size) : where_(std::move(where)) {
    fs::create_directories(where_);
    if (::mount("tmpfs", where_.c_str(), "tmpfs", 0, ("size=" + size).c_str()) == 0)
      mounted_ = true;
    else
      why_ = std::strerror(errno);
  }
  SmallDisk(const SmallDisk&) = delete;
  SmallDisk& operator=(const SmallDisk&) = delete;
  ~SmallDisk() {
    if (mounted_) ::umount2(where_.c_str(), MNT_DETACH);
  }
  [[nodiscard]] bool mounted() const { return mounted_; }
  [[nodiscard]] const std::string& why() const { return why_; }
  // Writes a file until the disk is full; false when it never filled (not a small disk).
  bool fill(const fs::path& file) const {
    std::ofstream out(file, std::ios::binary);
    const std::string block(64 << 10, 'f');
    for (int i = 0; i < 1 << 14; ++i)
      if (!out.write(block.data(), static_cast<std::streamsize>(block.size())).flush()) return true;
    return false;
  }

 private:
  fs::path where_;
  bool mounted_ = false;
  std::string why_;
};

TEST_F(ProfileAdmin, DiskFullDuringAPutKeepsTheOldVersionAndWritesNothingHalf) {
  SmallDisk disk(profiles_, "1m");
  if (!disk.mounted())
    GTEST_SKIP() << "cannot mount a small tmpfs here (" << disk.why()
                 << "): the disk-full case needs CAP_SYS_ADMIN";
  const auto xsl = write(files_ / "post.xsl", stylesheet());
  const auto a = write(files_ / "a.json", profile_json("full", "Version A"));
  const auto b = write(files_ / "b.json", profile_json("full", "Version B"));
  ServerProcess server(writable());
  ASSERT_TRUE(server.started()) << server.log();
  const auto first = put(server, "full", a, xsl);
  ASSERT_EQ(first.status, 201) << first.body;
  const std::string version = unquote(first.header("ETag"));
  // Everything but the store's own files: the disk is full from here on.
  const fs::path filler = profiles_ / ".filler";
  ASSERT_TRUE(disk.fill(filler));
  const auto before = entries(profiles_);

  const auto refused = put(server, "full", b, xsl);
  EXPECT_EQ(refused.status, 500) << refused.body;
  EXPECT_EQ(refused.header("Content-Type"), "application/problem+json");
  EXPECT_NE(refused.body.find("PROFILE-007"), std::string::npos) << refused.body;
  EXPECT_NE(refused.body.find("No space left on device"), std::string::npos) << refused.body;
  EXPECT_EQ(refused.body.find(profiles_.string()), std::string::npos)
      << "the server's paths stay out of the answer: " << refused.body;
  // Nothing half-written: no new version folder, no temporary left behind.
  EXPECT_EQ(entries(profiles_), before);
  const auto still = curl({server.url("/v1/profiles/full")});
  EXPECT_EQ(still.status, 200);
  EXPECT_EQ(unquote(still.header("ETag")), version);
  EXPECT_NE(still.body.find("Version A"), std::string::npos);
  EXPECT_EQ(post(server, "full").status, 200);
  EXPECT_EQ(curl({server.url("/readyz")}).status, 200);

  // Space again: the same PUT goes through.
  fs::remove(filler);
  const auto again = put(server, "full", b, xsl);
  EXPECT_EQ(again.status, 200) << again.body;
  EXPECT_NE(curl({server.url("/v1/profiles/full")}).body.find("Version B"), std::string::npos);
}

// A one-worker server without a queue over the store.
ServerOptions one_worker(const fs::path& profiles, std::vector<std::string> more = {}) {
  std::vector<std::string> args = {"--profiles", profiles.string(), "--workers",
                                   "1",          "--queue",         "0"};
  args.insert(args.end(), more.begin(), more.end());
  return options(std::move(args), {{"NCPOST_ADMIN_TOKEN", kToken}});
}
// Stores profile `id` with the text stylesheet `templates`, posts the example with it and
// expects a problem+json of `status` and `code`; returns how long the post took.
Clock::duration post_expecting_problem(const ServerProcess& server, const fs::path& files,
                                       const std::string& id, const std::string& templates,
                                       int status, const std::string& code) {
  const auto stored = put(server, id, write(files / (id + ".json"), profile_json(id, id)),
                          write(files / (id + ".xsl"),
                                "<xsl:stylesheet version=\"1.0\" "
                                "xmlns:xsl=\"http://www.w3.org/1999/XSL/Transform\">\n"
                                "<xsl:output method=\"text\"/>\n" +
                                    templates + "</xsl:stylesheet>\n"));
  EXPECT_LT(stored.status, 300) << stored.body;
  const auto started = Clock::now();
  const auto r = post(server, id);
  const auto took = Clock::now() - started;
  EXPECT_EQ(r.status, status) << r.body;
  EXPECT_EQ(r.header("Content-Type"), "application/problem+json");
  EXPECT_NE(r.body.find(code), std::string::npos) << r.body;
  return took;
}

// A stylesheet that recurses without end: the depth limit stops it, the post is a 422 problem
// naming the limit, within seconds, and the worker serves the next post.
TEST_F(ProfileAdmin, ALoopingStylesheetIsABoundedProblem) {
  ServerProcess server(one_worker(profiles_));
  ASSERT_TRUE(server.started()) << server.log();
  const auto took = post_expecting_problem(
      server, files_, "loops",
      "<xsl:template match=\"/\"><xsl:call-template name=\"again\"/></xsl:template>\n"
      "<xsl:template name=\"again\"><xsl:param name=\"n\" select=\"0\"/>\n"
      "  <xsl:call-template name=\"again\"><xsl:with-param name=\"n\" select=\"$n + 1\"/>"
      "</xsl:call-template>\n</xsl:template>\n",
      422, "XSLT-020");
  EXPECT_LT(took, 10s);
  EXPECT_EQ(post(server, "linuxcnc").status, 200) << server.log();
}

// A job stuck in its stylesheet (a transform of 2^40 template calls) past --job-timeout: the
// client gets a 504 problem at the time limit, which also cancels the job; the transform polls
// the cancel flag, so the worker comes back at once (before 2026-11-27 only when the step
// limit, xslt::Limits::max_steps, ended it: 6.7 s on a loaded machine), and serves the next
// post. PostJobTest.CancelStopsAStylesheetThatRunsOnAndOn checks the stop itself.
TEST_F(ProfileAdmin, AJobStuckPastTheTimeLimitIs504AndItsWorkerComesBack) {
  ServerProcess server(one_worker(profiles_, {"--job-timeout", "0.3"}));
  ASSERT_TRUE(server.started()) << server.log();
  const auto started = Clock::now();
  const auto took = post_expecting_problem(
      server, files_, "busy",
      "<xsl:template match=\"/\"><xsl:call-template name=\"busy\"/></xsl:template>\n"
      "<xsl:template name=\"busy\"><xsl:param name=\"d\" select=\"40\"/>\n"
      "  <xsl:if test=\"$d &gt; 0\">\n"
      "    <xsl:call-template name=\"busy\"><xsl:with-param name=\"d\" select=\"$d - 1\"/>"
      "</xsl:call-template>\n"
      "    <xsl:call-template name=\"busy\"><xsl:with-param name=\"d\" select=\"$d - 1\"/>"
      "</xsl:call-template>\n  </xsl:if>\n</xsl:template>\n",
      504, "HTTP-005");
  EXPECT_LT(took, 5s);
  // One worker, no queue: a 503 while the stuck job holds it, a 200 once it let go.
  const auto deadline = Clock::now() + 30s;
  CurlResult next;
  do {
    next = post(server, "linuxcnc");
    if (next.status == 200) break;
    EXPECT_EQ(next.status, 503) << next.body;
    std::this_thread::sleep_for(100ms);
  } while (Clock::now() < deadline);
  EXPECT_EQ(next.status, 200) << server.log();
  RecordProperty(
      "worker_back_after_ms",
      std::to_string(
          std::chrono::duration_cast<std::chrono::milliseconds>(Clock::now() - started).count()));
}

}  // namespace
}  // namespace ncpost::test
