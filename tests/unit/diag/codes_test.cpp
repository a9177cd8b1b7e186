// The code table is the contract: codes are unique, well formed, and documented.

#include <gtest/gtest.h>

#include <regex>
#include <set>

#include "corpus.hpp"
#include "ncpost/diag/diagnostic.hpp"

namespace ncpost::diag {
namespace {

TEST(DiagnosticCodes, AreUniqueAndWellFormed) {
  std::set<std::string_view> seen;
  const std::regex form("[A-Z0-9]+-[0-9]{3}");
  for (const CodeInfo& c : all_codes()) {
    EXPECT_TRUE(seen.insert(c.id).second) << "duplicate code " << c.id;
    EXPECT_TRUE(std::regex_match(std::string(c.id), form)) << c.id;
    EXPECT_FALSE(c.meaning.empty()) << c.id;
    EXPECT_EQ(info(c.code).id, c.id);
  }
}

TEST(DiagnosticCodes, AreAllDocumented) {
  const std::string doc = test::read_file(test::source_dir() / "docs/diagnostics.md");
  for (const CodeInfo& c : all_codes()) {
    const std::string row =
        "| `" + std::string(c.id) + "` | " + std::string(to_string(c.default_severity)) + " |";
    EXPECT_NE(doc.find(row), std::string::npos) << "docs/diagnostics.md lacks: " << row;
  }
}

TEST(DiagnosticCodes, TextForm) {
  const Diagnostic d =
      make(Code::P21DanglingReference, 12, 3, "#5 used by #7 attribute 1 is not defined");
  EXPECT_EQ(format(d, "part.stp"),
            "part.stp:12:3: error: P21-040: #5 used by #7 attribute 1 is not defined");
}

TEST(DiagnosticList, StopsCountingAtTheLimit) {
  DiagnosticList list(2);
  list.add(Code::P21LoneBackslash, 1, 1, "a warning does not count");
  EXPECT_FALSE(list.full());
  list.add(Code::P21BadNumber, 1, 1, "one");
  list.add(Code::P21BadNumber, 1, 1, "two");
  EXPECT_TRUE(list.full());
  EXPECT_EQ(list.error_count(), 2u);
}

}  // namespace
}  // namespace ncpost::diag
