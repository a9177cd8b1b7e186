#include "ncpost/xmltext/escape.hpp"

#include "ncpost/xmltext/utf8.hpp"

namespace ncpost::xmltext {
namespace {

constexpr std::string_view kReplacement = "\xEF\xBF\xBD";

enum class Form { Content, Attribute, Characters };

// The one walk over the text: runs that need nothing are copied whole; markup characters are
// escaped unless `form` is Characters; what XML 1.0 cannot carry becomes U+FFFD in every form.
void append(std::string& out, std::string_view text, Form form) {
  const bool escape = form != Form::Characters;
  const bool in_attribute = form == Form::Attribute;
  std::size_t i = 0;
  while (i < text.size()) {
    std::size_t run = i;
    while (run < text.size()) {
      const auto c = static_cast<unsigned char>(text[run]);
      if (c < 0x20 || c >= 0x80 || (escape && (c == '<' || c == '>' || c == '&' || c == '"')))
        break;
      ++run;
    }
    out.append(text.data() + i, run - i);
    i = run;
    if (i >= text.size()) break;
    const auto c = static_cast<unsigned char>(text[i]);
    if (escape) {
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
        default:
          break;
      }
    }
    if (c == '\t' || c == '\n' || c == '\r') {
      // Kept as they are in content; escaped in attributes (a parser would turn a literal one
      // into a space) and for CR (a parser would drop a literal one before LF).
      if (!escape || (!in_attribute && c != '\r'))
        out.push_back(static_cast<char>(c));
      else
        out += c == '\t' ? "&#9;" : c == '\n' ? "&#10;" : "&#13;";
      ++i;
      continue;
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

}  // namespace

void append_escaped(std::string& out, std::string_view text, bool in_attribute) {
  append(out, text, in_attribute ? Form::Attribute : Form::Content);
}

void append_characters(std::string& out, std::string_view text) {
  append(out, text, Form::Characters);
}

}  // namespace ncpost::xmltext
