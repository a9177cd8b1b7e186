// schemas/ap238_aim.exp, the project's AP238 AIM subset and the built-in for
// FILE_SCHEMA(('INTEGRATED_CNC_SCHEMA')): it must parse cleanly, lay out every entity exactly as
// the AP238 AIM long form of the corpus does, check every AIM program of the corpus without a
// single diagnostic, and declare every entity the AP238 interpreter reads.

#include <gtest/gtest.h>

#include <filesystem>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "corpus.hpp"
#include "ncpost/express/parse.hpp"
#include "ncpost/express/registry.hpp"
#include "ncpost/express/schema.hpp"
#include "ncpost/express/validate.hpp"
#include "ncpost/p21/model.hpp"
#include "ncpost/p21/reader.hpp"

namespace ncpost {
namespace {

namespace fs = std::filesystem;
using Strings = std::vector<std::string>;

constexpr std::string_view kLongForm = "express/stepcode_ap238-aim-long_integrated_cnc_schema.exp";

fs::path aim_schema_path() {
  return test::source_dir() / "schemas" / "ap238_aim.exp";
}

const express::ParseResult& aim_schema() {
  static const express::ParseResult result =
      express::parse_express(test::read_file(aim_schema_path()));
  return result;
}

std::string describe(const std::vector<diag::Diagnostic>& diagnostics, std::string_view file) {
  std::string out;
  for (const auto& d : diagnostics) out += diag::format(d, file) + "\n";
  return out;
}

Strings names_of(const express::Entity& entity) {
  Strings names;
  for (const auto& a : entity.attributes) names.push_back(a.name);
  return names;
}

TEST(aim_schema, ParsesWithoutDiagnostics) {
  ASSERT_TRUE(fs::exists(aim_schema_path())) << aim_schema_path();
  const auto& result = aim_schema();
  EXPECT_TRUE(result.diagnostics.empty())
      << describe(result.diagnostics, aim_schema_path().string());
  ASSERT_EQ(result.schemas.schemas().size(), 1u);
  EXPECT_NE(result.schemas.find_schema("INTEGRATED_CNC_SCHEMA"), nullptr);
}

TEST(aim_schema, IsTheBuiltInForIntegratedCncSchema) {
  EXPECT_EQ(express::builtin_aim_schema_text(), test::read_file(aim_schema_path()))
      << "the embedded AP238 AIM schema differs from schemas/ap238_aim.exp: rebuild";
  const express::SchemaRegistry registry;
  EXPECT_EQ(registry.find("INTEGRATED_CNC_SCHEMA"), &registry.builtin_aim());
  EXPECT_EQ(registry.find("integrated_cnc_schema { 1 0 10303 238 1 0 1 }"),
            &registry.builtin_aim());
  EXPECT_TRUE(registry.builtin_aim().builtin);
  EXPECT_EQ(registry.builtin_aim().origin, "<built-in AP238 AIM>");
  EXPECT_TRUE(registry.builtin_diagnostics().empty());
  // The ISO 14649 built-in stays the one for unknown schemas.
  EXPECT_EQ(registry.find("MILLING_SCHEMA"), &registry.builtin());
}

TEST(aim_schema, AttributeLayoutOfKeyEntities) {
  const auto& set = aim_schema().schemas;
  const auto expect_layout = [&](std::string_view name, const Strings& expected) {
    const auto* entity = set.find_entity(name);
    ASSERT_NE(entity, nullptr) << name;
    EXPECT_EQ(names_of(*entity), expected) << name;
  };
  expect_layout("machining_workingstep", {"name", "description", "consequence", "purpose"});
  expect_layout("machining_process_sequence_relationship",
                {"name", "description", "relating_method", "related_method", "sequence_position"});
  expect_layout("machining_tool", {"name", "description", "usage", "kind"});
  expect_layout("action_property", {"name", "description", "definition"});
  expect_layout("measure_representation_item", {"name", "value_component", "unit_component"});
  // Two supertypes that both declare name and description: the flattened list keeps both
  // (characterized_object's, then shape_aspect's), as INSTANCED_FEATURE's six parameters show.
  expect_layout("instanced_feature",
                {"name", "description", "name", "description", "of_shape", "product_definitional"});
  expect_layout("si_unit", {"dimensions", "prefix", "name"});
  EXPECT_TRUE(set.find_entity("si_unit")->attribute("dimensions")->derived_redeclared);
}

// Every entity of the subset has the long form's flattened attributes, in its order.
TEST(aim_schema, AttributesMatchTheLongForm) {
  NCPOST_REQUIRE_CORPUS_OR_SKIP(corpus);
  const auto long_form = express::parse_express(test::read_file(corpus / kLongForm));
  ASSERT_TRUE(long_form.ok()) << describe(long_form.diagnostics, kLongForm);
  std::size_t compared = 0;
  for (const auto& schema : aim_schema().schemas.schemas()) {
    for (const auto& entity : schema.entities) {
      const auto* theirs = long_form.schemas.find_entity(entity.name);
      ASSERT_NE(theirs, nullptr) << entity.name << " is not in the AP238 AIM long form";
      EXPECT_EQ(names_of(entity), names_of(*theirs)) << entity.name;
      for (std::size_t i = 0; i < entity.attributes.size() && i < theirs->attributes.size(); ++i)
        EXPECT_EQ(entity.attributes[i].derived_redeclared, theirs->attributes[i].derived_redeclared)
            << entity.name << "." << entity.attributes[i].name;
      ++compared;
    }
  }
  EXPECT_GT(compared, 150u);
}

// The corpus's AIM programs (Next-NC's milling and turning files) check against the subset
// without a single diagnostic: every entity they use is declared, with their layouts and types.
TEST(aim_schema, CorpusProgramsValidate) {
  NCPOST_REQUIRE_CORPUS_OR_SKIP(corpus);
  std::size_t files = 0;
  for (const auto& entry : fs::directory_iterator(corpus / "p21-aim")) {
    if (entry.path().extension() != ".stpnc") continue;
    SCOPED_TRACE(entry.path().filename().string());
    const auto read = p21::read(test::read_file(entry.path()));
    ASSERT_TRUE(read.ok());
    const auto diagnostics = express::validate(read.model, aim_schema().schemas);
    EXPECT_TRUE(diagnostics.empty()) << describe(diagnostics, entry.path().filename().string());
    ++files;
  }
  EXPECT_EQ(files, 19u);
}

// What engine/ap238 reads, by name: declared, so that no look-up silently finds nothing.
TEST(aim_schema, DeclaresWhatTheInterpreterReads) {
  const auto& set = aim_schema().schemas;
  for (const char* name : {"machining_project",
                           "product_definition_formation",
                           "product_definition",
                           "process_product_association",
                           "product_definition_process",
                           "machining_workplan",
                           "machining_workingstep",
                           "machining_rapid_movement",
                           "machining_nc_function",
                           "machining_process_executable",
                           "machining_process_sequence_relationship",
                           "machining_process_body_relationship",
                           "machining_process_branch_relationship",
                           "machining_process_concurrent_relationship",
                           "machining_operation_relationship",
                           "machining_feature_relationship",
                           "machining_feature_process",
                           "property_process",
                           "process_property_association",
                           "machining_operation",
                           "milling_type_operation",
                           "turning_type_operation",
                           "machining_touch_probing",
                           "machining_toolpath",
                           "machining_toolpath_sequence_relationship",
                           "machining_technology",
                           "machining_technology_relationship",
                           "machining_functions",
                           "machining_functions_relationship",
                           "machining_tool",
                           "action_property",
                           "action_property_representation",
                           "resource_property",
                           "resource_property_representation",
                           "representation",
                           "representation_relationship",
                           "measure_representation_item",
                           "descriptive_representation_item",
                           "global_unit_assigned_context",
                           "named_unit",
                           "si_unit",
                           "conversion_based_unit",
                           "context_dependent_unit",
                           "derived_unit",
                           "derived_unit_element",
                           "measure_with_unit",
                           "property_definition",
                           "property_definition_representation",
                           "shape_representation",
                           "shape_aspect",
                           "machining_setup",
                           "machining_setup_workpiece_relationship",
                           "context_dependent_shape_representation",
                           "representation_relationship_with_transformation",
                           "item_defined_transformation",
                           "axis2_placement_3d",
                           "elementary_surface",
                           "polyline",
                           "trimmed_curve",
                           "composite_curve",
                           "b_spline_curve_with_knots",
                           "rational_b_spline_curve"}) {
    EXPECT_NE(set.find_entity(name), nullptr) << name;
  }
}

}  // namespace
}  // namespace ncpost
