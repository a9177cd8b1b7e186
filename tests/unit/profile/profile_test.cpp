// profile.json validation (engine/profile) against the checked-in JSON Schema
// (stylesheets/profile.schema.json): every required field, every enumeration and every bound
// the schema declares must be refused by the C++ validation too, and the built-in profiles
// must load and compile.

#include "ncpost/profile/profile.hpp"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "corpus.hpp"

namespace ncpost::profile {
namespace {

using nlohmann::json;

class ProfileTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { xslt::initialise(); }
  static std::filesystem::path stylesheets() { return test::source_dir() / "stylesheets"; }
  static json valid() {
    return json::parse(test::read_file(stylesheets() / "linuxcnc" / "profile.json"));
  }
  static json schema() {
    return json::parse(test::read_file(stylesheets() / "profile.schema.json"));
  }
  static bool accepts(const json& doc) {
    std::vector<diag::Diagnostic> d;
    const bool ok = parse_profile(doc.dump(), d).has_value();
    EXPECT_EQ(ok, d.empty()) << doc.dump();
    return ok;
  }
};

TEST_F(ProfileTest, BuiltInProfilesParse) {
  for (const char* id : {"linuxcnc", "fanuc-0i", "linuxcnc-5ax", "fanuc-30i-5ax",
                         "siemens-840d-5ax", "heidenhain-tnc640-5ax"}) {
    std::vector<diag::Diagnostic> d;
    auto p = parse_profile(test::read_file(stylesheets() / id / "profile.json"), d);
    ASSERT_TRUE(p) << id << ": " << (d.empty() ? "" : d[0].message);
    EXPECT_EQ(p->id, id);
  }
}

TEST_F(ProfileTest, FieldsMapOntoJobConfig) {
  std::vector<diag::Diagnostic> d;
  auto p = parse_profile(test::read_file(stylesheets() / "fanuc-0i" / "profile.json"), d);
  ASSERT_TRUE(p);
  const auto config = job_config(*p);
  EXPECT_EQ(config.length.decimals, 3);
  EXPECT_FALSE(config.length.leading_zero);
  EXPECT_EQ(config.dwell.scale, 1000);
  EXPECT_EQ(config.block.start, 10);
  EXPECT_EQ(config.block.increment, 10);
  EXPECT_EQ(config.max_line_length, 128u);
  EXPECT_EQ(p->arcs, Arcs::R);
  EXPECT_EQ(p->canned_cycles, CannedCycles::Native);
  EXPECT_EQ(p->limits.severity, diag::Severity::Error);
}

// capabilities.output_options names what the stylesheet honours; the operation-name rules'
// options must be known ones with on/off (PROFILE-010, naming the rule's path and match).
TEST_F(ProfileTest, OutputOptions) {
  std::vector<diag::Diagnostic> d;
  auto fanuc = parse_profile(test::read_file(stylesheets() / "fanuc-0i" / "profile.json"), d);
  ASSERT_TRUE(fanuc);
  EXPECT_TRUE(fanuc->honours(canon::OutputOption::BlockNumbers));
  EXPECT_FALSE(fanuc->honours(canon::OutputOption::Subprogram));
  auto tnc =
      parse_profile(test::read_file(stylesheets() / "heidenhain-tnc640" / "profile.json"), d);
  ASSERT_TRUE(tnc);
  EXPECT_FALSE(tnc->honours(canon::OutputOption::BlockNumbers));  // Klartext numbers every block

  auto v = valid();
  v["capabilities"]["output_options"] = json::array({"block_numbers", "block_numbers"});
  EXPECT_FALSE(accepts(v));
  v["capabilities"]["output_options"] = json::array({"colour"});
  EXPECT_FALSE(accepts(v));

  v = valid();
  v["checks"] = json::parse(test::read_file(test::source_dir() / "tests/golden/cls/checks.json"));
  EXPECT_TRUE(accepts(v));
  v["checks"]["operation_rules"][3]["options"]["block_numbers"] = "sometimes";
  v["checks"]["operation_rules"][4]["options"]["numbering"] = "on";
  d.clear();
  EXPECT_FALSE(parse_profile(v.dump(), d));
  ASSERT_EQ(d.size(), 2u);
  for (const auto& x : d) EXPECT_EQ(x.code, diag::Code::ProfileOutputOption) << x.message;
  EXPECT_NE(d[0].message.find("/checks/operation_rules/3/options/block_numbers"), std::string::npos)
      << d[0].message;
  EXPECT_NE(d[0].message.find("'_NONUM'"), std::string::npos) << d[0].message;
  EXPECT_NE(d[0].message.find("'sometimes'"), std::string::npos) << d[0].message;
  EXPECT_NE(d[1].message.find("unknown output option 'numbering'"), std::string::npos)
      << d[1].message;
}

TEST_F(ProfileTest, HandPickedInvalidExamples) {
  auto v = valid();
  EXPECT_TRUE(accepts(v));
  auto a = v;
  a["units"] = "furlong";
  EXPECT_FALSE(accepts(a));
  auto b = v;
  b["formats"]["length"]["decimals"] = 13;
  EXPECT_FALSE(accepts(b));
  auto c = v;
  c["capabilities"].erase("arcs");
  EXPECT_FALSE(accepts(c));
  auto e = v;
  e["colour"] = "red";
  EXPECT_FALSE(accepts(e));
  auto f = v;
  f["id"] = "Bad Id";
  EXPECT_FALSE(accepts(f));
  auto g = v;
  g["limits"]["travel"]["x"] = json{{"min", 5}, {"max", 1}};
  EXPECT_FALSE(accepts(g));
  auto charset = v;  // parameters are fine; what would end the header line is not
  charset["output"]["mime_type"] = "text/plain; charset=utf-8";
  EXPECT_TRUE(accepts(charset));
  charset["output"]["mime_type"] = "text/plain; charset=utf-8\n";
  EXPECT_FALSE(accepts(charset));
  // The shared examples, which schema_check.py (ctest profile_schema_jsonschema) checks the
  // JSON Schema refuses too.
  const json examples = json::parse(
      test::read_file(test::source_dir() / "tests" / "unit" / "profile" / "invalid_examples.json"));
  ASSERT_GE(examples.size(), 10u);
  for (const auto& example : examples) {
    json doc = v;
    const json set = example.value("set", json::object());
    const json remove = example.value("remove", json::array());
    for (const auto& [path, value] : set.items()) doc[json::json_pointer(path)] = value;
    for (const auto& path : remove) {
      const json::json_pointer ptr(path.get<std::string>());
      doc[ptr.parent_pointer()].erase(ptr.back());
    }
    EXPECT_FALSE(accepts(doc)) << example["name"];
  }
  // min not below max: a rule JSON Schema cannot state (the C++ side only, like travel).
  auto h = v;
  h["kinematics"] = json::parse(
      R"({"type": "head-head", "primary": {"name": "C", "axis": "z", "direction": 1, "min": 0, "max": 0},
          "secondary": {"name": "A", "axis": "x", "direction": 1, "min": -90, "max": 90}})");
  EXPECT_FALSE(accepts(h));
  std::vector<diag::Diagnostic> d;
  EXPECT_FALSE(parse_profile("{not json", d));
  ASSERT_EQ(d.size(), 1u);
  EXPECT_EQ(d[0].code, diag::Code::ProfileJson);
  // Issue 23 (11): the position is the diagnostic's, not only words in its message.
  EXPECT_EQ(d[0].line, 1u);
  EXPECT_EQ(d[0].column, 3u) << "the 'o' that cannot continue a literal";
  EXPECT_EQ(d[0].message.find("json.exception"), std::string::npos) << d[0].message;
  d.clear();
  EXPECT_FALSE(parse_profile("{\n  \"id\": \"x\",\n  \"name\": ,\n}", d));
  ASSERT_EQ(d.size(), 1u);
  EXPECT_EQ(d[0].line, 3u);
  EXPECT_EQ(d[0].column, 11u) << d[0].message;
}

