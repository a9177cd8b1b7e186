// SchemaRegistry: the embedded built-in schema, schema directories, and the choice of a schema
// from a model's FILE_SCHEMA header.

#include "ncpost/express/registry.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <fstream>
#include <thread>

#include "corpus.hpp"
#include "ncpost/p21/reader.hpp"
#include "test_support.hpp"

namespace ncpost::express {
namespace {

namespace fs = std::filesystem;
using Strings = std::vector<std::string>;

p21::Model model_with_schemas(const std::string& file_schema) {
  p21::ReadResult read = p21::read(
      "ISO-10303-21;HEADER;FILE_DESCRIPTION((''),'2;1');FILE_NAME('','',(''),(''),'','','');"
      "FILE_SCHEMA((" +
      file_schema + "));ENDSEC;DATA;#1=FOO(1);ENDSEC;END-ISO-10303-21;");
  EXPECT_TRUE(read.ok()) << test::describe(read.diagnostics);
  return std::move(read.model);
}

Strings messages(const std::vector<diag::Diagnostic>& diagnostics) {
  Strings out;
  for (const auto& d : diagnostics) out.push_back(std::string(d.code_id()) + " " + d.message);
  return out;
}

// A fresh directory under the build tree, removed at the end of the test.
class TempDir {
 public:
  explicit TempDir(const std::string& name)
      : path_(fs::temp_directory_path() /
              ("ncpost_registry_" + name + "_" +
               std::to_string(::testing::UnitTest::GetInstance()->random_seed()))) {
    fs::remove_all(path_);
    fs::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ignored;
    fs::remove_all(path_, ignored);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  [[nodiscard]] const fs::path& path() const { return path_; }
  void write(const std::string& name, const std::string& text) const {
    std::ofstream(path_ / name, std::ios::binary) << text;
  }

 private:
  fs::path path_;
};

// ---------------------------------------------------------------------------------------------
// The built-in.

TEST(express_registry, BuiltinIsTheProjectSchemaEmbeddedAtBuildTime) {
  ASSERT_FALSE(builtin_schema_text().empty())
      << "the built-in schema is empty: schemas/iso14649.exp did not exist when this build was "
         "configured; re-run cmake";
  // Exactly the file's bytes: the build re-embeds it whenever it changes.
  const fs::path file = ncpost::test::source_dir() / "schemas/iso14649.exp";
  ASSERT_TRUE(fs::exists(file)) << file;
  EXPECT_EQ(builtin_schema_text(), ncpost::test::read_file(file))
      << "the embedded schema differs from schemas/iso14649.exp: rebuild";
  const SchemaRegistry registry;
  EXPECT_EQ(messages(registry.builtin_diagnostics()), Strings{});
  EXPECT_TRUE(registry.builtin().builtin);
  EXPECT_EQ(registry.builtin().origin, "<built-in>");
  EXPECT_NE(registry.builtin().set().find_entity("machining_workingstep"), nullptr);
  // Parsed once per process.
  EXPECT_EQ(builtin_schema().get(), builtin_schema().get());
  EXPECT_EQ(registry.known_names(),
            (Strings{"integrated_cnc_schema", "machining_schema", "milling_schema"}));
}

TEST(express_registry, Iso14649ProgramsSelectTheBuiltin) {
  const SchemaRegistry registry;
  const auto selection =
      registry.select_for(model_with_schemas("'MACHINING_SCHEMA','MILLING_SCHEMA'"));
  EXPECT_EQ(selection.source, &registry.builtin());
  EXPECT_EQ(messages(selection.diagnostics), Strings{});
  EXPECT_EQ(registry.find("milling_schema"), &registry.builtin());
  EXPECT_EQ(registry.find("Machining_Schema"), &registry.builtin());
}

// ---------------------------------------------------------------------------------------------
// Names in FILE_SCHEMA.

TEST(express_registry, NamesLoseTheirObjectIdentifier) {
  EXPECT_EQ(SchemaRegistry::normalise_name("AUTOMOTIVE_DESIGN { 1 0 10303 214 1 1 1 1 }"),
            "automotive_design");
  EXPECT_EQ(SchemaRegistry::normalise_name("CONFIG_CONTROL_DESIGN{1 0 10303 203}"),
            "config_control_design");
  EXPECT_EQ(SchemaRegistry::normalise_name("  IFC4 "), "ifc4");
  EXPECT_EQ(SchemaRegistry::normalise_name(""), "");
}

TEST(express_registry, UnknownSchemaIsNamedWithTheKnownOnes) {
  const SchemaRegistry registry;
  const auto model = model_with_schemas("'AUTOMOTIVE_DESIGN { 1 0 10303 214 1 1 1 1 }'");
  const auto selection = registry.select_for(model);
  EXPECT_EQ(selection.source, nullptr);
  EXPECT_EQ(messages(selection.diagnostics),
            (Strings{"EXP-050 no schema for FILE_SCHEMA 'AUTOMOTIVE_DESIGN { 1 0 10303 214 1 1 1 "
                     "1 }'; known: integrated_cnc_schema, machining_schema, milling_schema"}));
  const auto fallback = registry.select_or_builtin(model);
  EXPECT_EQ(fallback.source, &registry.builtin());
  EXPECT_EQ(messages(fallback.diagnostics),
            (Strings{"EXP-050 no schema for FILE_SCHEMA 'AUTOMOTIVE_DESIGN { 1 0 10303 214 1 1 1 "
                     "1 }'; known: integrated_cnc_schema, machining_schema, milling_schema",
                     "EXP-052 no schema for the file's FILE_SCHEMA; the built-in ISO 14649 schema "
                     "is used to read it, and the file is not checked against a schema"}));
  EXPECT_EQ(fallback.diagnostics.back().severity, diag::Severity::Note);
  EXPECT_TRUE(fallback.fallback);
  EXPECT_EQ(fallback.diagnostics.front().line, 1u);
  EXPECT_FALSE(registry.select_or_builtin(model_with_schemas("'MILLING_SCHEMA'")).fallback);
}

TEST(express_registry, EmptyFileSchema) {
  const SchemaRegistry registry;
  const auto selection = registry.select_for(model_with_schemas(""));
  EXPECT_EQ(selection.source, nullptr);
  EXPECT_EQ(messages(selection.diagnostics),
            (Strings{"EXP-050 the file names no schema in FILE_SCHEMA; known: "
                     "integrated_cnc_schema, machining_schema, milling_schema"}));
}

TEST(express_registry, AKnownNameWinsAndTheOthersAreReported) {
  const SchemaRegistry registry;
  const auto selection = registry.select_for(model_with_schemas("'OTHER','MILLING_SCHEMA'"));
  EXPECT_EQ(selection.source, &registry.builtin());
  EXPECT_EQ(messages(selection.diagnostics),
            (Strings{"EXP-050 no schema for FILE_SCHEMA 'OTHER'; known: "
                     "integrated_cnc_schema, machining_schema, milling_schema"}));
}

// ---------------------------------------------------------------------------------------------
// --schemas DIR

TEST(express_registry, DirectoryOfSchemas) {
  const TempDir dir("dir");
  dir.write("a_geometry.exp",
            "SCHEMA example_geometry; ENTITY pt; x : REAL; END_ENTITY; END_SCHEMA;");
  dir.write("b_broken.EXP",
            "SCHEMA broken; ENTITY e SUBTYPE OF (nothing); END_ENTITY; END_SCHEMA;");
  dir.write("c_clash.exp",
            "SCHEMA Example_Geometry; ENTITY other; END_ENTITY; END_SCHEMA;\n"
            "SCHEMA second; ENTITY s; END_ENTITY; END_SCHEMA;");
  dir.write("notes.txt", "not a schema");
  fs::create_directories(dir.path() / "sub.exp");  // a directory, not a file: skipped

  SchemaCache cache;
  SchemaRegistry registry;
  const auto reports = registry.add_directory(dir.path(), cache);
  ASSERT_EQ(reports.size(), 2u);
  EXPECT_EQ(reports[0].file.filename(), "b_broken.EXP");
  EXPECT_EQ(messages(reports[0].diagnostics),
            (Strings{"EXP-030 ENTITY e: supertype nothing is not declared",
                     "EXP-053 '" + (dir.path() / "b_broken.EXP").string() +
                         "' has errors; none of its schemas is registered"}));
  EXPECT_EQ(reports[1].file.filename(), "c_clash.exp");
  ASSERT_EQ(reports[1].diagnostics.size(), 1u);
  EXPECT_EQ(reports[1].diagnostics[0].code_id(), "EXP-051");
  EXPECT_EQ(reports[1].diagnostics[0].line, 1u);
  EXPECT_EQ(reports[1].diagnostics[0].severity, diag::Severity::Warning);

  EXPECT_EQ(registry.known_names(), (Strings{"example_geometry", "integrated_cnc_schema",
                                             "machining_schema", "milling_schema", "second"}));
  const SchemaSource* geometry = registry.find("EXAMPLE_GEOMETRY");
  ASSERT_NE(geometry, nullptr);
  EXPECT_EQ(fs::path(geometry->origin).filename(), "a_geometry.exp");
  EXPECT_NE(geometry->set().find_entity("pt"), nullptr);
  EXPECT_EQ(fs::path(registry.find("second")->origin).filename(), "c_clash.exp");
  EXPECT_EQ(registry.find("broken"), nullptr);
  EXPECT_EQ(cache.parse_count(), 3u);  // each file parsed once

  // A model naming schemas of two different sources uses the first and says so.
  const auto selection = registry.select_for(model_with_schemas("'EXAMPLE_GEOMETRY','SECOND'"));
  EXPECT_EQ(selection.source, geometry);
  ASSERT_EQ(selection.diagnostics.size(), 1u);
  EXPECT_EQ(selection.diagnostics[0].code_id(), "EXP-050");

  // Adding the same directory again parses nothing again.
  SchemaRegistry again;
  (void)again.add_directory(dir.path(), cache);
  EXPECT_EQ(cache.parse_count(), 3u);
}

TEST(express_registry, DirectorySchemasTakePrecedenceOverTheBuiltin) {
  const TempDir dir("override");
  dir.write("mine.exp",
            "SCHEMA machining_schema; ENTITY project; its_id : STRING; END_ENTITY; END_SCHEMA;");
  SchemaCache cache;
  SchemaRegistry registry;
  EXPECT_TRUE(registry.add_directory(dir.path(), cache).empty());
  const SchemaSource* source = registry.find("MACHINING_SCHEMA");
  ASSERT_NE(source, nullptr);
  EXPECT_FALSE(source->builtin);
  EXPECT_EQ(registry.find("MILLING_SCHEMA"), &registry.builtin());
}

TEST(express_registry, MissingDirectoryIsAnIoError) {
  SchemaRegistry registry;
  const auto reports = registry.add_directory("/nonexistent/ncpost/schemas");
  ASSERT_EQ(reports.size(), 1u);
  ASSERT_EQ(reports[0].diagnostics.size(), 1u);
  EXPECT_EQ(reports[0].diagnostics[0].code_id(), "IO-001");
  EXPECT_EQ(registry.known_names(),
            (Strings{"integrated_cnc_schema", "machining_schema", "milling_schema"}));
}

TEST(express_registry, CorpusSchemasDirectory) {
  NCPOST_REQUIRE_CORPUS_OR_SKIP(corpus);
  SchemaCache cache;
  SchemaRegistry registry;
  const auto reports = registry.add_directory(corpus / "express", cache);
  // The combined ISO 14649 schema has two known warnings (see docs/express.md); no errors.
  for (const auto& report : reports)
    for (const auto& d : report.diagnostics)
      EXPECT_NE(d.severity, diag::Severity::Error) << diag::format(d, report.file.string());
  EXPECT_NE(registry.find("INTEGRATED_CNC_SCHEMA"), nullptr);
  EXPECT_NE(registry.find("combined_schema"), nullptr);
  p21::ReadResult read =
      p21::read(ncpost::test::read_file(corpus / "p21/efrainrodriguez_exp2.stpnc"));
  const auto selection = registry.select_for(read.model);
  ASSERT_NE(selection.source, nullptr);
  EXPECT_EQ(fs::path(selection.source->origin).filename(),
            "stepcode_ap238-aim-long_integrated_cnc_schema.exp");
}

TEST(express_registry, ConcurrentReads) {
  const SchemaRegistry registry;
  const auto model = model_with_schemas("'MACHINING_SCHEMA','MILLING_SCHEMA'");
  std::atomic<int> found{0};
  std::vector<std::thread> threads;
  for (int t = 0; t < 8; ++t)
    threads.emplace_back([&] {
      for (int i = 0; i < 200; ++i)
        if (registry.select_for(model).source == &registry.builtin()) ++found;
    });
  for (auto& thread : threads) thread.join();
  EXPECT_EQ(found.load(), 8 * 200);
}

}  // namespace
}  // namespace ncpost::express
