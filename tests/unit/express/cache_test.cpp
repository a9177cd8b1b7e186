// SchemaCache: one parse per schema per process, shared safely between threads, refreshed when
// the file changes, bounded in size.

#include <gtest/gtest.h>

#include <atomic>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include "ncpost/express/schema_cache.hpp"

namespace ncpost::express {
namespace {

namespace fs = std::filesystem;

std::string schema_with(std::string_view entity) {
  return "SCHEMA s; ENTITY " + std::string(entity) + "; a : INTEGER; END_ENTITY; END_SCHEMA;";
}

class express_cache : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("ncpost_express_cache_" +
            std::to_string(::testing::UnitTest::GetInstance()->random_seed()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path write(std::string_view name, const std::string& text) {
    const fs::path path = dir_ / name;
    std::ofstream(path, std::ios::binary) << text;
    return path;
  }
  fs::path dir_;
};

TEST_F(express_cache, SameFileIsParsedOnce) {
  SchemaCache cache;
  const fs::path path = write("a.exp", schema_with("first"));
  const auto one = cache.load_file(path);
  const auto two = cache.load_file(dir_ / "." / "a.exp");  // same file, other spelling
  EXPECT_EQ(one.get(), two.get());
  EXPECT_EQ(cache.parse_count(), 1u);
  ASSERT_TRUE(one->ok());
  EXPECT_NE(one->schemas.find_entity("first"), nullptr);
}

TEST_F(express_cache, ConcurrentRequestsShareOneParse) {
  SchemaCache cache;
  const fs::path path = write("shared.exp", schema_with("shared"));
  const std::string text = schema_with("from_text");
  constexpr int kThreads = 8;
  std::vector<const ParseResult*> from_file(kThreads, nullptr);
  std::vector<const ParseResult*> from_text(kThreads, nullptr);
  std::atomic<int> ready{0};
  std::vector<std::thread> threads;
  for (int i = 0; i < kThreads; ++i) {
    threads.emplace_back([&, i] {
      ++ready;
      while (ready.load() < kThreads) std::this_thread::yield();  // start together
      // The shared_ptrs keep the results alive in the cache; raw pointers suffice to compare.
      from_file[static_cast<std::size_t>(i)] = cache.load_file(path).get();
      from_text[static_cast<std::size_t>(i)] = cache.load_text(text).get();
    });
  }
  for (auto& t : threads) t.join();
  for (int i = 1; i < kThreads; ++i) {
    EXPECT_EQ(from_file[static_cast<std::size_t>(i)], from_file[0]);
    EXPECT_EQ(from_text[static_cast<std::size_t>(i)], from_text[0]);
  }
  EXPECT_EQ(cache.parse_count(), 2u);
  EXPECT_NE(from_text[0]->schemas.find_entity("from_text"), nullptr);
}

TEST_F(express_cache, ChangedFileIsParsedAgain) {
  SchemaCache cache;
  const fs::path path = write("changing.exp", schema_with("before"));
  const auto before = cache.load_file(path);
  write("changing.exp", schema_with("after_the_edit"));
  fs::last_write_time(path, fs::last_write_time(path) + std::chrono::seconds(2));
  const auto after = cache.load_file(path);
  EXPECT_NE(before.get(), after.get());
  EXPECT_NE(after->schemas.find_entity("after_the_edit"), nullptr);
  EXPECT_NE(before->schemas.find_entity("before"), nullptr) << "old result stays valid";
  EXPECT_EQ(cache.size(), 1u);
}

TEST_F(express_cache, MissingFileGivesAnIoDiagnosticAndIsNotCached) {
  SchemaCache cache;
  const auto result = cache.load_file(dir_ / "missing.exp");
  ASSERT_EQ(result->diagnostics.size(), 1u);
  EXPECT_EQ(result->diagnostics[0].code_id(), "IO-001");
  EXPECT_FALSE(result->ok());
  EXPECT_EQ(cache.size(), 0u);
}

TEST_F(express_cache, LeastRecentlyUsedEntryIsDroppedBeyondTheLimit) {
  SchemaCacheLimits limits;
  limits.max_entries = 2;
  SchemaCache cache(limits);
  const auto a = cache.load_text(schema_with("a"));
  (void)cache.load_text(schema_with("b"));
  (void)cache.load_text(schema_with("a"));  // a is now the most recently used
  (void)cache.load_text(schema_with("c"));  // drops b
  EXPECT_EQ(cache.size(), 2u);
  EXPECT_EQ(cache.parse_count(), 3u);
  EXPECT_EQ(cache.load_text(schema_with("a")).get(), a.get());
  EXPECT_EQ(cache.parse_count(), 3u);
  (void)cache.load_text(schema_with("b"));
  EXPECT_EQ(cache.parse_count(), 4u);
}

TEST_F(express_cache, ProcessWideCacheIsOneObject) {
  EXPECT_EQ(&SchemaCache::process_wide(), &SchemaCache::process_wide());
}

}  // namespace
}  // namespace ncpost::express
