// The block → workingstep map of a posted program (POST /v1/posts with Accept: application/json).

#include "ncpost/pipeline/block_map.hpp"

#include <gtest/gtest.h>

namespace ncpost::pipeline {
namespace {

// Offsets into "G0 X1\nG1 X2\nG1 X3\n": lines 1 (0-5), 2 (6-11), 3 (12-17), the end (18) on 4.
TEST(BlockMap, LinesAtOffsets) {
  const std::string text = "G0 X1\nG1 X2\nG1 X3\n";
  EXPECT_EQ(lines_at(text, {0, 5, 6, 11, 12, 17, 18, 3}),
            (std::vector<std::size_t>{1, 1, 2, 2, 3, 3, 4, 1}));
  EXPECT_EQ(lines_at("", {0}), (std::vector<std::size_t>{1}));
}

// A motion's [begin, end) text: its first and last line; none for an empty one.
TEST(BlockMap, MotionLines) {
  const std::string text = "(WS 1)\nG0 X1\nG81 X1 Y1\nG80\nG1 X2\n";
  // Lines start at 0, 7, 13, 23, 27; the cycle wrote lines 3 and 4, one motion wrote nothing.
  const auto lines = motion_lines(text, {{7, 13}, {13, 27}, {27, 27}, {27, 32}});
  EXPECT_EQ(lines, nlohmann::ordered_json::parse("[[2, 2], [3, 4], null, [5, 5]]"));
}

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
