// The `checks` section: cls::parse_checks against $defs/checks of stylesheets/profile.schema.json
// (the same invalid examples as checks_schema_check.py, and a walk over the schema that breaks
// every rule it states), the name patterns, and the profile carrying the section as text.

#include "ncpost/cls/checks.hpp"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "corpus.hpp"
#include "ncpost/canon/sink.hpp"
#include "ncpost/cls/reader.hpp"
#include "ncpost/profile/profile.hpp"

namespace ncpost::cls {
namespace {

using nlohmann::json;

json example() {
  return json::parse(test::read_file(test::source_dir() / "tests/golden/cls/checks.json"));
}
json schema() {
  return json::parse(test::read_file(test::source_dir() / "stylesheets/profile.schema.json"));
}
bool accepts(const json& section) {
  std::vector<diag::Diagnostic> d;
  const bool ok = parse_checks(section, d).has_value();
  EXPECT_EQ(ok, d.empty()) << section.dump();
  for (const auto& x : d) EXPECT_EQ(x.code, diag::Code::ClsChecksInvalid);
  return ok;
}

TEST(ChecksConfig, ExampleParses) {
  std::vector<diag::Diagnostic> d;
  const auto config = parse_checks(example(), d);
  ASSERT_TRUE(config) << (d.empty() ? "" : d[0].message);
  EXPECT_TRUE(config->enabled);
  EXPECT_EQ(config->tool_patterns.size(), 3u);
  EXPECT_EQ(config->unmatched, Unmatched::Warning);
  ASSERT_EQ(config->heads.size(), 3u);
  ASSERT_NE(config->head("head30"), nullptr);
  EXPECT_DOUBLE_EQ(config->head("head30")->allowed_k.at(0), 0.8660254);
  EXPECT_EQ(config->operation_rules.size(), 5u);
  EXPECT_TRUE(config->default_head.empty());
}

json::json_pointer pointer(const std::string& path) {
  return json::json_pointer(path);
}

TEST(ChecksSchema, InvalidExamplesAreRefused) {
  const json examples = json::parse(
      test::read_file(test::source_dir() / "tests/unit/cls/checks_invalid_examples.json"));
  ASSERT_GE(examples.size(), 15u);
  for (const auto& e : examples) {
    json doc = e.contains("replace") ? e["replace"] : example();
    const json set = e.value("set", json::object());
    const json remove = e.value("remove", json::array());
    for (const auto& [path, value] : set.items()) doc[pointer(path)] = value;
    for (const auto& path : remove) {
      const auto p = pointer(path.get<std::string>());
      json& parent = doc[p.parent_pointer()];
      if (parent.is_array())
        parent.erase(std::stoul(p.back()));
      else
        parent.erase(p.back());
    }
    EXPECT_FALSE(accepts(doc)) << e["name"];
  }
}

TEST(ChecksSchema, PatternThatDoesNotCompile) {
  json doc = example();
  doc["tool_names"]["patterns"][0]["regex"] = "^T(";
  std::vector<diag::Diagnostic> d;
  EXPECT_FALSE(parse_checks(doc, d));
  ASSERT_FALSE(d.empty());
  EXPECT_NE(d[0].message.find("/tool_names/patterns/0/regex"), std::string::npos) << d[0].message;
  doc = example();
  doc["operation_rules"][0]["head"] = "no-such-head";
  EXPECT_FALSE(accepts(doc));
  doc = example();
  doc["heads"]["default"] = "no-such-head";
  EXPECT_FALSE(accepts(doc));
  EXPECT_FALSE(parse_checks(std::string_view("{not json"), d));
}

// Walks $defs/checks alongside the example: for each object drop each required field and add an
// unknown one, for each enum try a value outside it, for each bound go past it, for each type
// give another; the C++ validation must refuse every one.
void mutations(const json& s, const json& root, json& doc, json& node, const std::string& path,
               int& count) {
  const json* sch = &s;
  if (sch->contains("$ref")) {
    const std::string ref = (*sch)["$ref"].get<std::string>();
    sch = &root["$defs"][ref.substr(ref.rfind('/') + 1)];
  }
  auto refuse = [&](const std::string& what) {
    std::vector<diag::Diagnostic> d;
    EXPECT_FALSE(parse_checks(doc, d).has_value()) << path << ": " << what;
    ++count;
  };
  auto replaced = [&](const json& value, const std::string& what) {
    const json saved = node;
    node = value;
    refuse(what);
    node = saved;
  };
  if (sch->contains("enum")) replaced("not-in-the-enum", "enum");
  const std::string type = sch->value("type", "");
  if (type == "number") {
    if (sch->contains("minimum")) replaced((*sch)["minimum"].get<double>() - 1, "minimum");
    if (sch->contains("maximum")) replaced((*sch)["maximum"].get<double>() * 2 + 1, "maximum");
    replaced("text", "type");
  } else if (type == "boolean") {
    replaced("text", "type");
  } else if (type == "string") {
    replaced(5, "type");
    if (sch->contains("minLength")) replaced("", "minLength");
  } else if (type == "array") {
    replaced("text", "type");
    if (sch->contains("minItems") && (*sch)["minItems"].get<int>() > 0)
      replaced(json::array(), "minItems");
    for (std::size_t i = 0; i < node.size(); ++i)
      mutations((*sch)["items"], root, doc, node[i], path + "/" + std::to_string(i), count);
  } else if (type == "object") {
    replaced("text", "type");
    for (const auto& r : sch->value("required", json::array())) {
      const std::string key = r.get<std::string>();
      const json saved = node[key];
      node.erase(key);
      refuse("required " + key);
      node[key] = saved;
    }
    if (sch->value("additionalProperties", json(true)) == json(false)) {
      node["unknown_field"] = 1;
      refuse("additionalProperties");
      node.erase("unknown_field");
    }
    if (sch->contains("minProperties") && (*sch)["minProperties"].get<int>() > 0 &&
        !sch->contains("required"))
      replaced(json::object(), "minProperties");
    const json properties = sch->value("properties", json::object());
    for (const auto& [key, sub] : properties.items())
      if (node.contains(key)) mutations(sub, root, doc, node[key], path + "/" + key, count);
    if (const auto extra = sch->find("additionalProperties");
        extra != sch->end() && extra->is_object())
      for (auto& [key, value] : node.items())
        mutations(*extra, root, doc, value, path + "/" + key, count);
  }
}

TEST(ChecksSchema, SchemaAndValidationAgree) {
  const json s = schema();
  json doc = example();
  int count = 0;
  mutations(s["$defs"]["checks"], s, doc, doc, "", count);
  EXPECT_GT(count, 60);
  EXPECT_TRUE(accepts(doc));  // restored
}

TEST(ChecksNames, PatternsGiveDimensions) {
  std::vector<diag::Diagnostic> d;
  const auto config = parse_checks(example(), d);
  ASSERT_TRUE(config);
  auto t = dimensions_from_name(*config, "T15-D6-CR2");
  ASSERT_TRUE(t);
  EXPECT_EQ(t->diameter, 6.0);
  EXPECT_EQ(t->corner_radius, 2.0);
  EXPECT_FALSE(t->length);
  t = dimensions_from_name(*config, "T7-D12-L80");
  ASSERT_TRUE(t);
  EXPECT_EQ(t->diameter, 12.0);
  EXPECT_FALSE(t->corner_radius);  // the optional group did not take part
  EXPECT_EQ(t->length, 80.0);
  const auto ball = dimensions_from_name(*config, "BALL-50");
  ASSERT_TRUE(ball);
  EXPECT_EQ(ball->diameter, 50.0);
  EXPECT_EQ(ball->corner_radius, 25.0);
  const auto mill = dimensions_from_name(*config, "MILL-20");
  ASSERT_TRUE(mill);
  EXPECT_EQ(mill->diameter, 20.0);
  EXPECT_EQ(mill->corner_radius, 0.0);  // fixed by the pattern
  EXPECT_FALSE(dimensions_from_name(*config, "ENDMILL"));
  // A group that captured something that is not a number is left out.
  const auto odd = dimensions_from_name(*config, "T1-D1.2.3");
  ASSERT_TRUE(odd);
  EXPECT_FALSE(odd->diameter);
}

// Runs a CL text with `config` and returns the codes reported.
std::vector<std::string> codes_of(std::string_view text, const CheckConfig* config) {
  canon::ProgramBuffer sink;
  ReadOptions options;
  options.checks = config;
  const auto result = read(text, sink, options);
  std::vector<std::string> codes;
  for (const auto& d : result.diagnostics) codes.emplace_back(d.code_id());
  return codes;
}

constexpr std::string_view kWrongTool =
    "UNITS/MM\nTOOL PATH/OP,TOOL,T1-D10\nTLDATA/MILL,12,0,50,0,0\nGOTO/0,0,1,0,0,1\n";

// The operation-name rules' output options reach the canonical program on each operation's
// WORKINGSTEP_BEGIN: per operation, the first rule setting an option deciding it.
TEST(ChecksRun, OperationRulesPutOutputOptionsOnTheWorkingstep) {
  json section = example();
  section["operation_rules"].push_back(json::parse(
      R"({"match": "_NONUM", "options": {"block_numbers": "on", "subprogram": "off"}})"));
  std::vector<diag::Diagnostic> d;
  const auto config = parse_checks(section, d);
  ASSERT_TRUE(config) << (d.empty() ? "" : d[0].message);
  canon::ProgramBuffer sink;
  ReadOptions options;
  options.checks = &*config;
  const auto result = read(
      "UNITS/MM\nTOOL PATH/FACE_NONUM\nGOTO/0,0,1\nTOOL PATH/POCKET_SUB\nGOTO/0,0,1\n"
      "TOOL PATH/PLAIN\nGOTO/0,0,1\nFINI\n",
      sink, options);
  EXPECT_TRUE(result.ok());
  std::vector<std::pair<std::string, canon::OutputOptions>> begins;
  for (const auto& call : sink.calls())
    if (const auto* b = std::get_if<canon::Begin>(&call);
        b && b->scope == canon::Scope::Workingstep)
      begins.emplace_back(b->entity.name, b->options);
  ASSERT_EQ(begins.size(), 3u);
  EXPECT_EQ(begins[0].first, "FACE_NONUM");
  EXPECT_EQ(begins[0].second.block_numbers, canon::Switch::Off);  // the first rule decides
  EXPECT_EQ(begins[0].second.subprogram, canon::Switch::Off);     // only the later one sets it
  EXPECT_EQ(begins[1].second.block_numbers, canon::Switch::Unset);
  EXPECT_EQ(begins[1].second.subprogram, canon::Switch::On);
  EXPECT_TRUE(begins[2].second.empty());
  // Without checks (--no-checks) no rule runs, so no options either.
  canon::ProgramBuffer plain;
  (void)read("UNITS/MM\nTOOL PATH/FACE_NONUM\nGOTO/0,0,1\nFINI\n", plain);
  for (const auto& call : plain.calls())
    if (const auto* b = std::get_if<canon::Begin>(&call)) {
      EXPECT_TRUE(b->options.empty());
    }
}

TEST(ChecksConfig, UnknownOutputOptionsNameTheRule) {
  json section = example();
  section["operation_rules"][3]["options"] = json::parse(R"({"block_numbers": "sometimes"})");
  std::vector<diag::Diagnostic> d;
  EXPECT_FALSE(parse_checks(section, d));
  ASSERT_EQ(d.size(), 1u);
  EXPECT_NE(d[0].message.find("/operation_rules/3/options/block_numbers"), std::string::npos)
      << d[0].message;
  EXPECT_NE(d[0].message.find("'sometimes'"), std::string::npos) << d[0].message;
}

TEST(ChecksRun, SwitchedOffByTheProfileOrThePost) {
  std::vector<diag::Diagnostic> d;
  auto config = parse_checks(example(), d);
  ASSERT_TRUE(config);
  EXPECT_EQ(codes_of(kWrongTool, &*config), std::vector<std::string>{"CLS-101"});
  EXPECT_TRUE(codes_of(kWrongTool, nullptr).empty());  // --no-checks / checks=false
  config->enabled = false;                             // "enabled": false in the profile
  EXPECT_TRUE(codes_of(kWrongTool, &*config).empty());
}

TEST(ChecksRun, DefaultHeadChecksOperationsWithoutARule) {
  json doc = example();
  doc["heads"]["default"] = "head90";
  std::vector<diag::Diagnostic> d;
  const auto config = parse_checks(doc, d);
  ASSERT_TRUE(config);
  const auto codes = codes_of(kWrongTool, &*config);
  EXPECT_EQ(codes, (std::vector<std::string>{"CLS-101", "CLS-102"}));
}

TEST(ChecksRun, MessagesCarryBothValuesAndBothLines) {
  std::vector<diag::Diagnostic> d;
  const auto config = parse_checks(example(), d);
  ASSERT_TRUE(config);
  canon::ProgramBuffer sink;
  ReadOptions options;
  options.checks = &*config;
  const auto result = read(kWrongTool, sink, options);
  ASSERT_EQ(result.diagnostics.size(), 1u);
  const auto& e = result.diagnostics[0];
  EXPECT_EQ(e.line, 3u);
  EXPECT_EQ(e.message,
            "diameter: tool name 'T1-D10' (line 2) says 10.0000, TLDATA/ (line 3) says 12.0000");
  // stop_at_first_error: a failed check stops the read without the end sequence.
  canon::ProgramBuffer stopped;
  options.stop_at_first_error = true;
  const auto r2 = read(std::string(kWrongTool) + "GOTO/1,1,1\nFINI\n", stopped, options);
  EXPECT_FALSE(r2.ok());
  EXPECT_FALSE(std::holds_alternative<canon::End>(stopped.calls().back()));
}

TEST(ChecksProfile, ProfileCarriesTheSectionAsText) {
  json profile =
      json::parse(test::read_file(test::source_dir() / "stylesheets/linuxcnc/profile.json"));
  profile["checks"] = example();
  std::vector<diag::Diagnostic> d;
  const auto p = profile::parse_profile(profile.dump(), d);
  ASSERT_TRUE(p) << (d.empty() ? "" : d[0].message);
  ASSERT_TRUE(p->checks_json);
  EXPECT_TRUE(parse_checks(std::string_view(*p->checks_json), d)) << d.size();
  profile["checks"] = 5;
  EXPECT_FALSE(profile::parse_profile(profile.dump(), d));
  profile.erase("checks");
  const auto none = profile::parse_profile(profile.dump(), d);
  ASSERT_TRUE(none);
  EXPECT_FALSE(none->checks_json);
}

}  // namespace
}  // namespace ncpost::cls
