// `ncpost inspect` writes its JSON as it goes (issue 23: 16): the streamed text must be exactly
// the document's dump(2), for every program shape the golden cases hold and for a file with
// errors, so that streaming changed the memory and nothing else; written while the inspector
// walks the model (the tree never held), too; and the text form, written while walked, is the
// text of the whole tree.

#include <gtest/gtest.h>

#include "corpus.hpp"
#include "ncpost/pipeline/jobs.hpp"

namespace ncpost::pipeline {
namespace {

namespace fs = std::filesystem;

std::string streamed(const Inspection& inspection, std::size_t& pieces) {
  std::string text;
  write_inspection_json(inspection, [&](std::string_view piece) {
    text.append(piece);
    ++pieces;
  });
  return text;
}

TEST(InspectionJson, StreamedTextIsTheDocumentsDump) {
  static const Schemas schemas = load_schemas();
  JobContext context;
  context.schemas = &schemas;
  std::vector<fs::path> files;
  for (const char* folder : {"tests/golden/trace/cases", "tests/golden/p21-malformed",
                             "tests/golden/tolerant/cases", "tests/golden/ap238/cases"})
    for (const auto& entry : fs::directory_iterator(test::source_dir() / folder))
      if (entry.path().extension() == ".stp") files.push_back(entry.path());
  ASSERT_GE(files.size(), 5u);
  std::size_t with_workplan = 0, with_errors = 0, with_branches = 0;
  for (const auto& file : files) {
    const Inspection inspection =
        inspect(Input{.name = file.filename().string(), .bytes = test::read_file(file)}, context);
    std::size_t pieces = 0;
    const std::string document = inspection_json(inspection).dump(2);
    EXPECT_EQ(streamed(inspection, pieces), document) << file;
    EXPECT_GE(pieces, 1u);
    std::string walked;
    const Inspection alone =
        inspect_to_json(Input{.name = file.filename().string(), .bytes = test::read_file(file)},
                        context, [&](std::string_view piece) { walked.append(piece); });
    EXPECT_EQ(walked, document) << file << " written while walked";
    EXPECT_EQ(alone.job.ok, inspection.job.ok) << file;
    EXPECT_EQ(alone.job.diagnostics.size(), inspection.job.diagnostics.size()) << file;
    // The text form likewise (`ncpost inspect --format text`).
    std::string text;
    const Inspection as_text =
        inspect_to_text(Input{.name = file.filename().string(), .bytes = test::read_file(file)},
                        context, [&](std::string_view piece) { text.append(piece); });
    EXPECT_EQ(text, inspection_text(inspection)) << file << " as text, written while walked";
    EXPECT_EQ(as_text.job.ok, inspection.job.ok) << file;
    with_branches += text.find("true_branch: ") != std::string::npos ? 1 : 0;
    with_workplan += inspection.info.project && inspection.info.project->main_workplan ? 1 : 0;
    with_errors += inspection.job.ok ? 0 : 1;
  }
  EXPECT_GE(with_workplan, 3u) << "the cases must exercise the workplan tree";
  EXPECT_GE(with_errors, 1u) << "and a file with errors";
  EXPECT_GE(with_branches, 1u) << "and an if's branches";
}

// The text form against text written before it was streamed (tests/golden/inspect/*.txt): an
// if with an unset false branch, and a program with NC functions (a message's text).
TEST(InspectionText, IsTheGoldenText) {
  static const Schemas schemas = load_schemas();
  JobContext context;
  context.schemas = &schemas;
  for (const auto& [input, golden] :
       {std::pair<const char*, const char*>{"tests/golden/trace/cases/errors.stp", "errors.txt"},
        {"examples/bracket.stp", "bracket.txt"}}) {
    const fs::path file = test::source_dir() / input;
    std::string text;
    (void)inspect_to_text(Input{.name = file.filename().string(), .bytes = test::read_file(file)},
                          context, [&](std::string_view piece) { text.append(piece); });
    EXPECT_EQ(text, test::read_file(test::source_dir() / "tests/golden/inspect" / golden)) << input;
  }
}

}  // namespace
}  // namespace ncpost::pipeline
