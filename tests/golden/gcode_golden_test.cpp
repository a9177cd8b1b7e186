// G-code read with a dialect, golden: tests/golden/gcode/<profile-id>/<case>.<ext> holds the
// program, <case>.trace what engine/gcode makes of it — the canonical trace, then its
// diagnostics as `# file:line:column: severity: CODE: message` lines. The folder names the
// dialect (stylesheets/<profile-id>/dialect.json); files named <case>.sub.<ext> are
// subprogram files given to every case of the folder. NCPOST_UPDATE_GOLDEN=1 rewrites the
// golden files; review the diff (the coordinates are also checked by hand in
// tests/unit/gcode).

#include <gtest/gtest.h>

#include <algorithm>

#include "corpus.hpp"
#include "golden.hpp"
#include "ncpost/canon/trace.hpp"
#include "ncpost/gcode/gcode.hpp"

namespace ncpost::gcode {
namespace {

namespace fs = std::filesystem;

std::string read_golden(const fs::path& program, const Dialect& dialect,
                        const std::vector<SourceFile>& subprograms) {
  std::string out;
  canon::TraceWriter writer([&](std::string_view piece) { out += piece; });
  ReadOptions options;
  options.program_name = program.filename().string();
  options.subprograms = subprograms;
  const ReadResult r = read(test::read_file(program), dialect, writer, options);
  for (const auto& d : r.diagnostics) out += "# " + diag::format(d) + "\n";
  return out;
}

TEST(GcodeGolden, Cases) {
  const fs::path root = test::source_dir() / "tests" / "golden" / "gcode";
  int cases = 0;
  std::vector<fs::path> folders;
  for (const auto& e : fs::directory_iterator(root))
    if (e.is_directory()) folders.push_back(e.path());
  std::sort(folders.begin(), folders.end());
  for (const fs::path& folder : folders) {
    const std::string id = folder.filename().string();
    const auto loaded =
        load_dialect(test::read_file(test::source_dir() / "stylesheets" / id / "dialect.json"));
    ASSERT_TRUE(loaded.dialect) << id;
    std::vector<fs::path> programs;
    std::vector<SourceFile> subprograms;
    for (const auto& e : fs::directory_iterator(folder)) {
      const fs::path p = e.path();
      if (p.extension() == ".trace") continue;
      if (p.stem().extension() == ".sub")  // HOLE.sub.spf is the file HOLE.spf
        subprograms.push_back(
            {p.stem().stem().string() + p.extension().string(), test::read_file(p)});
      else
        programs.push_back(p);
    }
    std::sort(programs.begin(), programs.end());
    for (const fs::path& p : programs) {
      SCOPED_TRACE(p.string());
      ++cases;
      fs::path golden = p;
      golden.replace_extension(".trace");
      test::expect_golden(read_golden(p, *loaded.dialect, subprograms), golden);
    }
  }
  EXPECT_GE(cases, 5);
}

}  // namespace
}  // namespace ncpost::gcode
