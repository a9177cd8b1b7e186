// The one cap on diagnostics in an answer (pipeline::diagnostics_json): a hostile upload can
// make millions; 1000 are listed and one HTTP-013 note counts the rest.

#include "ncpost/pipeline/diagnostics.hpp"

#include <gtest/gtest.h>

#include <cstdint>

namespace ncpost::pipeline {
namespace {

std::vector<diag::FileDiagnostic> many(std::size_t n) {
  std::vector<diag::FileDiagnostic> out;
  for (std::uint32_t i = 0; i < n; ++i)
    out.push_back({"upload", diag::make(diag::Code::IoUnknownFormat, i + 1, 1, "bad")});
  return out;
}

TEST(DiagnosticsJson, UpToTheCapEveryDiagnosticIsListed) {
  const auto json = diagnostics_json(many(kMaxListedDiagnostics));
  ASSERT_EQ(json.size(), kMaxListedDiagnostics);
  EXPECT_EQ(json.back()["code"], "IO-002");
  EXPECT_EQ(json.back()["line"], kMaxListedDiagnostics);
}

TEST(DiagnosticsJson, BeyondTheCapOneNoteCountsTheRest) {
  const auto json = diagnostics_json(many(5000));
  ASSERT_EQ(json.size(), kMaxListedDiagnostics + 1);
  EXPECT_EQ(json[kMaxListedDiagnostics - 1]["line"], kMaxListedDiagnostics);
  EXPECT_EQ(json.back()["code"], "HTTP-013");
  EXPECT_EQ(json.back()["severity"], "note");
  EXPECT_EQ(json.back()["file"], "upload");
  EXPECT_EQ(json.back()["message"], "4000 more diagnostics are not listed");
}

TEST(DiagnosticsJson, TheCapIsAParameter) {
  const auto json = diagnostics_json(many(3), 2);
  ASSERT_EQ(json.size(), 3u);
  EXPECT_EQ(json.back()["message"], "1 more diagnostics are not listed");
}

}  // namespace
}  // namespace ncpost::pipeline
