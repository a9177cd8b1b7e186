#pragma once
// Escaping text for XML 1.0, shared by every stage that writes XML as a stream (no DOM).
// Anything XML 1.0 cannot carry (control characters other than tab and newline, malformed
// UTF-8) becomes U+FFFD, so the output is well-formed whatever the input held.

#include <string>
#include <string_view>

namespace ncpost::xmltext {

// Appends `text` escaped for element content (`in_attribute` false) or for a double-quoted
// attribute value (true).
void append_escaped(std::string& out, std::string_view text, bool in_attribute = false);

// Appends the characters an XML parser reads back from append_escaped's output: `text` with
// the same U+FFFD replacements, nothing escaped. For building a document tree directly, so
// that it holds exactly what parsing the escaped text would give.
void append_characters(std::string& out, std::string_view text);

// Whether `text` is printable ASCII without markup characters: then every form above is
// `text` itself, and a caller may use it as it is.
[[nodiscard]] constexpr bool is_plain(std::string_view text) noexcept {
  for (const char ch : text) {
    const auto c = static_cast<unsigned char>(ch);
    if (c < 0x20 || c >= 0x80 || c == '<' || c == '>' || c == '&' || c == '"') return false;
  }
  return true;
}

}  // namespace ncpost::xmltext
