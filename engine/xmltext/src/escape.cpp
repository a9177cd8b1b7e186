#include "ncpost/xmltext/escape.hpp"

#include "ncpost/xmltext/utf8.hpp"

namespace ncpost::xmltext {
namespace {

constexpr std::string_view kReplacement = "\xEF\xBF\xBD";

}  // namespace

void append_escaped(std::string& out, std::string_view text, bool in_attribute) {
  std::size_t i = 0;
  while (i < text.size()) {
    // Copy the longest run that needs nothing, in one append.
    std::size_t run = i;
    while (run < text.size()) {
      const auto c = static_cast<unsigned char>(text[run]);
      if (c < 0x20 || c >= 0x80 || c == '<' || c == '>' || c == '&' || c == '"') break;
      ++run;
    }
    out.append(text.data() + i, run - i);
    i = run;
    if (i >= text.size()) break;
    const auto c = static_cast<unsigned char>(text[i]);
    switch (c) {
      case '<':
        out += "&lt;";
        ++i;
        continue;
      case '>':
        out += "&gt;";
        ++i;
        continue;
      case '&':
        out += "&amp;";
        ++i;
        continue;
      case '"':
        out += in_attribute ? "&quot;" : "\"";
        ++i;
        continue;
      case '\t':
      case '\n':
        if (in_attribute)
          out += c == '\t' ? "&#9;" : "&#10;";
        else
          out.push_back(static_cast<char>(c));
        ++i;
        continue;
      case '\r':
        out += "&#13;";
        ++i;
        continue;
      default:
        break;
    }
    if (c < 0x20) {
      out += kReplacement;
      ++i;
      continue;
    }
    char32_t cp = 0;
    std::size_t len = utf8_sequence_length(text, i, cp);
    if (cp == 0xFFFE || cp == 0xFFFF) len = 0;  // valid UTF-8, but not XML characters
    if (len == 0) {
      out += kReplacement;
      ++i;
    } else {
      out.append(text.data() + i, len);
      i += len;
    }
  }
}

}  // namespace ncpost::xmltext
