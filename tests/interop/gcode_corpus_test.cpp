// The G-code corpus (../shared/corpus/gcode) read with the linuxcnc dialect, program by program,
// against LinuxCNC itself: the interpreter tests' `expected` output where a test is one plain
// rs274 run, and /usr/bin/rs274 run on the same file otherwise (the example programs, the
// trajectory-planner CAM programs, the cncjs fixtures, the interpreter tests that run several
// programs or filter their output). Each program is reported as
//   identical      same motions (kind, order, end points, arc centres and turns, feed in force)
//   both reject    LinuxCNC and we both refuse the program (an error)
//   different      the first difference is named
//   refused        we refuse a construct the dialect does not claim (named)
//   not run        the test needs LinuxCNC's task or Python, not rs274 (excluded)
// The table goes to <build>/gcode-corpus-report.md (docs/gcode.md quotes it).
//
// Runs rs274: the ctest RESOURCE_LOCK rs274, and by hand under flock /tmp/ncpost-rs274.lock.

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>

#include "corpus.hpp"
#include "motions.hpp"
#include "ncpost/gcode/gcode.hpp"

namespace ncpost::interop {
namespace {

namespace fs = std::filesystem;

enum class Verdict { Identical, BothReject, Different, Refused, NotRun };

const char* name(Verdict v) {
  switch (v) {
    case Verdict::Identical:
      return "identical";
    case Verdict::BothReject:
      return "both reject";
    case Verdict::Different:
      return "different";
    case Verdict::Refused:
      return "refused";
    case Verdict::NotRun:
      return "not run";
  }
  return "";
}

struct Program {
  std::string label;  // path relative to the set
  fs::path file;
  fs::path dir;  // where rs274 runs
  std::vector<std::string> rs274_args;
  std::optional<std::string> expected;  // LinuxCNC's own output, when the case has it
  bool must_fail = false;
  std::optional<std::vector<int>> tools;
  std::vector<gcode::SourceFile> subprograms;
  std::string not_run;             // why it is not run
  bool continue_on_error = false;  // rs274 -n 0: both sides go on after an error
};

struct Row {
  std::string label;
  Verdict verdict = Verdict::NotRun;
  std::size_t motions = 0;
  std::string note;
};

std::string one_line(std::string s, std::size_t limit = 160) {
  std::replace(s.begin(), s.end(), '\n', ' ');
  std::replace(s.begin(), s.end(), '|', '/');
  if (s.size() > limit) s = s.substr(0, limit) + "...";
  return s;
}

std::shared_ptr<const gcode::Dialect> linuxcnc_dialect() {
  static const auto d = [] {
    auto r = gcode::load_dialect(
        test::read_file(test::source_dir() / "stylesheets" / "linuxcnc" / "dialect.json"));
    EXPECT_TRUE(r.dialect) << (r.diagnostics.empty() ? "" : r.diagnostics[0].message);
    return r.dialect;
  }();
  return d;
}

std::vector<int> tools_of_table(const fs::path& table) {
  std::vector<int> tools;
  std::istringstream in(test::read_file(table));
  for (std::string line; std::getline(in, line);) {
    if (line.empty() || (line[0] != 'T' && line[0] != 't')) continue;
    tools.push_back(std::atoi(line.c_str() + 1));
  }
  return tools;
}

// Every T number in a program (outside comments, roughly): the tool table given to both sides.
std::vector<int> tools_in(const std::string& text) {
  std::set<int> tools;
  static const std::regex t(R"((?:^|[^A-Za-z_#<])[Tt]\s*(\d+))");
  std::string clean;
  bool paren = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '(') paren = true;
    if (!paren) clean += c;
    if (c == ')' || c == '\n') paren = false;
  }
  for (auto it = std::sregex_iterator(clean.begin(), clean.end(), t); it != std::sregex_iterator();
       ++it)
    tools.insert(std::stoi((*it)[1]));
  return {tools.begin(), tools.end()};
}

