// The JSON trace: each record parses, agrees with the text trace call by call (line number,
// name, numbers), strings are valid JSON whatever the bytes, and both layouts hold the same
// records with the header and end members.

#include "ncpost/canon/json_trace.hpp"

#include <gtest/gtest.h>

#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>

#include "canon_support.hpp"
#include "ncpost/canon/trace.hpp"

namespace ncpost::canon {
namespace {

using json = nlohmann::json;

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

std::string written(const std::vector<Call>& calls, JsonLayout layout, std::string header = {},
                    std::string end = {}) {
  std::string out;
  JsonTraceWriter writer([&out](std::string_view piece) { out += piece; }, layout,
                         std::move(header));
  for (const auto& c : calls) writer.call(c);
  writer.finish(end);
  return out;
}

std::string json_of(const Call& call) {
  std::string s;
  append_json_call(s, call, 7);
  return s;
}

TEST(CanonJsonTrace, ExactRecords) {
  EXPECT_EQ(json_of(StraightFeed{{91.9, -13.5, 2.5}}),
            R"({"n":7,"call":"STRAIGHT_FEED","x":91.9000,"y":-13.5000,"z":2.5000})");
  EXPECT_EQ(json_of(StraightTraverse{{1, 2, 3, Rotary{0, 90, 0}, Direction{0, 0, 1}}}),
            R"({"n":7,"call":"STRAIGHT_TRAVERSE","x":1.0000,"y":2.0000,"z":3.0000,)"
            R"("a":0.0000,"b":90.0000,"c":0.0000,"i":0.0000,"j":0.0000,"k":1.0000})");
  EXPECT_EQ(json_of(ArcFeed{{10, 0, -2}, {0, 0, -2}, {0, 0, 1}, -2}),
            R"({"n":7,"call":"ARC_FEED","x":10.0000,"y":0.0000,"z":-2.0000,)"
            R"("centre":[0.0000,0.0000,-2.0000],"normal":[0.0000,0.0000,1.0000],"turns":-2})");
  EXPECT_EQ(
      json_of(Begin{Scope::Workingstep, {10, "MACHINING_WORKINGSTEP", "WS 1"}}),
      R"({"n":7,"call":"WORKINGSTEP_BEGIN","id":10,"type":"MACHINING_WORKINGSTEP","name":"WS 1"})");
  EXPECT_EQ(json_of(End{Scope::Workplan, {}}),
            R"({"n":7,"call":"WORKPLAN_END","id":null,"type":null,"name":""})");
  EXPECT_EQ(json_of(SetFeedRate{250}), R"({"n":7,"call":"SET_FEED_RATE","rate":250.0000})");
  EXPECT_EQ(json_of(ProgramEnd{}), R"({"n":7,"call":"PROGRAM_END"})");
  EXPECT_EQ(json_of(SetFeedRate{std::numeric_limits<double>::quiet_NaN()}),
            R"({"n":7,"call":"SET_FEED_RATE","rate":null})");
}

TEST(CanonJsonTrace, StringsAreValidJsonWhateverTheBytes) {
  const std::string nasty = "a\"b\\c\n\t\x01 \xC3\xA9 \xFF end";
  const std::string record = json_of(Comment{nasty});
  const json parsed = json::parse(record);  // throws on invalid JSON or UTF-8
  EXPECT_EQ(parsed["text"].get<std::string>(), "a\"b\\c\n\t\x01 \xC3\xA9 \xEF\xBF\xBD end");
  EXPECT_NE(record.find(R"(\u0001)"), std::string::npos);
}

// Call by call the same line numbers, names and numbers as the text trace.
TEST(CanonJsonTrace, AgreesWithTheTextTrace) {
  const auto calls = test::sample_program();
  const auto records = lines_of(written(calls, JsonLayout::Lines, R"("stock":[])", R"("ok":true)"));
  const auto text = lines_of(trace(calls));
  ASSERT_EQ(records.size(), calls.size() + 2);
  EXPECT_EQ(json::parse(records.front()),
            json::parse(R"({"format":"ncpost-trace","version":1,"stock":[]})"));
  EXPECT_EQ(json::parse(records.back()), json::parse(R"({"end":true,"ok":true})"));
  for (std::size_t k = 0; k < calls.size(); ++k) {
    SCOPED_TRACE(text[k]);
    const json r = json::parse(records[k + 1]);
    EXPECT_EQ(r["n"], k + 1);
    const std::string name = r["call"];
    // "    16 STRAIGHT_FEED(..." → the name; a tilted arc prints as ARC_FEED_3D in the text.
    const std::string text_name = text[k].substr(6, text[k].find('(') - 6);
    EXPECT_EQ(text_name == "ARC_FEED_3D" ? "ARC_FEED" : text_name, name);
    if (r.contains("x") && name != "ARC_FEED") {
      std::string x;
      append_number(x, r["x"].get<double>());
      EXPECT_NE(text[k].find("(" + x + ", "), std::string::npos);
    }
  }
}

TEST(CanonJsonTrace, DocumentHoldsTheSameRecords) {
  const auto calls = test::sample_program();
  const json document =
      json::parse(written(calls, JsonLayout::Document, R"("stock":[])", R"("ok":false)"));
  const auto records = lines_of(written(calls, JsonLayout::Lines));
  ASSERT_EQ(document["calls"].size(), calls.size());
  for (std::size_t k = 0; k < calls.size(); ++k)
    EXPECT_EQ(document["calls"][k], json::parse(records[k + 1]));
  EXPECT_EQ(document["format"], "ncpost-trace");
  EXPECT_EQ(document["ok"], false);
  // No calls at all: still one valid document, and a header and end record as lines.
  EXPECT_EQ(json::parse(written({}, JsonLayout::Document))["calls"], json::array());
  EXPECT_EQ(lines_of(written({}, JsonLayout::Lines)).size(), 2u);
}

}  // namespace
}  // namespace ncpost::canon
