// ProfileStore administration: put() validates before it activates, remove(), the overlay on
// the built-ins, reload() after a change, the cache counters, and the crash test: a writer
// killed with SIGKILL at random moments leaves the old or the new version, never a broken one.

#include <gtest/gtest.h>
#include <poll.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <mutex>
#include <random>
#include <thread>

#include "ncpost/profile/profile.hpp"
#include "sha256.hpp"
#include "store_fixture.hpp"

namespace ncpost::profile {
namespace {

namespace fs = std::filesystem;
using test_store::profile_json;
using test_store::stylesheet;

std::string all(const std::vector<diag::FileDiagnostic>& d) {
  std::string out;
  for (const auto& x : d) out += diag::format(x) + "\n";
  return out;
}

bool has_code(const std::vector<diag::FileDiagnostic>& d, diag::Code code) {
  return std::any_of(d.begin(), d.end(), [&](const auto& x) { return x.diagnostic.code == code; });
}

// Names in the directory other than profiles and common/: version folders and leftovers.
std::vector<std::string> hidden_entries(const fs::path& dir) {
  std::vector<std::string> out;
  for (const auto& e : fs::directory_iterator(dir)) {
    const auto n = e.path().filename().string();
    if (!n.empty() && n[0] == '.') out.push_back(n);
  }
  std::sort(out.begin(), out.end());
  return out;
}

class StoreTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { xslt::initialise(); }
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("ncpost-store-" + std::to_string(::getpid()) + "-" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  ProfileStore writable() const {
    return ProfileStore(dir_, StoreOptions{.writable = true, .fallback = builtin_directory()});
  }
  fs::path dir_;
};

TEST(Sha256, KnownVectors) {
  EXPECT_EQ(detail::sha256_hex(""),
            "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
  EXPECT_EQ(detail::sha256_hex("abc"),
            "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  EXPECT_EQ(detail::sha256_hex("abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq"),
            "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1");
  detail::Sha256 h;  // fed in pieces across block boundaries
  for (int i = 0; i < 1000; ++i) h.update(std::string(1000, 'a'));
  EXPECT_EQ(h.hex(), "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0");
}

// A version names the folder a profile is stored in and goes into every post's ETag: the digest
// library must not change it. The profile is written here, so that edits to the built-in
// profiles do not move the pinned value (computed with the hand-written SHA-256 it replaced).
TEST_F(StoreTest, VersionOfAFixedProfileIsPinned) {
  const std::string json = R"({
  "id": "pinned", "name": "Pinned", "controller": "linuxcnc",
  "output": {"extension": ".ngc", "mime_type": "text/plain", "line_ending": "lf"},
  "block_numbers": {"start": 10, "increment": 10, "maximum": 99999, "wrap": true},
  "formats": {
    "length": {"decimals": 4, "decimal_point": true, "leading_zero": true, "trailing_zeros": false},
    "angle": {"decimals": 3, "decimal_point": true, "leading_zero": true, "trailing_zeros": false},
    "feed": {"decimals": 1, "decimal_point": true, "leading_zero": true, "trailing_zeros": false},
    "speed": {"decimals": 0, "decimal_point": false, "leading_zero": true, "trailing_zeros": false},
    "dwell": {"decimals": 3, "decimal_point": true, "leading_zero": true, "trailing_zeros": false}
  },
  "units": "mm",
  "capabilities": {"arcs": "ijk", "helical": false, "canned_cycles": "expand", "nurbs": "linearize"}
}
)";
  const std::string xsl =
      "<xsl:stylesheet version=\"1.0\" xmlns:xsl=\"http://www.w3.org/1999/XSL/Transform\">\n"
      "<xsl:output method=\"text\"/>\n<xsl:template match=\"/\">%</xsl:template>\n"
      "</xsl:stylesheet>\n";
  auto store = writable();
  const auto put = store.put("pinned", json, xsl);
  ASSERT_TRUE(put.profile) << all(put.diagnostics);
  EXPECT_EQ(put.profile->version,
            "3731b4181a81e77e90360a1fa32d9af40d49d306c2aa6790494fa5b93f9bc2f2");
}

TEST_F(StoreTest, PutCreatesThenReplacesAndKeepsRunningVersions) {
  auto store = writable();
  EXPECT_TRUE(store.writable());
  auto first = store.put("mill-a", profile_json("mill-a", "Mill A"), stylesheet("1"));
  ASSERT_TRUE(first.profile) << all(first.diagnostics);
  EXPECT_TRUE(first.created);
  EXPECT_EQ(first.profile->version.size(), 64u);
  EXPECT_FALSE(first.profile->read_only);
  EXPECT_EQ(first.profile->profile.name, "Mill A");
  EXPECT_TRUE(fs::is_symlink(dir_ / "mill-a"));

  std::vector<diag::FileDiagnostic> d;
  EXPECT_EQ(store.load("mill-a", d).get(), first.profile.get()) << "put() fills the cache";

  auto second = store.put("mill-a", profile_json("mill-a", "Mill A v2"), stylesheet("2"));
  ASSERT_TRUE(second.profile) << all(second.diagnostics);
  EXPECT_FALSE(second.created);
  EXPECT_NE(second.profile->version, first.profile->version);
  EXPECT_EQ(store.load("mill-a", d)->profile.name, "Mill A v2");
  // A job that started with the first version keeps it, compiled, after its files are gone.
  EXPECT_EQ(first.profile->profile.name, "Mill A");
  EXPECT_TRUE(first.profile->stylesheet);
  EXPECT_FALSE(fs::exists(first.profile->directory));
  // One version folder per profile: the old one was collected.
  EXPECT_EQ(hidden_entries(dir_).size(), 1u) << testing::PrintToString(hidden_entries(dir_));

  // The same content again is the same version.
  auto again = store.put("mill-a", profile_json("mill-a", "Mill A v2"), stylesheet("2"));
  ASSERT_TRUE(again.profile);
  EXPECT_EQ(again.profile->version, second.profile->version);

  // A fresh store reads what was stored, with the same version.
  ProfileStore fresh(dir_);
  auto reread = fresh.load("mill-a", d);
  ASSERT_TRUE(reread) << all(d);
  EXPECT_EQ(reread->version, second.profile->version);
  EXPECT_TRUE(reread->read_only) << "a store opened without writable";
}

TEST_F(StoreTest, InvalidUploadsChangeNothing) {
  auto store = writable();
  auto good = store.put("mill-b", profile_json("mill-b", "Good"), stylesheet("good"));
  ASSERT_TRUE(good.profile) << all(good.diagnostics);
  const auto before = hidden_entries(dir_);

  auto not_json = store.put("mill-b", "{\"id\": ", stylesheet("x"));
  EXPECT_FALSE(not_json.profile);
  EXPECT_TRUE(has_code(not_json.diagnostics, diag::Code::ProfileJson)) << all(not_json.diagnostics);
  EXPECT_EQ(not_json.diagnostics.front().file, "profile.json");

  auto bad_schema = profile_json("mill-b", "Bad");
  bad_schema.replace(bad_schema.find("\"units\": \"mm\""), 13, "\"units\": \"cubits\"");
  auto invalid = store.put("mill-b", bad_schema, stylesheet("x"));
  EXPECT_FALSE(invalid.profile);
  EXPECT_TRUE(has_code(invalid.diagnostics, diag::Code::ProfileInvalid))
      << all(invalid.diagnostics);

  auto other_id = store.put("mill-b", profile_json("mill-c", "Other"), stylesheet("x"));
  EXPECT_FALSE(other_id.profile);
  EXPECT_TRUE(has_code(other_id.diagnostics, diag::Code::ProfileInvalid));

  auto broken = store.put("mill-b", profile_json("mill-b", "Broken"),
                          "<xsl:stylesheet version='1.0' xmlns:xsl='http://www.w3.org/1999/XSL/"
                          "Transform'><xsl:template match='/'><xsl:value-of select='(('/>"
                          "</xsl:template></xsl:stylesheet>");
  EXPECT_FALSE(broken.profile);
  ASSERT_TRUE(has_code(broken.diagnostics, diag::Code::ProfileStylesheet))
      << all(broken.diagnostics);
  // The client's name for the file, not the server's path.
  EXPECT_EQ(broken.diagnostics.front().file, "post.xsl") << all(broken.diagnostics);

  // The same security as a built-in: imports from elsewhere are refused.
  auto escaping = store.put("mill-b", profile_json("mill-b", "Escaping"),
                            "<xsl:stylesheet version='1.0' xmlns:xsl='http://www.w3.org/1999/XSL/"
                            "Transform'><xsl:import href='/etc/passwd'/></xsl:stylesheet>");
  EXPECT_FALSE(escaping.profile);
  EXPECT_TRUE(has_code(escaping.diagnostics, diag::Code::XsltImportRefused))
      << all(escaping.diagnostics);

  std::vector<diag::FileDiagnostic> d;
  auto still = store.load("mill-b", d);
  ASSERT_TRUE(still);
  EXPECT_EQ(still->version, good.profile->version);
  EXPECT_EQ(hidden_entries(dir_), before) << "no leftovers from rejected uploads";
  ProfileStore fresh(dir_);
  EXPECT_EQ(fresh.load("mill-b", d)->version, good.profile->version);
}

TEST_F(StoreTest, IdsAreCheckedBeforeTheFileSystem) {
  auto store = writable();
  for (const char* id : {"../evil", "a/b", ".hidden", "", "UPPER", "a@b", "a~b"}) {
    auto r = store.put(id, profile_json("x", "x"), stylesheet("x"));
    EXPECT_FALSE(r.profile) << id;
    EXPECT_TRUE(has_code(r.diagnostics, diag::Code::ProfileBadId)) << id;
    EXPECT_EQ(store.remove(id), RemoveOutcome::NotFound) << id;
  }
  EXPECT_FALSE(fs::exists(dir_.parent_path() / "evil"));
  EXPECT_FALSE(fs::exists(dir_)) << "nothing was written";
}

TEST_F(StoreTest, ReadOnlyStoreRefusesWrites) {
  ProfileStore store;  // the built-ins
  EXPECT_FALSE(store.writable());
  auto r = store.put("linuxcnc", profile_json("linuxcnc", "x"), stylesheet("x"));
  EXPECT_FALSE(r.profile);
  EXPECT_TRUE(has_code(r.diagnostics, diag::Code::ProfileReadOnly));
  EXPECT_EQ(store.remove("linuxcnc"), RemoveOutcome::ReadOnly);
  EXPECT_EQ(store.remove("no-such"), RemoveOutcome::NotFound);
  std::vector<diag::FileDiagnostic> d;
  auto p = store.load("linuxcnc", d);
  ASSERT_TRUE(p);
  EXPECT_TRUE(p->read_only);
}

TEST_F(StoreTest, OverlayOnTheBuiltIns) {
  auto store = writable();
  std::vector<diag::FileDiagnostic> d;
  auto builtin = store.load("linuxcnc", d);
  ASSERT_TRUE(builtin) << all(d);
  EXPECT_TRUE(builtin->read_only);
  EXPECT_EQ(store.remove("linuxcnc"), RemoveOutcome::ReadOnly);

  // An upload with a built-in's id overrides it (200, not 201) ...
  auto over = store.put("linuxcnc", profile_json("linuxcnc", "Shop LinuxCNC"), stylesheet("o"));
  ASSERT_TRUE(over.profile) << all(over.diagnostics);
  EXPECT_FALSE(over.created);
  auto list = store.list(d);
  const auto row =
      std::find_if(list.begin(), list.end(), [](auto& s) { return s.id == "linuxcnc"; });
  ASSERT_NE(row, list.end());
  EXPECT_EQ(row->name, "Shop LinuxCNC");
  EXPECT_FALSE(row->read_only);
  EXPECT_EQ(std::count_if(list.begin(), list.end(), [](auto& s) { return s.id == "linuxcnc"; }), 1);
  EXPECT_TRUE(std::any_of(list.begin(), list.end(),
                          [](auto& s) { return s.id == "fanuc-0i" && s.read_only; }));

  // ... and deleting the upload shows the built-in again.
  EXPECT_EQ(store.remove("linuxcnc"), RemoveOutcome::Removed);
  auto back = store.load("linuxcnc", d);
  ASSERT_TRUE(back);
  EXPECT_TRUE(back->read_only);
  EXPECT_EQ(back->version, builtin->version);
}

// A profile may carry dialect.json (issue 19): stored with the version, loaded with it, checked
// by engine/gcode before anything is written.
TEST_F(StoreTest, DialectIsStoredWithTheVersion) {
  auto store = writable();
  std::vector<diag::FileDiagnostic> d;
  auto with = store.put("mill-d", profile_json("mill-d", "Mill D"), stylesheet("d"),
                        test_store::dialect_json("mill-d"));
  ASSERT_TRUE(with.profile) << all(with.diagnostics);
  ASSERT_TRUE(with.profile->dialect_json);
  EXPECT_NE(with.profile->dialect_json->find("\"mill-d\""), std::string::npos);
  EXPECT_TRUE(fs::exists(dir_ / "mill-d" / "dialect.json"));
  // A fresh store reads it back, same version.
  ProfileStore fresh(dir_, StoreOptions{.writable = true, .fallback = builtin_directory()});
  const auto reread = fresh.load("mill-d", d);
  ASSERT_TRUE(reread);
  EXPECT_EQ(reread->dialect_json, with.profile->dialect_json);
  EXPECT_EQ(reread->version, with.profile->version);

  // The dialect is part of the version.
  auto without = store.put("mill-d", profile_json("mill-d", "Mill D"), stylesheet("d"));
  ASSERT_TRUE(without.profile) << all(without.diagnostics);
  EXPECT_FALSE(without.profile->dialect_json);
  EXPECT_NE(without.profile->version, with.profile->version);

  // A dialect that does not load, or names another profile, is refused and nothing changes.
  auto broken = store.put("mill-d", profile_json("mill-d", "Mill D"), stylesheet("x"),
                          std::string_view("{\"id\": \"mill-d\"}"));
  EXPECT_FALSE(broken.profile);
  ASSERT_FALSE(broken.diagnostics.empty());
  EXPECT_EQ(broken.diagnostics[0].file, "dialect.json");
  EXPECT_TRUE(has_code(broken.diagnostics, diag::Code::GcodeDialectInvalid));
  auto other = store.put("mill-d", profile_json("mill-d", "Mill D"), stylesheet("x"),
                         test_store::dialect_json("mill-e"));
  EXPECT_FALSE(other.profile);
  EXPECT_TRUE(has_code(other.diagnostics, diag::Code::GcodeDialectInvalid));
  EXPECT_EQ(store.load("mill-d", d)->version, without.profile->version);

  // The built-in G-code profiles carry theirs.
  ProfileStore builtins(builtin_directory());
  const auto linuxcnc = builtins.load("linuxcnc", d);
  ASSERT_TRUE(linuxcnc);
  EXPECT_TRUE(linuxcnc->dialect_json);
}

TEST_F(StoreTest, RemoveThenNotFound) {
  auto store = writable();
  ASSERT_TRUE(store.put("gone", profile_json("gone", "Gone"), stylesheet("g")).profile);
  EXPECT_EQ(store.remove("gone"), RemoveOutcome::Removed);
  std::vector<diag::FileDiagnostic> d;
  EXPECT_FALSE(store.load("gone", d));
  EXPECT_TRUE(has_code(d, diag::Code::ProfileUnknown));
  EXPECT_EQ(store.remove("gone"), RemoveOutcome::NotFound);
  EXPECT_TRUE(hidden_entries(dir_).empty()) << testing::PrintToString(hidden_entries(dir_));
}

TEST_F(StoreTest, HandPlacedFolderIsReplacedAtomically) {
  fs::create_directories(dir_ / "hand");
  std::ofstream(dir_ / "hand" / "profile.json") << profile_json("hand", "By hand");
  fs::copy_file(builtin_directory() / "linuxcnc" / "post.xsl", dir_ / "hand" / "post.xsl");
  fs::create_directory_symlink(fs::absolute(builtin_directory() / "common"), dir_ / "common");
  auto store = writable();
  std::vector<diag::FileDiagnostic> d;
  auto by_hand = store.load("hand", d);
  ASSERT_TRUE(by_hand) << all(d);
  auto r = store.put("hand", profile_json("hand", "Uploaded"), stylesheet("u"));
  ASSERT_TRUE(r.profile) << all(r.diagnostics);
  EXPECT_FALSE(r.created);
  EXPECT_TRUE(fs::is_symlink(dir_ / "hand"));
  EXPECT_EQ(hidden_entries(dir_).size(), 1u) << "the old folder was removed";
  EXPECT_EQ(store.remove("hand"), RemoveOutcome::Removed);
}

// Issue 23 (2): the store replaces only profiles. The shared templates, other files and folders
// holding anything else are the operator's: refused with PROFILE-009, and left as they were.
TEST_F(StoreTest, ReservedAndForeignEntriesAreNeverReplaced) {
  fs::create_directories(dir_ / "keepme");
  std::ofstream(dir_ / "keepme" / "notes.txt") << "an operator's notes\n";
  fs::create_directories(dir_ / "empty");
  std::ofstream(dir_ / "schema") << "a file, not a profile\n";
  fs::create_directory_symlink(fs::absolute(builtin_directory() / "linuxcnc"), dir_ / "elsewhere");
  auto store = writable();
  for (const char* id : {"common", "keepme", "empty", "schema", "elsewhere"}) {
    auto r = store.put(id, profile_json(id, "Takeover"), stylesheet("t"));
    EXPECT_FALSE(r.profile) << id;
    EXPECT_TRUE(has_code(r.diagnostics, diag::Code::ProfileReserved)) << id << all(r.diagnostics);
  }
  EXPECT_EQ(store.remove("keepme"), RemoveOutcome::NotFound) << "no profile there to delete";
  EXPECT_EQ(store.remove("elsewhere"), RemoveOutcome::Foreign);
  EXPECT_TRUE(fs::exists(dir_ / "keepme" / "notes.txt"));
  EXPECT_TRUE(fs::is_regular_file(dir_ / "schema"));
  EXPECT_TRUE(fs::is_symlink(dir_ / "elsewhere"));
  EXPECT_TRUE(hidden_entries(dir_).empty()) << testing::PrintToString(hidden_entries(dir_));
  // What the store made itself it still replaces and removes.
  ASSERT_TRUE(store.put("mine", profile_json("mine", "Mine"), stylesheet("1")).profile);
  ASSERT_TRUE(store.put("mine", profile_json("mine", "Mine 2"), stylesheet("2")).profile);
  EXPECT_EQ(store.remove("mine"), RemoveOutcome::Removed);
}

TEST_F(StoreTest, ReloadPicksUpChangesOthersMade) {
  auto writer = writable();
  ASSERT_TRUE(writer.put("shared", profile_json("shared", "One"), stylesheet("1")).profile);
  ProfileStore reader(dir_, StoreOptions{.writable = false, .fallback = builtin_directory()});
  std::vector<diag::FileDiagnostic> d;
  auto one = reader.load("shared", d);
  ASSERT_TRUE(one) << all(d);
  EXPECT_EQ(reader.cache_stats().misses, 1u);
  EXPECT_EQ(reader.load("shared", d).get(), one.get());
  EXPECT_EQ(reader.cache_stats().hits, 1u);
  EXPECT_FALSE(reader.changed_since_last_scan());

  ASSERT_TRUE(writer.put("shared", profile_json("shared", "Two"), stylesheet("2")).profile);
  EXPECT_TRUE(reader.changed_since_last_scan());
  EXPECT_EQ(reader.load("shared", d)->profile.name, "One") << "cached until reload()";
  reader.reload();
  EXPECT_FALSE(reader.changed_since_last_scan());
  auto two = reader.load("shared", d);
  ASSERT_TRUE(two) << all(d);
  EXPECT_EQ(two->profile.name, "Two");
  EXPECT_EQ(reader.cache_stats().misses, 2u);
  EXPECT_EQ(one->profile.name, "One") << "the running job's version is unchanged";

  // An edit in place of a plain folder's file is seen too.
  fs::create_directories(dir_ / "plain");
  std::ofstream(dir_ / "plain" / "profile.json") << profile_json("plain", "Plain 1");
  fs::copy_file(builtin_directory() / "linuxcnc" / "post.xsl", dir_ / "plain" / "post.xsl");
  EXPECT_TRUE(reader.changed_since_last_scan()) << "a new folder";
  reader.reload();
  ASSERT_TRUE(reader.load("plain", d)) << all(d);
  std::this_thread::sleep_for(std::chrono::milliseconds(20));
  std::ofstream(dir_ / "plain" / "profile.json", std::ios::trunc)
      << profile_json("plain", "Plain 2");
  EXPECT_TRUE(reader.changed_since_last_scan());
  reader.reload();
  EXPECT_EQ(reader.load("plain", d)->profile.name, "Plain 2");
}

// Readers that load and reload while another thread replaces the profile never see an error:
// a load that races with the removal of the old version's folder reads the new one.
TEST_F(StoreTest, LoadsDuringPutsNeverFail) {
  auto store = writable();
  const std::string json[2] = {profile_json("busy", "A"), profile_json("busy", "B")};
  const std::string xsl[2] = {stylesheet("A"), stylesheet("B")};
  ASSERT_TRUE(store.put("busy", json[0], xsl[0]).profile);
  ProfileStore reader(dir_, StoreOptions{.writable = false, .fallback = builtin_directory()});
  std::atomic<bool> stop{false};
  std::atomic<int> failures{0}, loads{0};
  std::mutex first_mutex;
  std::string first;  // what the first failure said
  std::vector<std::thread> readers;
  for (int t = 0; t < 2; ++t) {
    readers.emplace_back([&] {
      while (!stop) {
        reader.reload();
        std::vector<diag::FileDiagnostic> d;
        const auto p = reader.load("busy", d);
        if (!p || (p->profile.name != "A" && p->profile.name != "B")) {
          if (failures++ == 0) {
            std::lock_guard lock(first_mutex);
            first = p ? "name " + p->profile.name : all(d);
          }
        }
        ++loads;
      }
    });
  }
  for (int i = 1; i <= 12; ++i) ASSERT_TRUE(store.put("busy", json[i % 2], xsl[i % 2]).profile);
  stop = true;
  for (auto& t : readers) t.join();
  EXPECT_EQ(failures.load(), 0) << "of " << loads.load() << " loads; the first:\n" << first;
  EXPECT_GT(loads.load(), 2);
}

// kill -9 of a writer at random moments (seeded) leaves the old or the new version.
TEST_F(StoreTest, CrashAtAnyMomentLeavesOneCompleteVersion) {
  auto store = writable();
  const auto a = store.put("crash", profile_json("crash", "Version A"), stylesheet("A"));
  const auto b = store.put("crash", profile_json("crash", "Version B"), stylesheet("B"));
  ASSERT_TRUE(a.profile && b.profile) << all(a.diagnostics) << all(b.diagnostics);
  const std::string version_a = a.profile->version, version_b = b.profile->version;

  std::mt19937 rng(20261122);
  std::uniform_int_distribution<int> delay_us(2'000, 60'000);
  int changes = 0;
  std::string last = version_b;
  for (int kill = 0; kill < 50; ++kill) {
    int ready[2];
    ASSERT_EQ(::pipe(ready), 0);
    const pid_t pid = ::fork();
    ASSERT_GE(pid, 0);
    if (pid == 0) {
      ::dup2(ready[1], STDOUT_FILENO);
      ::execl(NCPOST_STORE_WRITER, NCPOST_STORE_WRITER, dir_.c_str(), static_cast<char*>(nullptr));
      ::_exit(127);
    }
    ::close(ready[1]);
    // The delays count from the writer's first write, not from its start.
    pollfd wait_ready{ready[0], POLLIN, 0};
    char byte = 0;
    const bool started = ::poll(&wait_ready, 1, 30'000) == 1 && ::read(ready[0], &byte, 1) == 1;
    ::close(ready[0]);
    if (started) std::this_thread::sleep_for(std::chrono::microseconds(delay_us(rng)));
    ::kill(pid, SIGKILL);
    int status = 0;
    ::waitpid(pid, &status, 0);
    ASSERT_TRUE(WIFSIGNALED(status)) << "the writer stopped by itself (status " << status
                                     << "); run it by hand: " << NCPOST_STORE_WRITER << " DIR";

    ProfileStore fresh(dir_, StoreOptions{.writable = true, .fallback = builtin_directory()});
    std::vector<diag::FileDiagnostic> d;
    const auto loaded = fresh.load("crash", d);
    ASSERT_TRUE(loaded) << "after kill " << kill << ":\n" << all(d);
    ASSERT_TRUE(loaded->version == version_a || loaded->version == version_b)
        << "after kill " << kill << ": a version that is neither A nor B";
    EXPECT_EQ(loaded->profile.name, loaded->version == version_a ? "Version A" : "Version B");
    const auto list = fresh.list(d);
    EXPECT_EQ(std::count_if(list.begin(), list.end(), [](auto& s) { return s.id == "crash"; }), 1);
    if (loaded->version != last) ++changes;
    last = loaded->version;
  }
  RecordProperty("version_changes", changes);
  // The kills must have hit a writer that was writing, or the test proves nothing.
  EXPECT_GT(changes, 5);
  // Leftovers never break the next write, and the next write removes them.
  auto after = store.put("crash", profile_json("crash", "Version C"), stylesheet("C"));
  ASSERT_TRUE(after.profile) << all(after.diagnostics);
  EXPECT_EQ(hidden_entries(dir_).size(), 1u) << testing::PrintToString(hidden_entries(dir_));
}

}  // namespace
}  // namespace ncpost::profile