std::vector<gcode::SourceFile> files_beside(const fs::path& dir, const fs::path& except,
                                            bool recursive) {
  std::vector<gcode::SourceFile> out;
  auto add = [&](const fs::directory_entry& e) {
    if (!e.is_regular_file() || e.path() == except) return;
    const auto ext = e.path().extension().string();
    if (ext != ".ngc" && ext != ".nc" && ext != ".gcode") return;
    out.push_back({fs::relative(e.path(), dir).string(), test::read_file(e.path())});
  };
  if (recursive) {
    for (const auto& e : fs::recursive_directory_iterator(dir)) add(e);
  } else {
    for (const auto& e : fs::directory_iterator(dir)) add(e);
  }
  return out;
}

// ---- The interpreter tests: what each test.sh runs ----

std::vector<std::string> split_words(const std::string& line) {
  std::vector<std::string> out;
  std::string w;
  bool quoted = false;
  for (const char c : line) {
    if (c == '"' || c == '\'') {
      quoted = !quoted;
      continue;
    }
    if (!quoted && (c == ' ' || c == '\t')) {
      if (!w.empty()) out.push_back(w);
      w.clear();
      continue;
    }
    w += c;
  }
  if (!w.empty()) out.push_back(w);
  return out;
}

std::vector<Program> interp_programs(const fs::path& root) {
  std::vector<Program> out;
  std::vector<fs::path> scripts;
  for (const auto& e : fs::recursive_directory_iterator(root))
    if (e.path().filename() == "test.sh") scripts.push_back(e.path());
  std::sort(scripts.begin(), scripts.end());
  for (const fs::path& script : scripts) {
    const fs::path dir = script.parent_path();
    const std::string rel = fs::relative(dir, root).string();
    std::istringstream in(test::read_file(script));
    std::vector<std::vector<std::string>> runs;
    bool other_runner = false;
    bool simple = true;
    for (std::string line; std::getline(in, line);) {
      const auto first = line.find_first_not_of(" \t");
      if (first == std::string::npos || line[first] == '#') continue;
      auto words = split_words(line);
      const auto at = std::find(words.begin(), words.end(), "rs274");
      if (at == words.end()) {
        if (line.find("linuxcnc ") != std::string::npos ||
            line.find("python3") != std::string::npos)
          other_runner = true;
        if (line.find("exit") == std::string::npos) simple = false;
        continue;
      }
      std::vector<std::string> run(std::next(at), words.end());
      // "! rs274 ..." and "if ! rs274 ...; then  # expected to fail": the test wants an error.
      if (at != words.begin() && *std::prev(at) == "!") run.insert(run.begin(), "!");
      if (line.find("awk") != std::string::npos &&
          line.find("awk '{$1=\"\"; print}'") == std::string::npos)
        simple = false;  // a filtered output (MESSAGE lines only)
      if (line.find("awk") == std::string::npos) simple = false;
      runs.push_back(run);
    }
    if (runs.empty()) {
      Program p;
      p.label = rel;
      p.not_run = other_runner ? "runs LinuxCNC's task or Python, not rs274" : "runs no program";
      out.push_back(p);
      continue;
    }
    simple = simple && runs.size() == 1;
    for (const auto& run : runs) {
      Program base;
      base.dir = dir;
      base.must_fail = !run.empty() && run.front() == "!";
      std::vector<std::string> programs;
      bool plugin = false;
      for (std::size_t i = 0; i < run.size(); ++i) {
        const std::string& w = run[i];
        if (w == "|" || w == ">" || w == "2>&1" || w == "&" || w == "||" || w == ";") break;
        if ((w == "-t" || w == "-i" || w == "-n" || w == "-p" || w == "-v") && i + 1 < run.size()) {
          if (w == "-p") plugin = true;
          if (w == "-t") base.tools = tools_of_table(dir / run[i + 1]);
          if (w == "-n" && run[i + 1] == "0") base.continue_on_error = true;
          if (w == "-i") {
            // Remaps and Python plug-ins are LinuxCNC's own code, not G-code.
            const std::string ini = test::read_file(dir / run[i + 1]);
            if (ini.find("[PYTHON]") != std::string::npos || ini.find("REMAP") != std::string::npos)
              base.not_run = "needs LinuxCNC's Python plug-ins (the INI file loads them)";
            static const std::regex disable(R"(DISABLE_FANUC_STYLE_SUB\s*=\s*1)");
            if (std::regex_search(ini, disable))
              base.not_run = "its INI file turns a language feature off (DISABLE_FANUC_STYLE_SUB)";
          }
          if (w == "-t" || w == "-i" || w == "-n") {
            base.rs274_args.push_back(w);
            base.rs274_args.push_back(run[i + 1]);
          }
          ++i;
          continue;
        }
        if (w.size() > 4 && w.substr(w.size() - 4) == ".ngc") programs.push_back(w);
      }
      if (plugin || !base.not_run.empty()) {
        Program p;
        p.label = rel;
        p.not_run = plugin ? "runs a plug-in interpreter, not G-code" : base.not_run;
        out.push_back(p);
        continue;
      }
      if (!base.tools) base.tools = std::vector<int>{};  // rs274 without -t knows no tools
      for (const std::string& name : programs) {
        std::vector<fs::path> files;
        if (name.find("${") != std::string::npos) {
          // A loop over names: "test-legal-${t}.ngc".
          const std::string prefix = name.substr(0, name.find("${"));
          for (const auto& e : fs::directory_iterator(dir))
            if (e.path().filename().string().rfind(prefix, 0) == 0) files.push_back(e.path());
          std::sort(files.begin(), files.end());
        } else {
          files.push_back(dir / name);
        }
        for (const fs::path& f : files) {
          Program p = base;
          p.file = f;
          p.label = rel + "/" + f.filename().string();
          if (simple && !p.must_fail && fs::exists(dir / "expected"))
            p.expected = test::read_file(dir / "expected");
          p.subprograms = files_beside(dir, f, true);
          out.push_back(p);
        }
      }
    }
  }
  // bad/ and good/: every program must be refused / accepted with its .expected output.
  for (const char* folder : {"bad", "good"}) {
    std::vector<fs::path> files;
    for (const auto& e : fs::directory_iterator(root / folder))
      if (e.path().extension() == ".ngc") files.push_back(e.path());
    std::sort(files.begin(), files.end());
    for (const fs::path& f : files) {
      Program p;
      p.file = f;
      p.dir = f.parent_path();
      p.label = std::string(folder) + "/" + f.filename().string();
      p.tools = std::vector<int>{};
      p.must_fail = std::string(folder) == "bad";
      const fs::path expected = f.string() + ".expected";
      if (fs::exists(expected)) p.expected = test::read_file(expected);
      out.push_back(p);
    }
  }
  return out;
}

