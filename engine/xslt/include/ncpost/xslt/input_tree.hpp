#pragma once
// A document for transform() built event by event in memory, instead of XML text that
// transform() would parse. In: elements, attributes and character data, in document order.
// Out: a libxml2 tree whose nodes live in this object's arena, equal to the tree libxml2 would
// parse from the same events written as text (whitespace text nodes and element line numbers
// included), so a stylesheet cannot tell the two apart. Parsing and freeing a parsed tree cost
// the renderer more than a cheap stylesheet's whole run; building here costs a few hundred
// instructions per element, and clear() keeps the memory for the next document.
//
// Values and character data are given as written (not escaped); characters XML 1.0 cannot
// carry become U+FFFD, as the escaper writes them (xmltext). Text outside the root element is
// ignored, as a parser ignores whitespace there. No namespaces, comments or processing
// instructions: the canonical program's XML form has none.

#include <cstddef>
#include <memory>
#include <string>
#include <string_view>

namespace ncpost::xslt {

class InputTree {
 public:
  InputTree();
  ~InputTree();
  InputTree(const InputTree&) = delete;
  InputTree& operator=(const InputTree&) = delete;

  void start_element(std::string_view name);
  // For the element just started, before its first child.
  void attribute(std::string_view name, std::string_view value);
  void text(std::string_view characters);
  // Ends the innermost open element.
  void end_element();

  // Forgets the document; the arena's first block is kept for the next one.
  void clear();
  // One root element, closed.
  [[nodiscard]] bool complete() const noexcept;
  // Bytes of arena in use.
  [[nodiscard]] std::size_t bytes() const noexcept;

  // The document as XML text: what a parser would read back into the same tree. transform()
  // falls back to it for a stylesheet that strips whitespace (libxslt then frees input nodes,
  // which an arena cannot allow).
  [[nodiscard]] std::string to_xml() const;
  // Every node with its type, name, value and (for elements) line, one per line: what the tests
  // compare with describe_parsed().
  [[nodiscard]] std::string describe() const;

  struct Impl;

 private:
  friend struct Access;
  std::unique_ptr<Impl> impl_;
};

// describe() of the tree libxml2 parses from `xml` with transform()'s options; empty when it
// does not parse. For tests.
[[nodiscard]] std::string describe_parsed(std::string_view xml);

}  // namespace ncpost::xslt
