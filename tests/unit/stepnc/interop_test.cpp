// Programs from other systems (docs/interoperability.md): the variants table, the attribute
// reader's two modes, the schema names it accepts, the units cross-check and the geometry of a
// through hole's implicit depth, each without a job.

#include <gtest/gtest.h>

#include <string>

#include "features/implicit.hpp"
#include "ncpost/express/registry.hpp"
#include "ncpost/p21/reader.hpp"
#include "ncpost/stepnc/attributes.hpp"
#include "ncpost/stepnc/variants.hpp"
#include "units.hpp"

namespace ncpost::stepnc {
namespace {

const express::SchemaRegistry& registry() {
  static const express::SchemaRegistry r;
  return r;
}

const express::SchemaSet& iso14649() {
  return registry().builtin().set();
}

std::string program(std::string_view schema, std::string_view data) {
  return "ISO-10303-21;\nHEADER;\nFILE_DESCRIPTION((''),'2;1');\nFILE_NAME('t','',(''),(''),'','','"
         "');\n"
         "FILE_SCHEMA(('" +
         std::string(schema) + "'));\nENDSEC;\nDATA;\n" + std::string(data) +
         "ENDSEC;\nEND-ISO-10303-21;\n";
}

// ---- the table ----

TEST(Variants, EveryRowSaysWhereItComesFromAndWhatItAssumes) {
  ASSERT_FALSE(variants().empty());
  for (const Variant& v : variants()) {
    SCOPED_TRACE(std::string(v.written));
    EXPECT_FALSE(v.source.empty());
    EXPECT_FALSE(v.assumption.empty());
    EXPECT_EQ(find_variant(v.kind, v.written), &v);
    switch (v.kind) {
      case Variant::Kind::EntityAlias:
        // An alias is a name the schema does not declare, read as one it does.
        EXPECT_EQ(iso14649().find_entity(v.written), nullptr);
        EXPECT_NE(iso14649().find_entity(v.read_as), nullptr);
        break;
      case Variant::Kind::Supertype: {
        const express::Entity* written = iso14649().find_entity(v.written);
        const express::Entity* read_as = iso14649().find_entity(v.read_as);
        ASSERT_NE(written, nullptr);
        ASSERT_NE(read_as, nullptr);
        EXPECT_TRUE(written->is_abstract);
        EXPECT_FALSE(read_as->is_abstract);
        EXPECT_TRUE(iso14649().is_subtype_of(*read_as, *written));
        break;
      }
      case Variant::Kind::SchemaName:
        EXPECT_EQ(registry().find(v.written), nullptr);
        EXPECT_EQ(registry().find(v.read_as), &registry().builtin());
        break;
    }
  }
}

TEST(Variants, NamesAreFoundInAnyCaseAndStrictHasNone) {
  EXPECT_NE(find_variant(Variant::Kind::EntityAlias, "TOOL_DIMENSION"), nullptr);
  EXPECT_NE(find_variant(Variant::Kind::SchemaName, "COMBINED_SCHEMA { 1 0 14649 }"), nullptr);
  EXPECT_EQ(find_variant(Variant::Kind::SchemaName, "TOOL_DIMENSION"), nullptr);
  EXPECT_EQ(find_variant(Variant::Kind::EntityAlias, "TOOL_DIMENSIONS"), nullptr);
  EXPECT_FALSE(entity_aliases(Mode::Tolerant).empty());
  EXPECT_FALSE(schema_aliases(Mode::Tolerant).empty());
  EXPECT_TRUE(entity_aliases(Mode::Strict).empty());
  EXPECT_TRUE(schema_aliases(Mode::Strict).empty());
}

// ---- the attribute reader ----

TEST(Variants, ToleratedReaderReadsAToolDimensionAsAMillingOne) {
  const auto read = p21::read(program("MACHINING_SCHEMA",
                                      "#1=TOOL_DIMENSION(12.5,59.,$,30.,$,$,$);\n"
                                      "#2=CUTTING_TOOL('T1',#3,(),80.);\n"
                                      "#3=ENDMILL(#1,4,.RIGHT.,.F.,$);\n"));
  ASSERT_TRUE(read.ok());
  const p21::Instance& dimension = *read.model.find(1);
  const p21::Instance& tool = *read.model.find(2);
  const AttributeReader tolerant(read.model, iso14649(), Mode::Tolerant);
  const auto diameter = tolerant.get(dimension, "diameter");
  ASSERT_TRUE(diameter);
  EXPECT_DOUBLE_EQ(read.model.as_real(*diameter), 12.5);
  EXPECT_TRUE(tolerant.is_a(dimension, "milling_tool_dimension"));
  ASSERT_NE(tolerant.variant(dimension), nullptr);
  EXPECT_EQ(tolerant.variant(dimension)->read_as, "milling_tool_dimension");
  ASSERT_NE(tolerant.variant(tool), nullptr);
  EXPECT_EQ(tolerant.variant(tool)->read_as, "milling_cutting_tool");
  EXPECT_TRUE(tolerant.get(tool, "its_tool_body"));
  EXPECT_EQ(tolerant.variant(*read.model.find(3)), nullptr);  // ENDMILL is ISO 14649's own

  const AttributeReader strict(read.model, iso14649(), Mode::Strict);
  EXPECT_FALSE(strict.get(dimension, "diameter"));
  EXPECT_FALSE(strict.is_a(dimension, "milling_tool_dimension"));
  EXPECT_EQ(strict.variant(dimension), nullptr);
  EXPECT_EQ(strict.variant(tool), nullptr);
  EXPECT_TRUE(strict.get(tool, "its_tool_body"));  // read as the CUTTING_TOOL it is
}

TEST(Variants, CombinedSchemaIsReadAsIso14649AndChecked) {
  const auto read = p21::read(program("COMBINED_SCHEMA", "#1=CARTESIAN_POINT('',(0.,0.,0.));\n"));
  ASSERT_TRUE(read.ok());
  const auto tolerant = registry().select_or_builtin(read.model, schema_aliases(Mode::Tolerant));
  EXPECT_EQ(tolerant.source, &registry().builtin());
  EXPECT_FALSE(tolerant.fallback);
  ASSERT_EQ(tolerant.diagnostics.size(), 1u);
  EXPECT_EQ(tolerant.diagnostics[0].code, diag::Code::InteropSchemaName);
  EXPECT_NE(tolerant.diagnostics[0].message.find("'COMBINED_SCHEMA'"), std::string::npos);

  const auto strict = registry().select_or_builtin(read.model, schema_aliases(Mode::Strict));
  EXPECT_TRUE(strict.fallback);
  ASSERT_EQ(strict.diagnostics.size(), 2u);
  EXPECT_EQ(strict.diagnostics[0].code, diag::Code::ExpNoSchemaForModel);
  EXPECT_EQ(strict.diagnostics[1].code, diag::Code::ExpBuiltinFallback);
}

// ---- units ----

TEST(Units, IsoUnitsThatAgreeAreKept) {
  // 40 rev/s = 2400 rpm on a 10 mm tool: 1.2566 m/s; 0.1 mm × 2 teeth × 2400 rpm = 480 mm/min.
  const auto r = units::cross_check({-40., 1.2566, 0.008, 0.1}, {10., 2});
  EXPECT_TRUE(r.notes.empty());
  EXPECT_TRUE(r.errors.empty());
  EXPECT_DOUBLE_EQ(*r.spindle, -40.);
  EXPECT_DOUBLE_EQ(*r.feed, 0.008);
}

TEST(Units, AnRpmSpindleAgreeingWithTheCuttingSpeedIsTaken) {
  const auto r = units::cross_check({-2400., 1.2566, std::nullopt, std::nullopt}, {10., 2});
  ASSERT_EQ(r.notes.size(), 1u);
  EXPECT_TRUE(r.errors.empty());
  EXPECT_DOUBLE_EQ(*r.spindle, -40.);
  EXPECT_NE(r.notes[0].find("spindle -2400 read as rpm"), std::string::npos) << r.notes[0];
}

TEST(Units, BothPerMinuteAgreeAtAnAbsurdSpeedSoThePlausibleReadingIsTaken) {
  // 2400 "rev/s" and 75.4 "m/s" agree with each other, at 144,000 rpm: both are per minute.
  const auto r = units::cross_check({2400., 75.4, std::nullopt, std::nullopt}, {10., 2});
  EXPECT_EQ(r.notes.size(), 2u);
  EXPECT_TRUE(r.errors.empty());
  EXPECT_DOUBLE_EQ(*r.spindle, 40.);
}

TEST(Units, The138465RpmCaseIsReadAsRpm) {
  // 2307.75 written for rpm: 138,465 rpm as ISO rev/s, 72 m/s on a 10 mm drill.
  const auto r = units::cross_check({2307.75, std::nullopt, std::nullopt, std::nullopt}, {10., 2});
  ASSERT_EQ(r.notes.size(), 1u);
  EXPECT_NE(r.notes[0].find("138465 rpm"), std::string::npos) << r.notes[0];
  EXPECT_NEAR(*r.spindle, 2307.75 / 60, 1e-12);
}

TEST(Units, ValuesThatDisagreeInEveryUnitAreAnErrorNamingBoth) {
  const auto r = units::cross_check({-40., 10., std::nullopt, std::nullopt}, {10., 2});
  ASSERT_EQ(r.errors.size(), 1u);
  EXPECT_TRUE(r.notes.empty());
  EXPECT_NE(r.errors[0].find("spindle -40"), std::string::npos) << r.errors[0];
  EXPECT_NE(r.errors[0].find("cutspeed is 10"), std::string::npos) << r.errors[0];
  EXPECT_DOUBLE_EQ(*r.spindle, -40.);  // kept as written: the error stops the job
}

TEST(Units, AFeedInMmPerMinuteAgreeingWithFeedPerToothIsTaken) {
  const auto r = units::cross_check({-40., std::nullopt, 480., 0.1}, {10., 2});
  ASSERT_EQ(r.notes.size(), 1u);
  EXPECT_NE(r.notes[0].find("read as mm/min"), std::string::npos) << r.notes[0];
  EXPECT_DOUBLE_EQ(*r.feed, 0.008);
  const auto wrong = units::cross_check({-40., std::nullopt, 0.5, 0.1}, {10., 2});
  ASSERT_EQ(wrong.errors.size(), 1u);
  EXPECT_NE(wrong.errors[0].find("feedrate_per_tooth 0.1"), std::string::npos);
}

TEST(Units, AFeedOnItsOwnIsJudgedByItsSize) {
  EXPECT_TRUE(
      units::cross_check({std::nullopt, std::nullopt, 0.01, std::nullopt}, {}).notes.empty());
  const auto r = units::cross_check({std::nullopt, std::nullopt, 600., std::nullopt}, {});
  ASSERT_EQ(r.notes.size(), 1u);
  EXPECT_DOUBLE_EQ(*r.feed, 0.01);
  EXPECT_EQ(units::cross_check({std::nullopt, std::nullopt, 1e-9, std::nullopt}, {}).errors.size(),
            1u);
}

TEST(Units, NothingToCheckAgainstChangesNothing) {
  // No diameter: a spindle speed cannot be judged.
  const auto r = units::cross_check({2307.75, std::nullopt, std::nullopt, std::nullopt}, {});
  EXPECT_TRUE(r.notes.empty());
  EXPECT_TRUE(r.errors.empty());
  EXPECT_DOUBLE_EQ(*r.spindle, 2307.75);
}

// ---- a through hole's depth ----

TEST(ImplicitDepth, WhereTheAxisLeavesTheWorkpiece) {
  detail::Frame block;
  block.origin = {0, 0, -20};
  const detail::Vec3 size{100, 80, 20};
  EXPECT_NEAR(*features::exit_distance(block, size, {85, 12, 0}, {0, 0, -1}), 20, 1e-12);
  // From above the block, the distance runs to where the axis leaves it, not where it enters.
  EXPECT_NEAR(*features::exit_distance(block, size, {10, 10, 5}, {0, 0, -1}), 25, 1e-12);
  // Beside the block, or leaving it behind the start: no depth.
  EXPECT_FALSE(features::exit_distance(block, size, {120, 10, 0}, {0, 0, -1}));
  EXPECT_FALSE(features::exit_distance(block, size, {10, 10, -30}, {0, 0, -1}));
  // Slanted 45° in xz from the top: leaves through the bottom after 20·√2.
  const double s = std::sqrt(0.5);
  EXPECT_NEAR(*features::exit_distance(block, size, {50, 40, 0}, {s, 0, -s}), 20 * std::sqrt(2.),
              1e-9);
  // A rotated block (its x along the parent's y).
  detail::Frame turned;
  turned.origin = {0, 0, -10};
  turned.x = {0, 1, 0};
  turned.y = {-1, 0, 0};
  EXPECT_NEAR(*features::exit_distance(turned, {50, 30, 10}, {-5, 5, 0}, {0, 0, -1}), 10, 1e-12);
}

}  // namespace
}  // namespace ncpost::stepnc