std::vector<Program> plain_programs(const fs::path& root) {
  std::vector<Program> out;
  std::vector<fs::path> files;
  for (const auto& e : fs::recursive_directory_iterator(root)) {
    if (!e.is_regular_file()) continue;
    const auto ext = e.path().extension().string();
    if (ext == ".ngc" || ext == ".nc" || ext == ".gcode" || ext == ".tap")
      files.push_back(e.path());
  }
  std::sort(files.begin(), files.end());
  for (const fs::path& f : files) {
    Program p;
    p.file = f;
    p.dir = f.parent_path();
    p.label = fs::relative(f, root).string();
    // The tools it names, and 1 to 99 for those it computes (T#<toolno>).
    p.tools = tools_in(test::read_file(f));
    for (int t = 1; t < 100; ++t)
      if (std::find(p.tools->begin(), p.tools->end(), t) == p.tools->end()) p.tools->push_back(t);
    // rs274 finds subroutine files beside the program (its working directory).
    p.subprograms = files_beside(p.dir, f, false);
    out.push_back(p);
  }
  return out;
}

// ---- One program ----

Row check(const Program& p) {
  Row row;
  row.label = p.label;
  if (!p.not_run.empty()) {
    row.note = p.not_run;
    return row;
  }
  const auto dialect = linuxcnc_dialect();
  if (!dialect) return row;
  const std::string text = test::read_file(p.file);
  gcode::ReadOptions options;
  options.program_name = p.file.filename().string();
  options.subprograms = p.subprograms;
  options.tools = p.tools;
  options.max_steps = 2'000'000;
  Motions sink;
  const gcode::ReadResult ours = gcode::read(text, *dialect, sink, options);
  const diag::FileDiagnostic* refusal = nullptr;
  const diag::FileDiagnostic* first_error = nullptr;
  for (const auto& d : ours.diagnostics) {
    if (d.diagnostic.severity != diag::Severity::Error) continue;
    if (!first_error) first_error = &d;
    // Refused by name: a construct not converted, a lathe program, motion that depends on what
    // only the machine knows (the issue's rule).
    if (!refusal && (d.diagnostic.code == diag::Code::GcodeUnsupported ||
                     d.diagnostic.code == diag::Code::GcodeLathe ||
                     d.diagnostic.code == diag::Code::GcodeMachineMotion))
      refusal = &d;
  }
  row.motions = sink.motions.size();
  if (refusal) {
    row.verdict = Verdict::Refused;
    row.note = one_line(diag::format(*refusal));
    return row;
  }
  const bool our_error = first_error != nullptr && !p.continue_on_error;
  if (p.must_fail) {
    row.verdict = our_error ? Verdict::BothReject : Verdict::Different;
    row.note =
        our_error ? one_line(diag::format(*first_error)) : "accepted a program LinuxCNC refuses";
    return row;
  }
  std::vector<Motion> theirs;
  bool their_error = false;
  std::string their_message;
  if (p.expected) {
    theirs = parse_rs274(*p.expected);
  } else {
    if (!fs::exists(kRs274)) {
      row.note = "no reference: /usr/bin/rs274 is missing";
      return row;
    }
    std::vector<std::string> args = p.rs274_args;
    fs::path table;
    if (std::find(args.begin(), args.end(), "-t") == args.end() && p.tools && !p.tools->empty()) {
      table = fs::temp_directory_path() / ("ncpost-corpus-" + std::to_string(::getpid()) + ".tbl");
      std::ofstream out(table);
      for (int t : *p.tools) out << "T" << t << " P" << t << " Z0 D1 ;\n";
      args.push_back("-t");
      args.push_back(table.string());
    }
    const Rs274Run run = run_rs274(p.dir, p.file, args);
    theirs = parse_rs274(run.canon);
    their_error = run.status != 0 && !p.continue_on_error;
    if (their_error) {
      // rs274 prints the error text and the offending line last.
      std::istringstream log(run.log);
      std::vector<std::string> lines;
      for (std::string l; std::getline(log, l);)
        if (!l.empty() && l.find("N.....") == std::string::npos) lines.push_back(l);
      their_message = lines.size() >= 2 ? lines[lines.size() - 2] : (lines.empty() ? "" : lines[0]);
    }
    if (!table.empty()) fs::remove(table);
  }
  if (their_error && our_error) {
    // Both refuse: the motions LinuxCNC made before its error must be ours too (we go on after
    // an error, so ours may be more).
    auto mine = without_null_moves(sink.motions);
    const auto before = without_null_moves(theirs);
    if (mine.size() > before.size()) mine.resize(before.size());
    const Comparison c = compare_motions(mine, before, "LinuxCNC before its error", true);
    row.verdict = c.same() ? Verdict::BothReject : Verdict::Different;
    row.note = one_line((c.same() ? "" : c.differences.front() + "; ") + "rs274: " + their_message +
                        "; ours: " + diag::format(*first_error));
    return row;
  }
  if (their_error != our_error) {
    row.verdict = Verdict::Different;
    row.note = their_error ? one_line("rs274 refuses (" + their_message + "), we accept")
                           : one_line("we refuse: " + diag::format(*first_error));
    return row;
  }
  // Feeds in inverse time or per revolution are printed as written by rs274 and per minute by us.
  const bool feeds = text.find("G93") == std::string::npos &&
                     text.find("g93") == std::string::npos &&
                     text.find("G95") == std::string::npos && text.find("g95") == std::string::npos;
  const auto mine = without_null_moves(sink.motions);
  theirs = without_null_moves(theirs);
  const Comparison c = compare_motions(mine, theirs, "LinuxCNC", feeds);
  // NCPOST_GCODE_CASE=<label>: both motion lists on stdout, to see a difference whole.
  if (const char* only = std::getenv("NCPOST_GCODE_CASE"); only && p.label == only) {
    for (std::size_t i = 0; i < std::max(mine.size(), theirs.size()); ++i)
      std::printf("%4zu %-70s %s\n", i, i < mine.size() ? describe(mine[i]).c_str() : "-",
                  i < theirs.size() ? describe(theirs[i]).c_str() : "-");
  }
  row.verdict = c.same() ? Verdict::Identical : Verdict::Different;
  if (!c.same()) {
    row.note = one_line(c.differences.front());
  } else if (c.outcome.max_deviation > 0) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "max deviation %.6f", c.outcome.max_deviation);
    row.note = buf;
  }
  return row;
}

