// The block → workingstep map of a posted program (POST /v1/posts with Accept: application/json).

#include "ncpost/pipeline/block_map.hpp"

#include <gtest/gtest.h>

namespace ncpost::pipeline {
namespace {

TEST(BlockMap, BlocksBelongToTheWorkingstepWhoseTextTheyAreIn) {
  const std::string text = "%\nO0001\nN10 G0 X0\nN20 G1 X1\n(comment)\nN30 G1 X2\nN40 M30\n%\n";
  // Workingstep 7 starts at "N10", workingstep 9 at "N30"; the end marker before "N40".
  const std::vector<WorkingstepMark> marks = {
      {text.find("N10"), 7, "ROUGH"},
      {text.find("(comment)"), 0, {}},
      {text.find("N30"), 9, "FINISH"},
      {text.find("N40"), 0, {}},
  };
  const auto j = block_map(text, marks);
  EXPECT_EQ(j["blocks"].dump(), R"({"10":7,"20":7,"30":9})");
  ASSERT_EQ(j["workingsteps"].size(), 2u);
  EXPECT_EQ(j["workingsteps"][0]["first_line"], 3);
  EXPECT_EQ(j["workingsteps"][0]["last_line"], 4);
  EXPECT_EQ(j["workingsteps"][1]["name"], "FINISH");
  const auto unnumbered = block_map("G0 X0\nG1 X1\n", {{0, 5, "W"}});
  EXPECT_EQ(unnumbered["blocks"].dump(), R"({"L1":5,"L2":5})");
}

TEST(BlockMap, ABlockNumberSeenAgainKeepsEveryBlock) {
  // Block numbers that wrap (N9999 → N1 on a FANUC with N numbers up to 9999) repeat.
  const std::string text = "N1 G0 X0\nN2 G1 X1\nN1 G1 X2\nN2 G1 X3\nN1 M30\n";
  const auto j = block_map(text, {{0, 3, "A"}, {text.find("N1 G1 X2"), 4, "B"}});
  EXPECT_EQ(j["blocks"].dump(), R"({"1":3,"2":3,"1#2":4,"2#2":4,"1#3":4})");
}

TEST(BlockMap, GrowsInProportionToTheProgramAndStopsWhenCancelled) {
  // 200,000 numbered blocks (a few MB of program): every one mapped, in program order.
  std::string text;
  for (int n = 1; n <= 200000; ++n) text += "N" + std::to_string(n) + " G1 X1\n";
  const auto j = block_map(text, {{0, 7, "W"}});
  ASSERT_EQ(j["blocks"].size(), 200000u);
  EXPECT_EQ(j["blocks"].begin().key(), "1");
  EXPECT_EQ(j["blocks"]["200000"], 7);
  const std::atomic<bool> cancelled{true};
  EXPECT_TRUE(block_map(text, {{0, 7, "W"}}, &cancelled).is_null());
}

}  // namespace
}  // namespace ncpost::pipeline
