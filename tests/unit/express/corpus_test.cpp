// The real schemas of the shared corpus: ISO 14649 combined schema, AP238 AIM long form and the
// STEPcode unit schemas. All must parse without errors, quickly, with the attribute layout that
// real P21 files use.

#include "corpus.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <string>
#include <vector>

#include "test_support.hpp"

namespace ncpost::express {
namespace {

namespace fs = std::filesystem;
using Strings = std::vector<std::string>;

constexpr std::string_view kCombined =
    "express/michaloski_STEPNCpp_combined_schema_14649-10-11-12-111-121.exp";
constexpr std::string_view kAp238 = "express/stepcode_ap238-aim-long_integrated_cnc_schema.exp";

std::vector<fs::path> express_files(const fs::path& corpus) {
  std::vector<fs::path> files;
  for (const char* folder : {"express", "p21-syntax"}) {
    if (!fs::is_directory(corpus / folder)) continue;
    for (const auto& entry : fs::directory_iterator(corpus / folder))
      if (entry.path().extension() == ".exp") files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end());
  return files;
}

ParseResult parse_file(const fs::path& path) {
  return parse_express(::ncpost::test::read_file(path));
}

std::vector<diag::Diagnostic> errors_of(const ParseResult& result) {
  std::vector<diag::Diagnostic> errors;
  for (const auto& d : result.diagnostics)
    if (d.severity == diag::Severity::Error) errors.push_back(d);
  return errors;
}

TEST(express_corpus, EveryExpressFileParsesWithoutErrors) {
  NCPOST_REQUIRE_CORPUS_OR_SKIP(corpus);
  const std::vector<fs::path> files = express_files(corpus);
  ASSERT_GE(files.size(), 6u) << "expected the 2 express/ and 4 p21-syntax/ schemas";
  for (const fs::path& file : files) {
    const ParseResult result = parse_file(file);
    EXPECT_TRUE(errors_of(result).empty()) << file << "\n" << test::describe(result.diagnostics);
    ASSERT_FALSE(result.schemas.schemas().empty()) << file;
    EXPECT_FALSE(result.schemas.schemas()[0].entities.empty()) << file;
  }
}

TEST(express_corpus, DeclarationCountsMatchTheManifest) {
  NCPOST_REQUIRE_CORPUS_OR_SKIP(corpus);
  const ParseResult combined = parse_file(corpus / kCombined);
  ASSERT_EQ(combined.schemas.schemas().size(), 1u);
  EXPECT_EQ(combined.schemas.schemas()[0].name, "combined_schema");
  EXPECT_EQ(combined.schemas.schemas()[0].entities.size(), 495u);
  EXPECT_EQ(combined.schemas.schemas()[0].types.size(), 73u);
  const ParseResult ap238 = parse_file(corpus / kAp238);
  EXPECT_EQ(ap238.schemas.schemas()[0].name, "integrated_cnc_schema");
  EXPECT_EQ(ap238.schemas.schemas()[0].entities.size(), 481u);
  EXPECT_EQ(ap238.schemas.schemas()[0].types.size(), 92u);
  EXPECT_TRUE(ap238.diagnostics.empty()) << test::describe(ap238.diagnostics);
}

// The combined schema has real defects; they are warnings because they do not change how any
// instance is laid out. Pinning them here documents them and catches new ones.
TEST(express_corpus, CombinedSchemaDefectsAreTheKnownWarnings) {
  NCPOST_REQUIRE_CORPUS_OR_SKIP(corpus);
  const ParseResult result = parse_file(corpus / kCombined);
  EXPECT_EQ(test::positions(result),
            (Strings{"EXP-035@5323:31", "EXP-035@5323:43", "EXP-035@5323:56", "EXP-020@5585:1",
                     "EXP-020@5616:1"}));
  // bolt_holes is declared twice; the first declaration (a fixturing setup) is the one used.
  const Entity* bolt_holes = result.schemas.find_entity("bolt_holes");
  ASSERT_NE(bolt_holes, nullptr);
  EXPECT_EQ(bolt_holes->pos.line, 5446u);
  EXPECT_NE(bolt_holes->attribute("max_clamping_bolt_dia"), nullptr);
}

TEST(express_corpus, MachiningWorkingstepInTheCombinedSchema) {
  NCPOST_REQUIRE_CORPUS_OR_SKIP(corpus);
  const ParseResult result = parse_file(corpus / kCombined);
  const Entity* ws = result.schemas.find_entity("MACHINING_WORKINGSTEP");
  ASSERT_NE(ws, nullptr);
  EXPECT_EQ(test::attribute_names(*ws),
            (Strings{"its_id", "its_secplane", "its_feature", "its_operation", "its_effect"}));
  EXPECT_EQ(test::owners(*ws), (Strings{"executable", "workingstep", "machining_workingstep",
                                        "machining_workingstep", "machining_workingstep"}));
  EXPECT_EQ(ws->attribute_index("its_operation"), 3u);
  EXPECT_TRUE(ws->attribute("its_effect")->optional);
  EXPECT_FALSE(ws->attribute("its_feature")->optional);
  EXPECT_EQ(ws->attribute("its_operation")->type.name, "machining_operation");
  EXPECT_TRUE(result.schemas.is_subtype_of("machining_workingstep", "executable"));
  EXPECT_TRUE(result.schemas.find_entity("workingstep")->is_abstract);
}

TEST(express_corpus, CartesianPointInTheAp238LongForm) {
  NCPOST_REQUIRE_CORPUS_OR_SKIP(corpus);
  const ParseResult result = parse_file(corpus / kAp238);
  const SchemaSet& set = result.schemas;
  const Entity* point = set.find_entity("cartesian_point");
  ASSERT_NE(point, nullptr);
  EXPECT_EQ(test::attribute_names(*point), (Strings{"name", "coordinates"}));
  EXPECT_EQ(test::owners(*point), (Strings{"representation_item", "cartesian_point"}));
  EXPECT_EQ(to_express(point->attributes[1].type), "LIST [1:3] OF length_measure");
  EXPECT_EQ(set.underlying_type(*set.find_type("length_measure")).kind, TypeKind::Real);
  EXPECT_EQ(set.underlying_type(*set.find_type("label")).kind, TypeKind::String);
  EXPECT_TRUE(set.is_subtype_of("cartesian_point", "geometric_representation_item"));
}

TEST(express_corpus, Ap238OrientedEdgeDerivesItsEndsAndMultipleInheritanceWorks) {
  NCPOST_REQUIRE_CORPUS_OR_SKIP(corpus);
  const ParseResult result = parse_file(corpus / kAp238);
  // P21: ORIENTED_EDGE('',*,*,#edge,.T.)
  const Entity* oriented_edge = result.schemas.find_entity("oriented_edge");
  ASSERT_NE(oriented_edge, nullptr);
  EXPECT_EQ(test::attribute_names(*oriented_edge),
            (Strings{"name", "edge_start", "edge_end", "edge_element", "orientation"}));
  std::vector<bool> derived;
  for (const auto& a : oriented_edge->attributes) derived.push_back(a.derived_redeclared);
  EXPECT_EQ(derived, (std::vector<bool>{false, true, true, false, false}));
  // SUBTYPE OF (pcurve, bounded_curve): representation_item.name reached twice, kept once.
  const Entity* bounded_pcurve = result.schemas.find_entity("bounded_pcurve");
  ASSERT_NE(bounded_pcurve, nullptr);
  EXPECT_EQ(test::attribute_names(*bounded_pcurve),
            (Strings{"name", "basis_surface", "reference_to_curve"}));
}

TEST(express_corpus, StepcodeUnitSchemas) {
  NCPOST_REQUIRE_CORPUS_OR_SKIP(corpus);
  const ParseResult selects = parse_file(corpus / "p21-syntax/stepcode_select_segfault_2.exp");
  const SchemaSet& set = selects.schemas;
  std::vector<std::string> leaves;
  for (const DeclRef ref : set.select_leaves(*set.find_type("docd")))
    leaves.emplace_back(set.name_of(ref));
  EXPECT_EQ(leaves, (Strings{"cdl", "d"}));
  EXPECT_EQ(test::attribute_names(*set.find_entity("drc")), (Strings{"base"}));
  EXPECT_TRUE(set.is_subtype_of("drc", "sa"));

  const ParseResult bounds = parse_file(corpus / "p21-syntax/stepcode_array_bounds_expr.exp");
  const Entity* mesh = bounds.schemas.find_entity("structured_mesh");
  ASSERT_NE(mesh, nullptr);
  EXPECT_EQ(test::attribute_names(*mesh), (Strings{"description", "index_count", "vertex_counts"}));
  EXPECT_EQ(mesh->attributes[2].type.upper->text, "SELF\\mesh.index_count");

  const ParseResult inverse = parse_file(corpus / "p21-syntax/stepcode_inverse_attr.exp");
  const Entity* window = inverse.schemas.find_entity("Window");
  ASSERT_NE(window, nullptr);
  EXPECT_EQ(test::attribute_names(*window), (Strings{"objecttype", "description"}));
  const Entity* object = inverse.schemas.find_entity("object");
  ASSERT_EQ(object->inverse_attributes.size(), 1u);
  EXPECT_EQ(object->inverse_attributes[0].for_attribute, "relatedobjects");
}

TEST(express_corpus, Ap238ParsesWellUnderASecond) {
  NCPOST_REQUIRE_CORPUS_OR_SKIP(corpus);
  const std::string text = ::ncpost::test::read_file(corpus / kAp238);
  ASSERT_GT(text.size(), 600'000u);
  const auto start = std::chrono::steady_clock::now();
  const ParseResult result = parse_express(text);
  const auto elapsed = std::chrono::steady_clock::now() - start;
  EXPECT_TRUE(result.ok());
  EXPECT_LT(elapsed, std::chrono::milliseconds(1000))
      << std::chrono::duration_cast<std::chrono::milliseconds>(elapsed).count() << " ms";
}

}  // namespace
}  // namespace ncpost::express