struct Summary {
  std::map<Verdict, int> counts;
  std::vector<Row> rows;
  [[nodiscard]] int count(Verdict v) const {
    const auto it = counts.find(v);
    return it == counts.end() ? 0 : it->second;
  }
  // Identical or both reject, of the programs whose constructs the dictionary claims.
  [[nodiscard]] double agreement() const {
    const int claimed =
        count(Verdict::Identical) + count(Verdict::BothReject) + count(Verdict::Different);
    return claimed == 0 ? 1.0
                        : double(count(Verdict::Identical) + count(Verdict::BothReject)) / claimed;
  }
};

Summary run_set(const std::string& title, const std::vector<Program>& programs, std::ostream& md) {
  Summary s;
  for (const Program& p : programs) {
    SCOPED_TRACE(p.label);
    Row r = check(p);
    ++s.counts[r.verdict];
    s.rows.push_back(r);
  }
  md << "### " << title << "\n\n";
  md << "| verdict | programs |\n|---|---|\n";
  for (const Verdict v : {Verdict::Identical, Verdict::BothReject, Verdict::Different,
                          Verdict::Refused, Verdict::NotRun})
    md << "| " << name(v) << " | " << s.count(v) << " |\n";
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.1f%%", 100 * s.agreement());
  md << "\nAgreement on the programs the dictionary claims (identical or both reject): " << buf
     << "\n\n| program | verdict | motions | note |\n|---|---|---|---|\n";
  for (const Row& r : s.rows)
    md << "| `" << r.label << "` | " << name(r.verdict) << " | " << r.motions << " | " << r.note
       << " |\n";
  md << "\n";
  std::printf(
      "[ gcode    ] %s: %d identical, %d both reject, %d different, %d refused, %d not run "
      "(%s agree)\n",
      title.c_str(), s.count(Verdict::Identical), s.count(Verdict::BothReject),
      s.count(Verdict::Different), s.count(Verdict::Refused), s.count(Verdict::NotRun), buf);
  return s;
}

