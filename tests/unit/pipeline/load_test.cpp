// pipeline::load: an upload read while it arrived (p21::StreamReader) loads to the same model and
// diagnostics as the whole text; input that is not P21 goes the ordinary way; a cancel flag
// stops loading with `cancelled` and no verdict.

#include "ncpost/pipeline/load.hpp"

#include <gtest/gtest.h>

#include "corpus.hpp"
#include "ncpost/express/registry.hpp"
#include "ncpost/p21/compare.hpp"
#include "ncpost/p21/stream_reader.hpp"

namespace ncpost::pipeline {
namespace {

const express::SchemaRegistry& registry() {
  static const express::SchemaRegistry r;
  return r;
}

std::string trace_case(const std::string& name) {
  return test::read_file(test::source_dir() / "tests/golden/trace/cases" / (name + ".stp"));
}

std::string report(const LoadedModel& m) {
  std::string out;
  for (const auto& d : m.diagnostics) out += diag::format(d, "f") + "\n";
  return out;
}

LoadedModel load_streamed(const std::string& text, std::size_t piece, const LoadOptions& options) {
  p21::StreamReader reader(text.size());
  for (std::size_t at = 0; at < text.size(); at += piece) {
    EXPECT_TRUE(reader.append(std::string_view(text).substr(at, piece)));
    reader.read_more(reader.appended());
  }
  return load(reader, registry(), options);
}

TEST(LoadStreamed, SameModelAndDiagnosticsAsTheWholeText) {
  for (const char* name : {"curves", "errors", "executables"}) {
    SCOPED_TRACE(name);
    const std::string text = trace_case(name);
    const LoadedModel whole = load(text, registry());
    const LoadedModel streamed = load_streamed(text, 97, {});
    EXPECT_EQ(streamed.format, InputFormat::P21);
    EXPECT_EQ(report(streamed), report(whole));
    EXPECT_EQ(streamed.schema, whole.schema);
    EXPECT_EQ(streamed.ok(), whole.ok());
    EXPECT_FALSE(p21::first_difference(streamed.model, whole.model).has_value());
  }
}

TEST(LoadStreamed, SchemaErrorsAreFoundAsWithTheWholeText) {
  // Valid P21, but not valid against the schema: the check runs after the streamed read too.
  std::string text = trace_case("curves");
  const auto at = text.find("CARTESIAN_POINT(");
  ASSERT_NE(at, std::string::npos);
  text.replace(at, 16, "CARTESIAN_POINT('x',");
  const LoadedModel whole = load(text, registry());
  ASSERT_FALSE(whole.ok());
  const LoadedModel streamed = load_streamed(text, 64, {});
  EXPECT_FALSE(streamed.ok());
  EXPECT_EQ(report(streamed), report(whole));
}

TEST(LoadStreamed, XmlIsTakenBackAndLoadedAsP28) {
  NCPOST_REQUIRE_CORPUS_OR_SKIP(corpus);
  const std::string text = test::read_file(corpus / "p28" / "xbim_4walls1floorSite.ifcxml");
  const LoadedModel whole = load(text, registry(), false);
  LoadOptions options;
  options.validate = false;
  const LoadedModel streamed = load_streamed(text, 1000, options);
  EXPECT_EQ(streamed.format, InputFormat::P28);
  EXPECT_EQ(report(streamed), report(whole));
  EXPECT_FALSE(p21::first_difference(streamed.model, whole.model).has_value());
}

TEST(LoadCancel, AFlagStopsLoadingWithoutAVerdict) {
  const std::string text = trace_case("executables");
  std::atomic<bool> cancel{true};
  LoadOptions options;
  options.cancel = &cancel;
  const LoadedModel cut = load(text, registry(), options);
  EXPECT_TRUE(cut.cancelled);
  EXPECT_FALSE(cut.ok());
  EXPECT_TRUE(cut.diagnostics.empty()) << report(cut);
  cancel = false;
  const LoadedModel again = load(text, registry(), options);
  EXPECT_FALSE(again.cancelled);
  EXPECT_TRUE(again.ok()) << report(again);
}

}  // namespace
}  // namespace ncpost::pipeline
