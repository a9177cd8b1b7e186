#pragma once
// One block as read and evaluated: its words with their values (already through expressions
// and parameters), its G and M codes looked up in the dialect, and its parameter assignments,
// which take effect after the whole block has been read (LinuxCNC's rule, also FANUC's).

#include <array>
#include <bitset>
#include <cstdint>
#include <string>
#include <vector>

#include "ncpost/gcode/dialect.hpp"
#include "value.hpp"

namespace ncpost::gcode::detail {

struct Word {
  double value = 0;              // in the program's units as written (not yet scaled to mm)
  std::uint32_t column = 0;      // 1-based column of the word's letter
  bool integer_literal = false;  // written as a plain integer literal (FANUC least increments)
  bool machine = false;          // derived from a value only the machine knows
  // Sinumerik X=AC(..) / X=IC(..): this word absolute or incremental whatever G90/G91 says.
  enum class Distance : std::uint8_t { Modal, Absolute, Incremental } distance = Distance::Modal;
};

struct CodeRef {
  const CodeSpec* spec = nullptr;
  int number = 0;  // G × 10 (G38.2 → 382), or the M number
  bool m = false;
  std::uint32_t column = 0;
};

struct Assignment {
  bool named = false;
  double number = 0;  // #n / Rn / Qn
  std::string name;   // #<name>, a Sinumerik variable
  Value value{};
  std::uint32_t column = 0;
};

struct Block {
  std::uint32_t line = 0;
  std::uint32_t first_column = 1;
  std::bitset<kMaxWords> present;
  std::array<Word, kMaxWords> words{};
  std::vector<CodeRef> codes;  // G and M codes in the order written
  std::vector<Assignment> assignments;
  bool has_line_number = false;
  double line_number = 0;
  // Sinumerik / Heidenhain pieces the converter reads besides words (a cycle call's
  // parameters, a MSG text) live with the statement that made them, not here.

  void clear() {
    present.reset();
    codes.clear();
    assignments.clear();
    has_line_number = false;
    line_number = 0;
    first_column = 1;
  }
  [[nodiscard]] bool has(WordId w) const noexcept { return w < kMaxWords && present.test(w); }
  [[nodiscard]] const Word& word(WordId w) const noexcept { return words[w]; }
  [[nodiscard]] double value(WordId w, double otherwise = 0) const noexcept {
    return has(w) ? words[w].value : otherwise;
  }
  void set(WordId w, const Word& value) {
    present.set(w);
    words[w] = value;
  }
  void erase(WordId w) { present.reset(w); }
};

}  // namespace ncpost::gcode::detail
