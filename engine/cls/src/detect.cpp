// Format detection: is the head of an upload APT CL / CLSF? The first records decide: `$$`
// comments are skipped (G-code writes comments in parentheses or after ';', P21 and P28 begin
// with ISO-10303-21; or '<'), and the first statement must be a CL major word.

#include <array>
#include <string_view>

#include "ncpost/cls/reader.hpp"
#include "records.hpp"

namespace ncpost::cls {
namespace {

// Words a CL file starts with in practice; a word with its slash or one of the slash-less
// statements. Enough for detection; the reader itself knows more.
constexpr std::array<std::string_view, 27> kStartWords = {
    "PARTNO", "UNITS",  "TOOL PATH", "TLDATA", "MSYS",   "FROM",   "GOTO",   "RAPID",  "CIRCLE",
    "FEDRAT", "SPINDL", "COOLNT",    "LOAD",   "LOADTL", "SELECT", "SELCTL", "CUTTER", "PPRINT",
    "CYCLE",  "SET",    "MULTAX",    "MACHIN", "PAINT",  "INDIRV", "CLPRNT", "REMARK", "MODE"};

bool known_start(std::string_view word) noexcept {
  for (auto w : kStartWords)
    if (detail::is_word(word, w)) return true;
  return false;
}

}  // namespace

bool looks_like_cl(std::string_view head) noexcept {
  int lines = 0;
  while (!head.empty() && lines < 64) {
    const std::size_t newline = head.find('\n');
    std::string_view line = head.substr(0, newline);
    head = newline == std::string_view::npos ? std::string_view{} : head.substr(newline + 1);
    ++lines;
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    line = detail::trim(line);
    if (line.empty() || line.substr(0, 2) == "$$") continue;
    if (newline == std::string_view::npos && head.empty() && line.size() < 4) return false;
    const std::size_t slash = line.find('/');
    if (slash != std::string_view::npos) return known_start(detail::trim(line.substr(0, slash)));
    // Statements without a slash: RAPID, and APT's PARTNO / REMARK / PPRINT text forms.
    const std::size_t space = line.find_first_of(" \t$");
    const std::string_view word = line.substr(0, space);
    return detail::is_word(word, "RAPID") || detail::is_word(word, "PARTNO") ||
           detail::is_word(word, "REMARK") || detail::is_word(word, "PPRINT");
  }
  return false;
}

}  // namespace ncpost::cls
