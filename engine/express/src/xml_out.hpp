#pragma once
// A minimal streaming XML writer: elements are appended to a string buffer as they are opened
// and closed (no DOM), with two-space indentation. Text and attribute values are escaped, and
// anything that XML 1.0 cannot carry (control characters, malformed UTF-8) becomes U+FFFD, so
// the output is always well-formed whatever the schema's string literals contain.

#include <initializer_list>
#include <string>
#include <string_view>
#include <vector>

namespace ncpost::express::detail {

// Appends `text` to `out`, escaped for element content (quote = false) or for a double-quoted
// attribute value (quote = true): xmltext::append_escaped, the project's one XML escaper.
void append_escaped(std::string& out, std::string_view text, bool quote);

struct XmlAttribute {
  std::string_view name;
  std::string_view value;
};

class XmlOut {
 public:
  explicit XmlOut(std::string& out) : out_(out) {}

  void declaration();
  // <name express-production="production" a="v"...>
  void open(std::string_view name, std::string_view production,
            std::initializer_list<XmlAttribute> attributes = {});
  void close();
  // <name express-production="production">text</name>, or an empty element if text is empty.
  void leaf(std::string_view name, std::string_view production, std::string_view text,
            std::initializer_list<XmlAttribute> attributes = {});
  [[nodiscard]] std::size_t depth() const noexcept { return open_.size(); }

 private:
  void start_tag(std::string_view name, std::string_view production,
                 std::initializer_list<XmlAttribute> attributes);
  void indent();

  std::string& out_;
  std::vector<std::string_view> open_;  // names of the open elements (all string literals)
};

}  // namespace ncpost::express::detail
