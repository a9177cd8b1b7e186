// dialect.json loading (engine/gcode load_dialect) against the checked-in JSON Schema
// (stylesheets/dialect.schema.json): every required field, enumeration, pattern and bound the
// schema declares must be refused by the C++ validation too, and the built-in dialects load.

#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>

#include "gcode_support.hpp"

namespace ncpost::gcode {
namespace {

using nlohmann::json;
namespace fs = std::filesystem;

fs::path stylesheets() {
  return ncpost::test::source_dir() / "stylesheets";
}
json valid() {
  return json::parse(ncpost::test::read_file(stylesheets() / "linuxcnc" / "dialect.json"));
}
bool accepts(const json& doc) {
  const auto r = load_dialect(doc.dump());
  EXPECT_EQ(r.dialect != nullptr, r.diagnostics.empty()) << doc.dump().substr(0, 200);
  return r.dialect != nullptr;
}

TEST(DialectTest, BuiltInDialectsLoad) {
  int count = 0;
  for (const auto& e : fs::directory_iterator(stylesheets())) {
    const fs::path file = e.path() / "dialect.json";
    if (!fs::exists(file)) continue;
    ++count;
    const auto r = load_dialect(ncpost::test::read_file(file));
    ASSERT_TRUE(r.dialect) << file << ": "
                           << (r.diagnostics.empty() ? "" : r.diagnostics[0].message);
    EXPECT_EQ(r.dialect->id, e.path().filename().string());
    EXPECT_FALSE(r.dialect->codes.empty());
  }
  EXPECT_GE(count, 1);
}

// The pipeline's one call: a dialect text and a program; a broken dialect reads nothing.
TEST(DialectTest, ReadWithDialect) {
  canon::ProgramBuffer good;
  const auto r = read_with_dialect("G0 X1\nM2\n", valid().dump(), "linuxcnc/dialect.json", good);
  EXPECT_TRUE(r.ok());
  const auto calls = std::move(good).take();
  EXPECT_EQ(r.calls, calls.size());
  bool moved = false;
  for (const auto& c : calls)
    if (const auto* t = std::get_if<canon::StraightTraverse>(&c)) moved = t->to.x == 1;
  EXPECT_TRUE(moved);

  json broken = valid();
  broken.erase("codes");
  canon::ProgramBuffer none;
  const auto b = read_with_dialect("G0 X1\nM2\n", broken.dump(), "mine/dialect.json", none);
  EXPECT_FALSE(b.ok());
  ASSERT_FALSE(b.diagnostics.empty());
  EXPECT_EQ(b.diagnostics[0].file, "mine/dialect.json");
  EXPECT_EQ(b.diagnostics[0].diagnostic.code, diag::Code::GcodeDialectInvalid);
  EXPECT_EQ(b.calls, 0u);
  EXPECT_TRUE(std::move(none).take().empty());
}

TEST(DialectTest, WhatTheLinuxcncDialectSays) {
  const auto d = test::dialect("linuxcnc");
  ASSERT_TRUE(d);
  EXPECT_EQ(d->syntax, Syntax::WordAddress);
  EXPECT_TRUE(d->metric);
  ASSERT_TRUE(d->g_code(382));
  EXPECT_EQ(d->g_code(382)->action, Action::Unsupported);
  ASSERT_TRUE(d->g_code(10));
  EXPECT_EQ(d->g_code(10)->action, Action::Linear);
  EXPECT_EQ(d->g_code(591)->index, 7);  // G59.1
  ASSERT_TRUE(d->m_code(30));
  EXPECT_EQ(d->m_code(30)->action, Action::ProgramEnd);
  EXPECT_FALSE(d->g_code(9999));
  EXPECT_FALSE(d->m_code(5000));
  EXPECT_EQ(d->word("X"), letter_word('X'));
  EXPECT_EQ(d->parameters.style, ParameterStyle::Hash);
  EXPECT_TRUE(d->parameters.named);
  // Longest operator spelling first: "**" is tried before "*".
  ASSERT_FALSE(d->expressions.operators.empty());
  EXPECT_EQ(d->expressions.operators.front().spelling.size(), 3u);
}

TEST(DialectTest, NotJson) {
  const auto r = load_dialect("{not json");
  EXPECT_FALSE(r.dialect);
  ASSERT_EQ(r.diagnostics.size(), 1u);
  EXPECT_EQ(r.diagnostics[0].code, diag::Code::GcodeDialectJson);
}

TEST(DialectTest, ErrorsNameTheJsonPath) {
  json d = valid();
  d["codes"]["G0"]["action"] = "teleport";
  const auto r = load_dialect(d.dump());
  ASSERT_FALSE(r.dialect);
  ASSERT_FALSE(r.diagnostics.empty());
  EXPECT_EQ(r.diagnostics[0].code, diag::Code::GcodeDialectInvalid);
  EXPECT_NE(r.diagnostics[0].message.find("/codes/G0/action"), std::string::npos)
      << r.diagnostics[0].message;
}

TEST(DialectTest, CrossReferencesAreChecked) {
  json a = valid();
  a["codes"]["G0"]["group"] = "no-such-group";
  EXPECT_FALSE(accepts(a));
  json b = valid();
  b["codes"]["G4"]["requires"] = json::array({"Ö"});
  EXPECT_FALSE(accepts(b));
  json c = valid();
  c["arcs"]["radius_word"] = "V";  // not a word of the dialect
  EXPECT_FALSE(accepts(c));
  json e = valid();
  e["program"]["initial_motion"] = "G4";  // not a motion
  EXPECT_FALSE(accepts(e));
  json f = valid();
  f["codes"]["G00"] = f["codes"]["G0"];  // G00 is G0 again
  EXPECT_FALSE(accepts(f));
}

// The examples schema_check.py (ctest gcode_dialect_schema_jsonschema) checks the schema
// refuses too.
TEST(DialectTest, SharedInvalidExamples) {
  const json examples = json::parse(ncpost::test::read_file(
      ncpost::test::source_dir() / "tests" / "unit" / "gcode" / "invalid_examples.json"));
  ASSERT_GE(examples.size(), 20u);
  for (const auto& example : examples) {
    json doc = valid();
    const json set = example.value("set", json::object());
    const json remove = example.value("remove", json::array());
    for (const auto& [path, value] : set.items()) doc[json::json_pointer(path)] = value;
    for (const auto& path : remove) {
      const json::json_pointer ptr(path.get<std::string>());
      doc[ptr.parent_pointer()].erase(ptr.back());
    }
    EXPECT_FALSE(accepts(doc)) << example["name"];
  }
}

// Walks the schema alongside the valid document: drop each required field, add an unknown one,
// leave each enumeration, pattern, constant and bound, give a value of another type. The C++
// validation must refuse every one. Maps (codes, words, functions) are walked on a few entries.
void mutations(const json& schema, const json& root, json& doc, json& node, const std::string& path,
               int& count) {
  const json* s = &schema;
  if (s->contains("$ref")) {
    const std::string ref = (*s)["$ref"].get<std::string>();
    s = &root["$defs"][ref.substr(ref.rfind('/') + 1)];
  }
  auto check = [&](const std::string& what) {
    EXPECT_FALSE(load_dialect(doc.dump()).dialect) << path << ": " << what;
    ++count;
  };
  auto replaced = [&](const json& value, const std::string& what) {
    const json saved = node;
    node = value;
    check(what);
    node = saved;
  };
  if (s->contains("enum")) replaced("not-in-the-enum", "enum");
  if (s->contains("const")) replaced("not-the-const", "const");
  if (s->contains("pattern") && node.is_string()) replaced("bad value!", "pattern");
  const std::string type = s->value("type", "");
  if (type == "integer" || type == "number") {
    if (s->contains("minimum"))
      replaced(type == "integer" ? json((*s)["minimum"].get<long long>() - 1)
                                 : json((*s)["minimum"].get<double>() - 1),
               "minimum");
    if (s->contains("exclusiveMinimum")) replaced((*s)["exclusiveMinimum"], "exclusiveMinimum");
    if (s->contains("maximum"))
      replaced(type == "integer" ? json((*s)["maximum"].get<long long>() + 1)
                                 : json((*s)["maximum"].get<double>() * 2 + 1),
               "maximum");
    replaced("text", "type");
  } else if (type == "boolean" || type == "array") {
    replaced("text", "type");
    if (type == "array" && node.is_array() && !node.empty()) {
      if (s->contains("items") && (*s)["items"].is_object())
        mutations((*s)["items"], root, doc, node[0], path + "/0", count);
      if (s->contains("prefixItems"))
        for (std::size_t i = 0; i < (*s)["prefixItems"].size() && i < node.size(); ++i)
          mutations((*s)["prefixItems"][i], root, doc, node[i], path + "/" + std::to_string(i),
                    count);
    }
  } else if (type == "object") {
    replaced("text", "type");
    for (const auto& r : s->value("required", json::array())) {
      const std::string key = r.get<std::string>();
      if (!node.contains(key)) continue;
      const json saved = node[key];
      node.erase(key);
      check("required " + key);
      node[key] = saved;
    }
    if (s->value("additionalProperties", json(true)) == json(false)) {
      node["unknown_field"] = 1;
      check("additionalProperties");
      node.erase("unknown_field");
    }
    if (s->contains("properties")) {
      for (const auto& [key, sub] : (*s)["properties"].items()) {
        if (key == "$schema" || !node.contains(key)) continue;
        mutations(sub, root, doc, node[key], path + "/" + key, count);
      }
    }
    const json additional = s->value("additionalProperties", json(true));
    if (additional.is_object()) {
      int walked = 0;
      for (auto it = node.begin(); it != node.end() && walked < 3; ++it, ++walked) {
        if (s->contains("properties") && (*s)["properties"].contains(it.key())) continue;
        mutations(additional, root, doc, it.value(), path + "/" + it.key(), count);
      }
    }
  }
}

TEST(DialectTest, SchemaAndValidationAgree) {
  const json schema = json::parse(ncpost::test::read_file(stylesheets() / "dialect.schema.json"));
  json doc = valid();
  int count = 0;
  mutations(schema, schema, doc, doc, "", count);
  EXPECT_GT(count, 120);
  EXPECT_TRUE(accepts(doc));  // restored
}

}  // namespace
}  // namespace ncpost::gcode
