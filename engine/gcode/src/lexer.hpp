#pragma once
// Lines of program text, and each line in the form the block reader works on: comments taken
// out (kept with their original text and column), letters in upper case, and — for dialects
// where spaces may stand inside words (`X 1 0 . 5`, `X [ - #6 / 2. ]`) — without spaces.
// Every character of the normalised text knows its column in the original line, so
// diagnostics point at the source. One Line is reused for every block: no allocation per line
// once it has grown to the longest line.

#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "ncpost/gcode/dialect.hpp"

namespace ncpost::gcode::detail {

struct Comment {
  std::string_view text;  // without its delimiters, as written
  std::uint32_t column = 0;
  bool semicolon = false;  // `;` to the end of the line (not `( )`)
};

struct LexError {
  std::uint32_t column = 0;
  bool unclosed_comment = false;
  bool unclosed_string = false;
};

// What a Line holds, copied member by member; Line re-points `text` after a copy.
struct LineFields {
  std::uint32_t number = 0;  // 1-based line number in its file
  std::string_view raw;      // the line as written, without the line end
  // Normalised: `raw` itself when normalising would change nothing (most lines a CAM system
  // writes), else `buffer`.
  std::string_view text;
  std::string buffer;
  // columns[i]: 1-based column of text[i] in raw, for i < text.size(), unless text is raw (the
  // vector only grows: entries past the text are left from longer lines, and not zeroed for
  // every line).
  std::vector<std::uint32_t> columns;
  bool text_is_raw = false;
  std::vector<Comment> comments;
  bool block_delete = false;  // '/' first
  bool has_error = false;
  LexError error{};
};

struct Line : LineFields {
  Line() = default;
  Line(const Line& other) { *this = other; }
  Line& operator=(const Line& other);
  Line(Line&&) = delete;  // a moved buffer need not keep its address: copy instead
  Line& operator=(Line&&) = delete;

  // Replaces the text with `edited`, of the same length, each character keeping its column.
  void set_text(std::string_view edited);
  // 1-based column in `raw` of normalised position `i` (the end of the line past the text).
  [[nodiscard]] std::uint32_t column(std::size_t i) const noexcept {
    if (i >= text.size()) return static_cast<std::uint32_t>(raw.size() + 1);
    return text_is_raw ? static_cast<std::uint32_t>(i + 1) : columns[i];
  }
};

// What normalising does with each byte in one dialect, looked up once per character instead
// of asking the dialect's rules for each (made once per reading).
struct Lexing {
  enum Class : std::uint8_t { Plain, Space, OpenComment, Semicolon, Checksum, Quote };
  explicit Lexing(const Dialect& dialect);
  const Dialect& dialect;
  std::array<std::uint8_t, 256> classes{};
  std::array<char, 256> upper{};  // a Plain or Space byte as written into the text
  // 0 for a byte that is dropped (a blank where blanks may stand inside words), else 1.
  std::array<std::uint8_t, 256> advance{};
  // What a byte is in a line that normalising leaves as it is (upper-case letters, numbers and
  // single blanks between words): not in such a line, a letter, a number, a blank.
  enum PlainKind : std::uint8_t { NotPlain, PlainLetter, PlainNumber, PlainBlank };
  std::array<std::uint8_t, 256> plain{};
  // 1 where a line of plain bytes may have these neighbours (before × 4 + after), may start
  // with, and may end with this kind of byte.
  std::array<std::uint8_t, 16> plain_pair{};
  std::array<std::uint8_t, 4> plain_first{};
  std::array<std::uint8_t, 4> plain_last{};
};

// Normalises `raw` into `line` (its number is left as set).
void normalise(std::string_view raw, const Lexing& lexing, Line& line);

// Walks a text line by line; offsets let control flow jump back and forth without copying.
class LineCursor {
 public:
  LineCursor() = default;
  explicit LineCursor(std::string_view text) : text_(text) {}

  [[nodiscard]] bool at_end() const noexcept { return offset_ >= text_.size(); }
  // The next line (without '\n' or "\r\n") and its number; advances.
  std::string_view next(std::uint32_t& number) noexcept;
  [[nodiscard]] std::size_t offset() const noexcept { return offset_; }
  [[nodiscard]] std::uint32_t line_number() const noexcept { return line_; }
  // Positions the cursor so that next() returns the line starting at `offset`, numbered `line`.
  void seek(std::size_t offset, std::uint32_t line) noexcept {
    offset_ = offset;
    line_ = line - 1;
  }
  [[nodiscard]] std::string_view text() const noexcept { return text_; }

 private:
  std::string_view text_;
  std::size_t offset_ = 0;
  std::uint32_t line_ = 0;  // number of the line last returned
};

[[nodiscard]] constexpr char upper(char c) noexcept {
  return (c >= 'a' && c <= 'z') ? static_cast<char>(c - 'a' + 'A') : c;
}
[[nodiscard]] constexpr bool is_letter(char c) noexcept {
  return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z');
}
[[nodiscard]] constexpr bool is_digit(char c) noexcept {
  return c >= '0' && c <= '9';
}

}  // namespace ncpost::gcode::detail
