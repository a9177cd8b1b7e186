// The CL reader's contract beyond the golden traces: any cut into pieces reads the same, line
// endings, positions, limits (record length, errors, warnings, tool names), cancellation,
// stop at the first error, format detection, numbers, and the arc sense checked against the
// corpus's own tangents.

#include "ncpost/cls/reader.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <charconv>
#include <cmath>

#include "../../../engine/cls/src/records.hpp"
#include "corpus.hpp"
#include "ncpost/canon/trace.hpp"

namespace ncpost::cls {
namespace {

namespace fs = std::filesystem;

struct Read {
  std::string trace;
  ReadResult result;
};

Read read_whole(std::string_view text, const ReadOptions& options = {}) {
  Read r;
  canon::TraceWriter w([&](std::string_view s) { r.trace += s; });
  r.result = read(text, w, options);
  return r;
}

// Pieces of pseudo-random sizes (1..64 bytes) that depend on the text only.
Read read_in_pieces(std::string_view text, const ReadOptions& options = {}) {
  Read r;
  canon::TraceWriter w([&](std::string_view s) { r.trace += s; });
  Reader reader(w, options);
  std::uint32_t state = static_cast<std::uint32_t>(text.size()) * 2654435761u + 1;
  for (std::size_t at = 0; at < text.size();) {
    state = state * 1664525u + 1013904223u;
    const std::size_t take = std::min<std::size_t>(1 + (state >> 26), text.size() - at);
    reader.feed(text.substr(at, take));
    at += take;
  }
  r.result = reader.finish();
  return r;
}

std::string diagnostics_text(const ReadResult& r) {
  std::string out;
  for (const auto& d : r.diagnostics) out += diag::format(d, "f") + "\n";
  return out;
}

std::vector<fs::path> inputs() {
  std::vector<fs::path> files;
  for (const auto& e : fs::directory_iterator(test::source_dir() / "tests/golden/cls/cases"))
    if (e.path().extension() == ".cls") files.push_back(e.path());
  if (const auto corpus = test::corpus_dir())
    for (const auto& e : fs::directory_iterator(*corpus / "cls")) files.push_back(e.path());
  std::sort(files.begin(), files.end());
  return files;
}

TEST(ClsReader, PiecesReadTheSameAsTheWhole) {
  const auto files = inputs();
  ASSERT_GE(files.size(), 10u);
  for (const auto& f : files) {
    const std::string text = test::read_file(f);
    const Read whole = read_whole(text);
    const Read pieces = read_in_pieces(text);
    EXPECT_EQ(whole.trace, pieces.trace) << f;
    EXPECT_EQ(diagnostics_text(whole.result), diagnostics_text(pieces.result)) << f;
    EXPECT_EQ(whole.result.calls, pieces.result.calls);
  }
}

TEST(ClsReader, CrLfReadsAsLf) {
  for (const auto& f : inputs()) {
    const std::string text = test::read_file(f);
    std::string crlf;
    for (char c : text) crlf += c == '\n' ? std::string("\r\n") : std::string(1, c);
    const Read a = read_whole(text);
    const Read b = read_in_pieces(crlf);
    EXPECT_EQ(a.trace, b.trace) << f;
    EXPECT_EQ(diagnostics_text(a.result), diagnostics_text(b.result)) << f;
  }
}

TEST(ClsReader, LastLineWithoutNewlineAndContinuationPositions) {
  const Read r = read_whole("UNITS/MM\nGOTO/1,$\n 2,$ remark\n  x\nGOTO/4,5,6");
  ASSERT_EQ(r.result.diagnostics.size(), 1u) << diagnostics_text(r.result);
  EXPECT_EQ(r.result.diagnostics[0].code, diag::Code::ClsBadNumber);
  EXPECT_EQ(r.result.diagnostics[0].line, 4u);  // the field on the third line of the record
  EXPECT_EQ(r.result.diagnostics[0].column, 3u);
  EXPECT_NE(r.trace.find("COMMENT(\"remark\")"), std::string::npos) << r.trace;
  EXPECT_NE(r.trace.find("STRAIGHT_FEED(4.0000, 5.0000, 6.0000)"), std::string::npos) << r.trace;
}

// Found by the fuzzer: a word without a slash (and so without arguments) at the end of the text
// reported a column computed from no text at all.
TEST(ClsReader, WordWithoutArgumentsPointsIntoTheRecord) {
  for (const char* text : {"UNITS/MM\nCYCLE", "UNITS/MM\nCYCLE\n", "UNITS/MM\nGOTO"}) {
    const Read r = read_whole(text);
    ASSERT_EQ(r.result.diagnostics.size(), 1u) << text;
    EXPECT_EQ(r.result.diagnostics[0].line, 2u);
    EXPECT_LE(r.result.diagnostics[0].column, 6u) << diagnostics_text(r.result);
  }
}

TEST(ClsReader, OpenContinuationAtTheEnd) {
  const Read r = read_whole("UNITS/MM\nGOTO/1,2,$\n");
  ASSERT_FALSE(r.result.diagnostics.empty());
  EXPECT_EQ(r.result.diagnostics.back().code, diag::Code::ClsOpenContinuation);
}

TEST(ClsReader, RecordLongerThanTheLimitIsSkipped) {
  ReadOptions o;
  o.max_record_bytes = 64;
  const std::string long_line = "PPRINT/" + std::string(200, 'A') + "\n";
  const std::string continued =
      "GOTO/1,$\n" + std::string(40, '1') + ",$\n" + std::string(40, '2') + "\n";
  for (const std::string& text : {long_line, continued}) {
    const Read whole = read_whole("UNITS/MM\n" + text + "GOTO/1,2,3\n", o);
    const Read pieces = read_in_pieces("UNITS/MM\n" + text + "GOTO/1,2,3\n", o);
    ASSERT_FALSE(whole.result.diagnostics.empty());
    EXPECT_EQ(whole.result.diagnostics[0].code, diag::Code::ClsRecordTooLong);
    EXPECT_EQ(whole.result.diagnostics[0].line, 2u);
    EXPECT_NE(whole.trace.find("STRAIGHT_FEED(1.0000, 2.0000, 3.0000)"), std::string::npos);
    EXPECT_EQ(whole.trace, pieces.trace);
    EXPECT_EQ(diagnostics_text(whole.result), diagnostics_text(pieces.result));
  }
}

TEST(ClsReader, ErrorsAndWarningsAreBounded) {
  std::string bad = "UNITS/MM\n";
  for (int i = 0; i < 5000; ++i) bad += "GOTO/x,1,1\n";
  ReadOptions o;
  o.max_errors = 10;
  const Read r = read_whole(bad, o);
  EXPECT_EQ(r.result.diagnostics.size(), 10u);
  // The read stopped at the limit: no end sequence.
  EXPECT_EQ(r.trace.find("PROGRAM_END"), std::string::npos);

  std::string unknown = "UNITS/MM\n";
  for (int i = 0; i < 5000; ++i) unknown += "WORD" + std::to_string(i) + "/1\n";
  const Read u = read_whole(unknown, o);
  EXPECT_EQ(u.result.diagnostics.size(), 11u);  // 10 and one note that more were dropped
  EXPECT_EQ(u.result.diagnostics.back().code, diag::Code::ClsTooManyDiagnostics);
  const Read many = read_whole(unknown);
  EXPECT_EQ(many.result.diagnostics.size(), 257u);  // 256 words, then one note for the rest
  EXPECT_TRUE(many.result.ok());
}

TEST(ClsReader, StopAtFirstErrorLeavesTheProgramOpen) {
  ReadOptions o;
  o.stop_at_first_error = true;
  const Read r = read_whole("UNITS/MM\nGOTO/1,2,3\nGOTO/x,2,3\nGOTO/4,5,6\nFINI\n", o);
  EXPECT_FALSE(r.result.ok());
  EXPECT_EQ(r.result.diagnostics.size(), 1u);
  EXPECT_EQ(r.trace.find("4.0000"), std::string::npos);
  EXPECT_EQ(r.trace.find("PROGRAM_END"), std::string::npos);
}

TEST(ClsReader, CancelStopsWithoutTheEnd) {
  std::string text = "UNITS/MM\n";
  for (int i = 0; i < 20000; ++i) text += "GOTO/1,2,3\n";
  std::atomic<bool> cancel{true};
  ReadOptions o;
  o.cancel = &cancel;
  canon::ProgramBuffer sink;
  const auto r = read(text, sink, o);
  EXPECT_TRUE(r.cancelled);
  EXPECT_FALSE(r.ok());
  EXPECT_LT(sink.calls().size(), 5000u);
  EXPECT_FALSE(std::holds_alternative<canon::ProgramEnd>(sink.calls().back()));
}

TEST(ClsReader, UnitsAndHeader) {
  const Read none = read_whole("GOTO/1,2,3\n");
  ASSERT_EQ(none.result.diagnostics.size(), 1u);
  EXPECT_EQ(none.result.diagnostics[0].code, diag::Code::ClsAssumption);
  ReadOptions inch;
  inch.default_units = canon::Units::Inches;
  EXPECT_NE(read_whole("GOTO/1,2,3\n", inch).trace.find("CANON_UNITS_INCHES"), std::string::npos);
  // PARTNO/ and UNITS/ after comments still make the header; the comments follow it.
  const Read r = read_whole("$$ first\nPARTNO/BRACKET 7\nUNITS/INCHES\nGOTO/1,2,3\n");
  EXPECT_TRUE(r.result.diagnostics.empty());
  EXPECT_EQ(r.trace.substr(0, r.trace.find('\n')),
            "    1 PROJECT_BEGIN($, CL_PROGRAM, \"BRACKET 7\")");
  EXPECT_NE(r.trace.find("    2 USE_LENGTH_UNITS(CANON_UNITS_INCHES)"), std::string::npos);
  EXPECT_NE(r.trace.find("    6 COMMENT(\"first\")"), std::string::npos) << r.trace;
  // UNITS/ later changes the unit from there on.
  const Read later = read_whole("UNITS/MM\nGOTO/1,2,3\nUNITS/INCHES\nGOTO/1,2,3\n");
  EXPECT_NE(later.trace.find("USE_LENGTH_UNITS(CANON_UNITS_INCHES)"), std::string::npos);
}

TEST(ClsReader, MsysCanBeLeftUnapplied) {
  const std::string text = "UNITS/MM\nMSYS/100,50,0,0,1,0,-1,0,0\nGOTO/10,0,5\n";
  EXPECT_NE(read_whole(text).trace.find("STRAIGHT_FEED(100.0000, 60.0000, 5.0000)"),
            std::string::npos);
  ReadOptions o;
  o.apply_msys = false;
  EXPECT_NE(read_whole(text, o).trace.find("STRAIGHT_FEED(10.0000, 0.0000, 5.0000)"),
            std::string::npos);
}

TEST(ClsReader, ToolNamesGetNumbers) {
  const std::string text =
      "UNITS/MM\nTOOL PATH/A,TOOL,T2-D10\nGOTO/1,1,1\nTOOL PATH/B,TOOL,ROUGHER\nGOTO/1,1,1\n"
      "TOOL PATH/C,TOOL,FINISHER\nGOTO/1,1,1\nTOOL PATH/D,TOOL,ROUGHER\nGOTO/1,1,1\n"
      "TOOL PATH/E,TOOL,ROUGHER\nLOAD/TOOL,7\nGOTO/1,1,1\n";
  const Read r = read_whole(text);
  // T2 is 2; the others 1 and 3 (2 is taken); the same name the same number; LOAD/TOOL wins.
  std::vector<std::string> changes;
  for (std::size_t at = 0; (at = r.trace.find("CHANGE_TOOL(", at)) != std::string::npos; ++at)
    changes.push_back(r.trace.substr(at + 12, r.trace.find(')', at) - at - 12));
  EXPECT_EQ(changes, (std::vector<std::string>{"2", "1", "3", "1", "7"}));
  ReadOptions o;
  o.max_tool_names = 1;
  const Read limited = read_whole(text, o);
  ASSERT_FALSE(limited.result.ok());
  EXPECT_EQ(limited.result.diagnostics.back().code, diag::Code::ClsLimit);
}

TEST(ClsReader, LooksLikeCl) {
  for (const auto& f : inputs()) EXPECT_TRUE(looks_like_cl(test::read_file(f))) << f;
  EXPECT_TRUE(looks_like_cl("\n\n  $$ comment\r\nTOOL PATH/OP,TOOL,T1\r\n"));
  EXPECT_TRUE(looks_like_cl("PARTNO BRACKET\nFROM/0,0,0\n"));
  EXPECT_TRUE(looks_like_cl("goto/1,2,3\n"));
  EXPECT_FALSE(looks_like_cl("ISO-10303-21;\nHEADER;\n"));
  EXPECT_FALSE(looks_like_cl("<?xml version=\"1.0\"?>\n<iso_10303_28/>"));
  EXPECT_FALSE(looks_like_cl("%\n(PROGRAM)\nG21 G90\nG0 X1 Y2\nM2\n%\n"));
  EXPECT_FALSE(looks_like_cl("N10 G0 X1/2\n"));  // a slash, but no CL word before it
  EXPECT_FALSE(looks_like_cl("O1000\nT1 M6\n"));
  EXPECT_FALSE(looks_like_cl(""));
  EXPECT_FALSE(looks_like_cl("$$ only comments\n"));
}

TEST(ClsReader, Numbers) {
  using detail::parse_number;
  EXPECT_EQ(parse_number("+1.5"), 1.5);
  EXPECT_EQ(parse_number("-0.5"), -0.5);
  EXPECT_EQ(parse_number(".5"), 0.5);
  EXPECT_EQ(parse_number("5."), 5.0);
  EXPECT_EQ(parse_number("1.5D-3"), 1.5e-3);
  EXPECT_EQ(parse_number("2E2"), 200.0);
  for (const char* bad : {"", "-", "--1", "+-1", "1,2", "nan", "inf", "1e999", "x", "1 2"})
    EXPECT_FALSE(parse_number(bad)) << bad;
  // The fast path gives exactly what from_chars gives, for every length of mantissa it takes.
  std::uint64_t state = 12345;
  for (int i = 0; i < 200000; ++i) {
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    const int digits = 1 + static_cast<int>((state >> 33) % 16);
    const int point = static_cast<int>((state >> 20) % (digits + 1));
    std::string text = (state & 1) ? "-" : "";
    std::uint64_t d = state;
    for (int k = 0; k < digits; ++k) {
      if (k == point) text += '.';
      text += static_cast<char>('0' + (d % 10));
      d = d / 10 + (state >> 40);
    }
    double expected = 0;
    const char* begin = text.data() + (text[0] == '-' ? 1 : 0);
    std::from_chars(begin, text.data() + text.size(), expected);
    if (text[0] == '-') expected = -expected;
    const auto fast = detail::fast_decimal(text);
    if (fast) {
      ASSERT_EQ(*fast, expected) << text;
    }
    ASSERT_EQ(parse_number(text), expected) << text;
  }
}

// The sense of CIRCLE/ (clockwise seen from the tip of its axis) against the files themselves:
// where an arc follows a straight feed, the arc's start tangent should go on in the feed's
// direction. Counted over every arc of the corpus, the opposite convention must lose.
TEST(ClsReader, ArcSenseAgreesWithTheCorpusTangents) {
  NCPOST_REQUIRE_CORPUS_OR_SKIP(corpus);
  std::size_t agree = 0, disagree = 0;
  for (const auto& e : fs::directory_iterator(corpus / "cls")) {
    canon::ProgramBuffer sink;
    const auto r = read(test::read_file(e.path()), sink);
    EXPECT_TRUE(r.ok()) << e.path();
    canon::Point previous{}, position{};
    bool straight_before = false;
    for (const auto& call : sink.calls()) {
      if (const auto* f = std::get_if<canon::StraightFeed>(&call)) {
        previous = position;
        position = {f->to.x, f->to.y, f->to.z};
        straight_before = true;
      } else if (const auto* t = std::get_if<canon::StraightTraverse>(&call)) {
        position = {t->to.x, t->to.y, t->to.z};
        straight_before = false;
      } else if (const auto* a = std::get_if<canon::ArcFeed>(&call)) {
        if (straight_before) {
          const double rx = position.x - a->centre.x, ry = position.y - a->centre.y;
          // Counter-clockwise about the normal is n × r; turns < 0 is the other way.
          const double sense = (a->turns > 0 ? 1 : -1) * (a->normal.k > 0 ? 1 : -1);
          const double tx = -ry * sense, ty = rx * sense;
          const double dx = position.x - previous.x, dy = position.y - previous.y;
          const double cosine = (tx * dx + ty * dy) / (std::hypot(tx, ty) * std::hypot(dx, dy));
          if (cosine > 0.5) ++agree;
          if (cosine < -0.5) ++disagree;
        }
        previous = position;
        position = {a->end.x, a->end.y, a->end.z};
        straight_before = false;
      }
    }
  }
  std::printf("[ arcs     ] after a feed: %zu continue its direction, %zu reverse it\n", agree,
              disagree);
  EXPECT_GT(agree, 200u);
  EXPECT_LT(disagree * 20, agree);
}

}  // namespace
}  // namespace ncpost::cls
