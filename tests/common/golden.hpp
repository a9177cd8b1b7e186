#pragma once
// Golden files: compare with the checked-in expectation, or rewrite it when
// NCPOST_UPDATE_GOLDEN=1 (creating its folder).

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "corpus.hpp"

namespace ncpost::test {

inline void expect_golden(const std::string& actual, const std::filesystem::path& golden) {
  if (const char* update = std::getenv("NCPOST_UPDATE_GOLDEN");
      update && std::string(update) == "1") {
    std::filesystem::create_directories(golden.parent_path());
    std::ofstream(golden, std::ios::binary) << actual;
    return;
  }
  ASSERT_TRUE(std::filesystem::exists(golden)) << golden;
  EXPECT_EQ(actual, read_file(golden)) << "differs from " << golden;
}

}  // namespace ncpost::test
