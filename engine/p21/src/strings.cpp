#include "ncpost/p21/strings.hpp"

#include <cstdint>

#include "ncpost/xmltext/utf8.hpp"

namespace ncpost::p21 {
namespace {

constexpr char32_t kReplacement = 0xFFFD;

int hex_value(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  return -1;
}

// Reads `digits` hex digits at raw[pos]; returns -1 when they are not all hex.
std::int64_t read_hex(std::string_view raw, std::size_t pos, std::size_t digits) {
  if (pos + digits > raw.size()) return -1;
  std::int64_t value = 0;
  for (std::size_t i = 0; i < digits; ++i) {
    const int h = hex_value(raw[pos + i]);
    if (h < 0) return -1;
    value = value * 16 + h;
  }
  return value;
}

// The decoder and the checker walk the same grammar; `Sink` receives code points or problems.
template <typename Sink>
void walk(std::string_view raw, Sink& sink) {
  char32_t page_offset = 0x80;  // \S\ adds 0x80 within ISO 8859-1 unless \P?\ switched pages
  std::size_t i = 0;
  const std::size_t n = raw.size();
  while (i < n) {
    const char c = raw[i];
    if (c == '\'') {
      // The lexer only lets doubled apostrophes through.
      sink.code_point(U'\'');
      i += (i + 1 < n && raw[i + 1] == '\'') ? 2 : 1;
      continue;
    }
    if (c == '\n' || c == '\r') {  // line breaks are not part of the value
      ++i;
      continue;
    }
    if (c != '\\') {
      const auto uc = static_cast<unsigned char>(c);
      if (uc >= 0x80) {
        char32_t cp = 0;
        const std::size_t len = xmltext::utf8_sequence_length(raw, i, cp);
        if (len == 0) {
          sink.problem(i,
                       "byte 0x" + std::string{"0123456789ABCDEF"[uc >> 4]} +
                           "0123456789ABCDEF"[uc & 15] + " is not valid UTF-8",
                       StringProblem::Encoding);
          sink.code_point(kReplacement);
          ++i;
        } else {
          sink.code_point(cp);
          i += len;
        }
        continue;
      }
      if (uc < 0x20 || uc == 0x7F) {
        sink.problem(i, "control character in a string; use \\X\\ to write it",
                     StringProblem::Encoding);
        sink.code_point(kReplacement);
        ++i;
        continue;
      }
      sink.code_point(static_cast<char32_t>(uc));
      ++i;
      continue;
    }
    // A control directive.
    const std::string_view rest = raw.substr(i);
    if (rest.starts_with("\\\\")) {
      sink.code_point(U'\\');
      i += 2;
    } else if (rest.starts_with("\\S\\") && rest.size() >= 4) {
      sink.code_point(static_cast<char32_t>(static_cast<unsigned char>(rest[3])) + page_offset);
      i += 4;
    } else if (rest.size() >= 4 && rest[1] == 'P' && rest[3] == '\\' && rest[2] >= 'A' &&
               rest[2] <= 'I') {
      // \PA\ .. \PI\ select ISO 8859-1 .. -9. Only part 1 maps linearly to Unicode; other
      // pages are decoded as part 1 and reported, rather than mis-decoded silently.
      if (rest[2] != 'A')
        sink.problem(i,
                     "ISO 8859 page \\P" + std::string(1, rest[2]) + "\\ is decoded as ISO 8859-1",
                     StringProblem::Encoding);
      i += 4;
    } else if (rest.starts_with("\\X\\")) {
      const std::int64_t v = read_hex(raw, i + 3, 2);
      if (v < 0) {
        sink.problem(i, "\\X\\ must be followed by two hex digits", StringProblem::Malformed);
        sink.code_point(kReplacement);
        i += 3;
      } else {
        sink.code_point(static_cast<char32_t>(v));
        i += 5;
      }
    } else if (rest.starts_with("\\X2\\") || rest.starts_with("\\X4\\")) {
      const std::size_t digits = rest[2] == '2' ? 4 : 8;
      std::size_t j = i + 4;
      char32_t pending_high = 0;
      bool ok = true;
      while (j < n && raw[j] != '\\') {
        const std::int64_t v = read_hex(raw, j, digits);
        if (v < 0) {
          ok = false;
          break;
        }
        auto cp = static_cast<char32_t>(v);
        j += digits;
        if (digits == 4 && cp >= 0xD800 && cp <= 0xDBFF) {
          pending_high = cp;
          continue;
        }
        if (digits == 4 && cp >= 0xDC00 && cp <= 0xDFFF && pending_high != 0) {
          cp = 0x10000 + ((pending_high - 0xD800) << 10) + (cp - 0xDC00);
        } else if (pending_high != 0) {
          sink.code_point(kReplacement);
        }
        pending_high = 0;
        sink.code_point(cp);
      }
      if (pending_high != 0) sink.code_point(kReplacement);
      if (!ok || !raw.substr(j).starts_with("\\X0\\")) {
        sink.problem(i,
                     std::string("\\X") + rest[2] + "\\ run must hold groups of " +
                         std::to_string(digits) + " hex digits and end with \\X0\\",
                     StringProblem::Malformed);
        sink.code_point(kReplacement);
        // Skip to the end of the broken run so the rest of the string still decodes.
        while (j < n && raw[j] != '\\') ++j;
        i = raw.substr(j).starts_with("\\X0\\") ? j + 4 : j + (j < n ? 1 : 0);
      } else {
        i = j + 4;
      }
    } else if (rest.starts_with("\\N\\") || rest.starts_with("\\F\\")) {
      i += 3;  // print control directives carry no content
    } else {
      // Writers often put Windows paths in unescaped. The meaning is plain, so the backslash is
      // kept as a literal and the reader warns instead of rejecting the file.
      sink.problem(i,
                   "backslash that starts no control directive is read as a literal '\\'; "
                   "write \\\\ for a backslash",
                   StringProblem::LoneBackslash);
      sink.code_point(U'\\');
      ++i;
    }
  }
}

struct DecodeSink {
  std::string& out;
  void code_point(char32_t cp) { append_utf8(cp, out); }
  void problem(std::size_t, const std::string&, StringProblem::Kind) {}
};

struct CheckSink {
  StringProblem result;
  void code_point(char32_t) {}
  void problem(std::size_t at, const std::string& what, StringProblem::Kind kind) {
    // The most serious problem is reported, the first of its kind.
    if (kind > result.kind) result = {kind, at, what};
  }
};

}  // namespace

void append_utf8(char32_t cp, std::string& out) {
  if (cp > 0x10FFFF || (cp >= 0xD800 && cp <= 0xDFFF)) cp = kReplacement;
  if (cp < 0x80) {
    out.push_back(static_cast<char>(cp));
  } else if (cp < 0x800) {
    out.push_back(static_cast<char>(0xC0 | (cp >> 6)));
    out.push_back(static_cast<char>(0x80 | (cp & 0x3F)));
  } else if (cp < 0x10000) {
    out.push_back(static_cast<char>(0xE0 | (cp >> 12)));
    out.push_back(static_cast<char>(0x80 | ((cp >> 6) & 0x3F)));
    out.push_back(static_cast<char>(0x80 | (cp & 0x3F)));
  } else {
    out.push_back(static_cast<char>(0xF0 | (cp >> 18)));
    out.push_back(static_cast<char>(0x80 | ((cp >> 12) & 0x3F)));
    out.push_back(static_cast<char>(0x80 | ((cp >> 6) & 0x3F)));
    out.push_back(static_cast<char>(0x80 | (cp & 0x3F)));
  }
}

void decode_string(std::string_view raw, std::string& out) {
  DecodeSink sink{out};
  walk(raw, sink);
}

StringProblem check_string(std::string_view raw) {
  CheckSink sink;
  walk(raw, sink);
  return sink.result;
}

void encode_string(std::string_view utf8, std::string& out) {
  static constexpr char kHex[] = "0123456789ABCDEF";
  std::size_t i = 0;
  bool in_x2 = false;
  auto close_run = [&] {
    if (in_x2) out += "\\X0\\";
    in_x2 = false;
  };
  while (i < utf8.size()) {
    const auto uc = static_cast<unsigned char>(utf8[i]);
    if (uc >= 0x20 && uc < 0x7F) {
      close_run();
      if (uc == '\'')
        out += "''";
      else if (uc == '\\')
        out += "\\\\";
      else
        out.push_back(static_cast<char>(uc));
      ++i;
      continue;
    }
    char32_t cp = 0;
    std::size_t len = xmltext::utf8_sequence_length(utf8, i, cp);
    if (len == 0) {
      cp = kReplacement;
      len = 1;
    }
    i += len;
    if (cp > 0xFFFF) {
      close_run();
      out += "\\X4\\";
      for (int shift = 28; shift >= 0; shift -= 4) out.push_back(kHex[(cp >> shift) & 0xF]);
      out += "\\X0\\";
      continue;
    }
    if (!in_x2) out += "\\X2\\";
    in_x2 = true;
    for (int shift = 12; shift >= 0; shift -= 4) out.push_back(kHex[(cp >> shift) & 0xF]);
  }
  close_run();
}

}  // namespace ncpost::p21
