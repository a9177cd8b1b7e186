#pragma once
// Locates the shared corpus of real files (../shared/corpus, or NCPOST_CORPUS). The corpus is
// data written by others and is never copied into the project. Where it is missing the test
// skips with a message, unless NCPOST_REQUIRE_CORPUS=1, which makes the absence a failure.

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>

namespace ncpost::test {

inline std::filesystem::path source_dir() {
  if (const char* env = std::getenv("NCPOST_SOURCE_DIR")) return env;
#ifdef NCPOST_SOURCE_DIR
  return NCPOST_SOURCE_DIR;
#else
  return std::filesystem::current_path();
#endif
}

inline std::optional<std::filesystem::path> corpus_dir() {
  if (const char* env = std::getenv("NCPOST_CORPUS"); env && *env) {
    if (std::filesystem::is_directory(env)) return std::filesystem::path(env);
    return std::nullopt;
  }
  auto candidate = source_dir() / ".." / "shared" / "corpus";
  if (std::filesystem::is_directory(candidate)) return std::filesystem::canonical(candidate);
  return std::nullopt;
}

inline bool corpus_required() {
  const char* env = std::getenv("NCPOST_REQUIRE_CORPUS");
  return env && std::string(env) == "1";
}

inline std::string read_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

}  // namespace ncpost::test

// Use at the top of a test that needs the corpus: binds `corpus` to its path or skips.
#define NCPOST_REQUIRE_CORPUS_OR_SKIP(corpus)                                               \
  const auto corpus##_opt = ::ncpost::test::corpus_dir();                                   \
  if (!corpus##_opt) {                                                                      \
    if (::ncpost::test::corpus_required())                                                  \
      FAIL() << "NCPOST_REQUIRE_CORPUS=1 but the corpus was not found (set NCPOST_CORPUS)"; \
    GTEST_SKIP() << "corpus not found: set NCPOST_CORPUS or place it at ../shared/corpus";  \
  }                                                                                         \
  const std::filesystem::path corpus = *corpus##_opt
