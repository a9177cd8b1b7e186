// `ncpost inspect` writes its JSON as it goes (issue 23: 16): the streamed text must be exactly
// the document's dump(2), for every program shape the golden cases hold and for a file with
// errors, so that streaming changed the memory and nothing else.

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
  for (const char* folder : {"tests/golden/trace/cases", "tests/golden/p21-malformed"})
    for (const auto& entry : fs::directory_iterator(test::source_dir() / folder))
      if (entry.path().extension() == ".stp") files.push_back(entry.path());
  ASSERT_GE(files.size(), 5u);
  std::size_t with_workplan = 0, with_errors = 0;
  for (const auto& file : files) {
    const Inspection inspection =
        inspect(Input{.name = file.filename().string(), .bytes = test::read_file(file)}, context);
    std::size_t pieces = 0;
    EXPECT_EQ(streamed(inspection, pieces), inspection_json(inspection).dump(2)) << file;
    EXPECT_GE(pieces, 1u);
    with_workplan += inspection.info.project && inspection.info.project->main_workplan ? 1 : 0;
    with_errors += inspection.job.ok ? 0 : 1;
  }
  EXPECT_GE(with_workplan, 3u) << "the cases must exercise the workplan tree";
  EXPECT_GE(with_errors, 1u) << "and a file with errors";
}

}  // namespace
}  // namespace ncpost::pipeline
