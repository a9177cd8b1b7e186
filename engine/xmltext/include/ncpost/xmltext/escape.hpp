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

}  // namespace ncpost::xmltext