std::ofstream& report() {
  static std::ofstream out(fs::path(NCPOST_BINARY_DIR) / "gcode-corpus-report.md");
  return out;
}

TEST(GcodeCorpus, LinuxcncInterpreterTests) {
  NCPOST_REQUIRE_CORPUS_OR_SKIP(corpus);
  const Summary s = run_set("linuxcnc_tests_interp",
                            interp_programs(corpus / "gcode" / "linuxcnc_tests_interp"), report());
  EXPECT_GE(s.agreement(), 0.95);
  for (const Row& r : s.rows) {
    if (r.label.rfind("bad/", 0) != 0) continue;
    EXPECT_TRUE(r.verdict == Verdict::BothReject || r.verdict == Verdict::Refused)
        << r.label << " must be refused: " << r.note;
  }
}

TEST(GcodeCorpus, LinuxcncExamplePrograms) {
  NCPOST_REQUIRE_CORPUS_OR_SKIP(corpus);
  (void)run_set("linuxcnc_nc_files", plain_programs(corpus / "gcode" / "linuxcnc_nc_files"),
                report());
}

TEST(GcodeCorpus, TrajectoryPlannerPrograms) {
  NCPOST_REQUIRE_CORPUS_OR_SKIP(corpus);
  (void)run_set("linuxcnc_tests_trajectory-planner",
                plain_programs(corpus / "gcode" / "linuxcnc_tests_trajectory-planner"), report());
}

TEST(GcodeCorpus, CncjsFixtures) {
  NCPOST_REQUIRE_CORPUS_OR_SKIP(corpus);
  (void)run_set("cncjs_gcode-parser_fixtures",
                plain_programs(corpus / "gcode" / "cncjs_gcode-parser_fixtures"), report());
}

}  // namespace
}  // namespace ncpost::interop
