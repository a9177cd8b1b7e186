#include "lexer.hpp"

#include <cstring>

namespace ncpost::gcode::detail {

std::string_view LineCursor::next(std::uint32_t& number) noexcept {
  const std::size_t start = offset_;
  const void* nl = std::memchr(text_.data() + start, '\n', text_.size() - start);
  std::size_t end =
      nl ? static_cast<std::size_t>(static_cast<const char*>(nl) - text_.data()) : text_.size();
  offset_ = nl ? end + 1 : end;
  if (end > start && text_[end - 1] == '\r') --end;
  number = ++line_;
  return text_.substr(start, end - start);
}

Line& Line::operator=(const Line& other) {
  if (this == &other) return *this;
  LineFields::operator=(other);
  // A normalised text is a view of the buffer: of this line's own copy now.
  if (!text_is_raw) text = std::string_view(buffer).substr(0, other.text.size());
  return *this;
}

void Line::set_text(std::string_view edited) {
  if (text_is_raw) {
    if (columns.size() < text.size()) columns.resize(text.size());
    for (std::size_t i = 0; i < text.size(); ++i) columns[i] = static_cast<std::uint32_t>(i + 1);
  }
  buffer.assign(edited);
  text = buffer;
  text_is_raw = false;
}

Lexing::Lexing(const Dialect& d) : dialect(d) {
  const bool squeeze = d.ignore_whitespace;  // blanks may stand inside words, and are dropped
  for (std::size_t c = 0; c < 256; ++c) {
    const char ch = static_cast<char>(c);
    upper[c] = ch == '\t' ? ' ' : ncpost::gcode::detail::upper(ch);
    advance[c] = (ch == ' ' || ch == '\t') && squeeze ? 0 : 1;
    std::uint8_t k = Plain;
    if (ch == ' ' || ch == '\t')
      k = Space;
    else if (ch == '(' && d.parenthesis_comments)
      k = OpenComment;
    else if (ch == ';' && d.semicolon_comments)
      k = Semicolon;
    else if (ch == '*' && d.checksums && d.syntax != Syntax::Klartext)
      k = Checksum;
    else if (ch == '"' && !squeeze)
      k = Quote;
    classes[c] = k;
    if (ch >= 'A' && ch <= 'Z')
      plain[c] = PlainLetter;
    else if (is_digit(ch) || ch == '.' || ch == '-' || ch == '+')
      plain[c] = PlainNumber;
    else if (ch == ' ')
      plain[c] = PlainBlank;
  }
  for (std::uint8_t before = PlainLetter; before <= PlainBlank; ++before) {
    for (std::uint8_t after = PlainLetter; after <= PlainBlank; ++after) {
      // Where blanks are dropped, a letter is followed by its number, and a number after a
      // blank would join the word before it.
      const bool joins = (before == PlainLetter && after != PlainNumber) ||
                         (before == PlainBlank && after == PlainNumber);
      plain_pair[before * 4u + after] = squeeze && joins ? 0 : 1;
    }
  }
  plain_first[PlainLetter] = plain_first[PlainNumber] = 1;
  plain_last[PlainNumber] = 1;
  plain_last[PlainLetter] = squeeze ? 0 : 1;
}

namespace {

// True when normalising `raw` would leave it as it is, blanks aside: only upper-case letters,
// numbers and blanks, none first or last. Where blanks are dropped they must also stand only
// between words of one letter and a number ("X1 Y-2", not "G 1", "X1 2" or "O100 SUB"), so
// that keeping them changes how no word reads (the block reader steps over blanks between
// words). Without a branch per byte: each pair of neighbours is looked up in a table.
bool is_plain(std::string_view raw, const Lexing& lexing) noexcept {
  const std::size_t n = raw.size();
  if (n == 0) return true;
  const auto* const bytes = reinterpret_cast<const unsigned char*>(raw.data());
  unsigned ok = lexing.plain_first[lexing.plain[bytes[0]]];
  for (std::size_t i = 1; i < n; ++i)
    ok &= lexing.plain_pair[lexing.plain[bytes[i - 1]] * 4u + lexing.plain[bytes[i]]];
  return (ok & lexing.plain_last[lexing.plain[bytes[n - 1]]]) != 0;
}

}  // namespace

void normalise(std::string_view raw, const Lexing& lexing, Line& line) {
  const Dialect& dialect = lexing.dialect;
  line.raw = raw;
  line.comments.clear();
  line.block_delete = false;
  line.has_error = false;
  line.error = {};
  if (is_plain(raw, lexing)) {
    line.text = raw;
    line.text_is_raw = true;
    return;
  }
  line.text_is_raw = false;
  // The text is at most as long as the raw line: written by index into buffers sized once (the
  // Line is reused from line to line, so this allocates only for a longer line than before).
  const std::size_t n = raw.size();
  line.buffer.resize(n);
  if (line.columns.size() < n) line.columns.resize(n);
  char* text = line.buffer.data();
  std::uint32_t* columns = line.columns.data();
  std::size_t out = 0;
  auto finish = [&]() {
    // Trailing blanks carry nothing.
    while (out > 0 && text[out - 1] == ' ') --out;
    line.text = std::string_view(line.buffer).substr(0, out);
  };
  std::size_t i = 0;
  while (i < n && (raw[i] == ' ' || raw[i] == '\t')) ++i;
  if (i < n && raw[i] == '/' && dialect.block_delete) {
    line.block_delete = true;
    ++i;
    // Sinumerik and FANUC skip levels /1 ... /9: the level digit belongs to the '/'.
    if (!dialect.ignore_whitespace && i < n && is_digit(raw[i])) ++i;
  }
  bool in_string = false;
  std::uint32_t string_column = 0;
  for (; i < n; ++i) {
    const auto c = static_cast<unsigned char>(raw[i]);
    const auto column = static_cast<std::uint32_t>(i + 1);
    if (in_string) {
      text[out] = raw[i];
      columns[out++] = column;
      if (c == '"') in_string = false;
      continue;
    }
    const std::uint8_t kind = lexing.classes[c];
    if (kind <= Lexing::Space) {
      // Most bytes: written (upper case, a tab as a blank) and kept unless a dropped blank.
      text[out] = lexing.upper[c];
      columns[out] = column;
      out += lexing.advance[c];
      continue;
    }
    switch (kind) {
      case Lexing::OpenComment: {
        const std::size_t close = raw.find(')', i + 1);
        if (close == std::string_view::npos) {
          line.has_error = true;
          line.error.column = column;
          line.error.unclosed_comment = true;
          finish();
          return;
        }
        line.comments.push_back({raw.substr(i + 1, close - i - 1), column, false});
        i = close;
        continue;
      }
      case Lexing::Semicolon:
        line.comments.push_back({raw.substr(i + 1), column, true});
        i = n;
        break;
      case Lexing::Checksum:  // '*NN' checksum to the line end
        i = n;
        break;
      case Lexing::Quote:
      default:
        in_string = true;
        string_column = column;
        text[out] = raw[i];
        columns[out++] = column;
        continue;
    }
    break;
  }
  if (in_string) {
    line.has_error = true;
    line.error.column = string_column;
    line.error.unclosed_string = true;
  }
  finish();
}

}  // namespace ncpost::gcode::detail
