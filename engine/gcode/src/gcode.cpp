// The entry points: read() and looks_like_gcode(); write_xml() is in xml_form.cpp.

#include "ncpost/gcode/gcode.hpp"

#include <iterator>
#include <string>

#include "interpreter.hpp"

namespace ncpost::gcode {

ReadResult read(std::string_view text, const Dialect& dialect, canon::Sink& sink,
                const ReadOptions& options) {
  detail::Interpreter interpreter(text, dialect, sink, options, nullptr);
  interpreter.run();
  return std::move(interpreter).result();
}

ReadResult read_with_dialect(std::string_view text, std::string_view dialect_json,
                             std::string_view dialect_name, canon::Sink& sink,
                             const ReadOptions& options) {
  DialectResult loaded = load_dialect(dialect_json);
  ReadResult result;
  if (!loaded.dialect) {
    result.diagnostics = diag::with_file(loaded.diagnostics, dialect_name);
    return result;
  }
  result = read(text, *loaded.dialect, sink, options);
  // Warnings the dialect raised while loading come first.
  if (!loaded.diagnostics.empty()) {
    auto all = diag::with_file(loaded.diagnostics, dialect_name);
    all.insert(all.end(), std::make_move_iterator(result.diagnostics.begin()),
               std::make_move_iterator(result.diagnostics.end()));
    result.diagnostics = std::move(all);
  }
  return result;
}

namespace {

bool starts_with_ci(std::string_view text, std::string_view prefix) {
  if (text.size() < prefix.size()) return false;
  for (std::size_t i = 0; i < prefix.size(); ++i)
    if (detail::upper(text[i]) != prefix[i]) return false;
  return true;
}

// "GOTO/1,2,3", "FEDRAT/200": a word of letters, then '/'.
bool apt_statement(std::string_view line) {
  const std::size_t slash = line.find('/');
  if (slash == std::string_view::npos || slash < 2 || slash > 12) return false;
  for (std::size_t i = 0; i < slash; ++i)
    if (!detail::is_letter(line[i]) && line[i] != '_') return false;
  return true;
}

// The statement a numbered Heidenhain block starts with.
bool klartext_block(std::string_view block) {
  static constexpr std::string_view kStarts[] = {
      ";",    "*",        "L ",   "L\t",  "END PGM", "TOOL ", "CYCL ", "CC",
      "C ",   "CR ",      "CP ",  "CT ",  "LBL ",    "CALL ", "FN ",   "Q",
      "STOP", "BLK FORM", "RND ", "CHF ", "APPR ",   "DEP "};
  if (block == "L" || block == "STOP") return true;
  for (const std::string_view start : kStarts)
    if (starts_with_ci(block, start)) return true;
  return false;
}

}  // namespace

bool looks_like_gcode(std::string_view head) noexcept {
  // Skip a UTF-8 byte order mark and leading blank lines.
  if (head.size() >= 3 && head.substr(0, 3) == "\xEF\xBB\xBF") head.remove_prefix(3);
  // The other formats announce themselves on their first line.
  std::size_t p = 0;
  while (p < head.size() &&
         (head[p] == ' ' || head[p] == '\t' || head[p] == '\r' || head[p] == '\n'))
    ++p;
  const std::string_view rest = head.substr(p);
  if (starts_with_ci(rest, "ISO-10303-21") || starts_with_ci(rest, "<?XML") ||
      rest.starts_with("<") || rest.starts_with("/*"))
    return false;
  // Line by line: a line that is clearly G-code counts, one that is clearly APT/CL refuses.
  int gcode_lines = 0;
  int other_lines = 0;
  std::size_t i = p;
  int lines = 0;
  while (i < head.size() && lines < 64) {
    std::size_t end = head.find('\n', i);
    if (end == std::string_view::npos) end = head.size();
    std::string_view line = head.substr(i, end - i);
    i = end + 1;
    while (!line.empty() && (line.back() == '\r' || line.back() == ' ' || line.back() == '\t'))
      line.remove_suffix(1);
    while (!line.empty() && (line.front() == ' ' || line.front() == '\t')) line.remove_prefix(1);
    if (line.empty()) continue;
    ++lines;
    if (line.front() == '%' || line.front() == ';' || line.front() == '(') {
      ++gcode_lines;
      continue;
    }
    // APT / CLSF statements: a word, '/', arguments (GOTO/, PARTNO, FEDRAT/, TLAXIS/, ...).
    if (starts_with_ci(line, "PARTNO") || starts_with_ci(line, "CLPRNT") ||
        starts_with_ci(line, "MACHIN") || starts_with_ci(line, "UNITS/") ||
        starts_with_ci(line, "TOOL PATH/") || starts_with_ci(line, "$$") || apt_statement(line)) {
      ++other_lines;
      continue;
    }
    if (starts_with_ci(line, "BEGIN PGM")) return true;
    // Heidenhain numbered blocks: "0 BEGIN PGM", "12 L X+10 ...".
    std::size_t k = 0;
    while (k < line.size() && detail::is_digit(line[k])) ++k;
    if (k > 0 && k < line.size() && line[k] == ' ') {
      const std::string_view block = line.substr(k + 1);
      if (starts_with_ci(block, "BEGIN PGM")) return true;
      if (klartext_block(block)) {
        ++gcode_lines;
        continue;
      }
    }
    const char c = detail::upper(line.front());
    const bool word_start = c == 'N' || c == 'G' || c == 'M' || c == 'O' || c == 'X' || c == 'Y' ||
                            c == 'Z' || c == 'T' || c == 'S' || c == 'F' || c == '#' || c == '/' ||
                            c == ':' || c == 'R';
    if (word_start && line.size() >= 2) {
      const char n = line[1];
      if (detail::is_digit(n) || n == '-' || n == '.' || n == ' ' || n == '[' || n == '<' ||
          n == '=' || (c == '#' && detail::is_digit(n)) || c == '/') {
        ++gcode_lines;
        continue;
      }
    }
    ++other_lines;
  }
  return gcode_lines > 0 && gcode_lines >= 2 * other_lines;
}

}  // namespace ncpost::gcode