// Walks the schema alongside the valid document: for each object, drop each required field
// and add an unknown one; for each enum, try a value outside it; for each numeric bound, go
// past it; for each type, give a value of another type. The C++ validation must refuse all.
void mutations(const json& schema, const json& root_schema, json& doc, json& node,
               const std::string& path, int& count) {
  const json* s = &schema;
  if (s->contains("$ref")) {
    const std::string ref = (*s)["$ref"].get<std::string>();  // "#/$defs/name"
    s = &root_schema["$defs"][ref.substr(ref.rfind('/') + 1)];
  }
  auto check = [&](const std::string& what) {
    std::vector<diag::Diagnostic> d;
    EXPECT_FALSE(parse_profile(doc.dump(), d).has_value()) << path << ": " << what;
    ++count;
  };
  if (s->contains("enum")) {
    const json saved = node;
    node = "not-in-the-enum";
    check("enum");
    node = saved;
  }
  const std::string type = s->value("type", "");
  if (type == "integer" || type == "number") {
    const json saved = node;
    if (s->contains("minimum")) {
      node = (*s)["minimum"].get<double>() - 1;
      if (type == "integer") node = (*s)["minimum"].get<std::int64_t>() - 1;
      check("minimum");
    }
    if (s->contains("exclusiveMinimum")) {
      node = (*s)["exclusiveMinimum"];
      check("exclusiveMinimum");
    }
    if (s->contains("maximum")) {
      node = (*s)["maximum"].get<double>() * 2 + 1;
      if (type == "integer") node = (*s)["maximum"].get<std::int64_t>() + 1;
      check("maximum");
    }
    node = "text";
    check("type");
    node = saved;
  } else if (type == "boolean" || type == "array") {
    const json saved = node;
    node = "text";
    check("type");
    node = saved;
  } else if (type == "object") {
    for (const auto& r : s->value("required", json::array())) {
      const std::string key = r.get<std::string>();
      const json saved = node[key];
      node.erase(key);
      check("required " + key);
      node[key] = saved;
    }
    node["unknown_field"] = 1;
    check("additionalProperties");
    node.erase("unknown_field");
    for (const auto& [key, sub] : (*s)["properties"].items()) {
      if (key == "$schema" || !node.contains(key)) continue;
      mutations(sub, root_schema, doc, node[key], path + "/" + key, count);
    }
  }
}

