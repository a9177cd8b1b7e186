#pragma once
// What planner tests share: a planner needs no P21 model. Its spec is written by hand, the
// subjects it names are instances that exist only in the test, and the report keeps its
// findings (features/report.hpp).

#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <string_view>
#include <vector>

#include "features/draft.hpp"
#include "features/report.hpp"

namespace ncpost::stepnc::features::test {

// An instance of the test's imagined file, with the id a message names it by.
inline Subject subject(const p21::Instance& instance, std::string_view type) {
  return {&instance, type};
}

class Planning : public ::testing::Test {
 protected:
  p21::Instance workingstep_{10};
  p21::Instance feature_{125};
  p21::Instance tool_{112};
  p21::Instance operation_{180};
  p21::Instance strategy_{128};
  FeatureOptions options_;
  Findings report_{subject(workingstep_, "MACHINING_WORKINGSTEP")};
  Draft draft_{options_, report_};

  Subject feature(std::string_view type = "CLOSED_POCKET") const { return subject(feature_, type); }
  Subject tool() const { return subject(tool_, "MILLING_CUTTING_TOOL"); }
  Subject operation() const { return subject(operation_, "BOTTOM_AND_SIDE_ROUGH_MILLING"); }

  [[nodiscard]] const std::vector<Move>& moves() const { return draft_.moves(); }
  [[nodiscard]] std::size_t count(Move::Kind kind) const {
    return static_cast<std::size_t>(std::count_if(moves().begin(), moves().end(),
                                                  [&](const Move& m) { return m.kind == kind; }));
  }
  // The findings as "CODE: message" lines, for messages that must name what they are about.
  [[nodiscard]] std::vector<std::string> findings() const {
    std::vector<std::string> out;
    for (const Finding& f : report_.all())
      out.push_back(std::string(diag::info(f.code).id) + ": " + f.message);
    return out;
  }
};

}  // namespace ncpost::stepnc::features::test