TEST_F(ProfileTest, SchemaAndValidationAgree) {
  const json s = schema();
  json doc = valid();
  int count = 0;
  mutations(s, s, doc, doc, "", count);
  EXPECT_GT(count, 80);
  EXPECT_TRUE(accepts(doc));  // restored
  // The five-axis profiles carry a kinematics section (one of each type): walked the same way.
  for (const char* id : {"linuxcnc-5ax", "fanuc-30i-5ax", "siemens-840d-5ax"}) {
    SCOPED_TRACE(id);
    json five = json::parse(test::read_file(stylesheets() / id / "profile.json"));
    int kinematics_count = 0;
    mutations(s["properties"]["kinematics"], s, five, five["kinematics"], "/kinematics",
              kinematics_count);
    EXPECT_GT(kinematics_count, 25);
    EXPECT_TRUE(accepts(five));
  }
}

// The shared valid examples (valid_examples.json, which schema_check.py checks the JSON Schema
// accepts too): each kinematics type, every optional field.
TEST_F(ProfileTest, ValidKinematicsExamples) {
  const json examples = json::parse(
      test::read_file(test::source_dir() / "tests" / "unit" / "profile" / "valid_examples.json"));
  ASSERT_GE(examples.size(), 3u);
  for (const auto& example : examples) {
    json doc = valid();
    for (const auto& [path, value] : example["set"].items()) doc[json::json_pointer(path)] = value;
    EXPECT_TRUE(accepts(doc)) << example["name"];
  }
  std::vector<diag::Diagnostic> d;
  const auto p =
      parse_profile(test::read_file(stylesheets() / "fanuc-30i-5ax" / "profile.json"), d);
  ASSERT_TRUE(p);
  ASSERT_TRUE(p->kinematics);
  const Kinematics& k = *p->kinematics;
  EXPECT_EQ(k.type, KinematicsType::TableTable);
  EXPECT_EQ(k.primary.name, 'A');
  EXPECT_EQ(k.primary.axis, MachineAxis::X);
  EXPECT_EQ(k.primary.min, -120);
  EXPECT_EQ(k.primary.max, 30);
  EXPECT_TRUE(k.secondary.continuous);
  EXPECT_TRUE(k.tool_centre_point);
  EXPECT_EQ(k.solution, RotarySolution::Shortest);
  EXPECT_EQ(k.pole_tolerance, 1e-9);
  const auto config = job_config(*p);
  EXPECT_TRUE(config.rotary_axes[0]);
  EXPECT_FALSE(config.rotary_axes[1]);
  EXPECT_TRUE(config.rotary_axes[2]);
  // A profile without kinematics writes every rotary axis a motion carries, as before.
  const auto three = parse_profile(test::read_file(stylesheets() / "linuxcnc" / "profile.json"), d);
  ASSERT_TRUE(three);
  EXPECT_FALSE(three->kinematics);
  EXPECT_EQ(job_config(*three).rotary_axes, (std::array<bool, 3>{true, true, true}));
}

TEST_F(ProfileTest, StoreListsAndLoadsBuiltIns) {
  ProfileStore store(stylesheets());
  std::vector<diag::FileDiagnostic> d;
  const auto list = store.list(d);
  ASSERT_GE(list.size(), 2u);
  EXPECT_TRUE(d.empty());
  auto a = store.load("linuxcnc", d);
  ASSERT_TRUE(a) << (d.empty() ? "" : diag::format(d[0]));
  auto b = store.load("linuxcnc", d);
  EXPECT_EQ(a.get(), b.get());  // compiled once, cached
  EXPECT_TRUE(store.load("fanuc-0i", d));
  EXPECT_FALSE(store.load("no-such-profile", d));
  ASSERT_FALSE(d.empty());
  EXPECT_EQ(d.back().diagnostic.code, diag::Code::ProfileUnknown);
  EXPECT_FALSE(store.load("../etc", d));
}

}  // namespace
}  // namespace ncpost::profile
