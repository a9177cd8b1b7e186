// InputTree: libxml2 nodes bump-allocated in blocks that clear() reuses. libxml2 never frees
// them: transform() lends the tree to a document shell (xmlNewDoc) for one run and takes it
// back before freeing the shell, and stylesheets under which libxslt would free input nodes
// (xsl:strip-space) are given the text form instead (transform.cpp).

#include "ncpost/xslt/input_tree.hpp"

#include <libxml/parser.h>
#include <libxml/parserInternals.h>  // xmlStringText, the name of text nodes
#include <libxml/tree.h>

#include <algorithm>
#include <climits>
#include <cstring>
#include <vector>

#include "internal.hpp"
#include "ncpost/xmltext/escape.hpp"

namespace ncpost::xslt {
namespace {

constexpr std::size_t kBlockBytes = std::size_t{64} << 10;
constexpr unsigned kMaxLine = USHRT_MAX;  // libxml2 stores larger line numbers as this

const xmlChar* as_xml(const char* s) {
  return reinterpret_cast<const xmlChar*>(s);
}

// Visits the tree in document order with an explicit stack of open elements.
template <class Enter, class Leave>
void walk(xmlNodePtr root, Enter enter, Leave leave) {
  std::vector<xmlNodePtr> stack;
  for (xmlNodePtr n = root; n != nullptr;) {
    enter(n, stack.size());
    if (n->type == XML_ELEMENT_NODE && n->children != nullptr) {
      stack.push_back(n);
      n = n->children;
      continue;
    }
    if (n->type == XML_ELEMENT_NODE) leave(n, stack.size());
    while (n != nullptr && n->next == nullptr && !stack.empty()) {
      n = stack.back();
      stack.pop_back();
      leave(n, stack.size());
    }
    n = (n == nullptr || n == root) ? nullptr : n->next;
  }
}

}  // namespace

struct InputTree::Impl {
  std::vector<std::unique_ptr<std::byte[]>> blocks;
  std::vector<std::unique_ptr<std::byte[]>> large;  // pieces bigger than a quarter block
  std::size_t block = 0;                            // index of the block being filled
  std::size_t used = 0;                             // bytes used in it
  std::size_t total = 0;                            // bytes handed out since clear()

  xmlNodePtr root = nullptr;
  xmlNodePtr open = nullptr;  // innermost open element; null outside the root
  xmlAttrPtr last_attribute = nullptr;
  std::string pending;  // character data gathered until the next tag
  unsigned pending_line = 0;
  unsigned line = 1;
  bool malformed = false;  // a second root, an end without a start

  void* allocate(std::size_t bytes) {
    bytes = (bytes + 7) & ~std::size_t{7};
    total += bytes;
    if (bytes > kBlockBytes / 4) {
      large.push_back(std::unique_ptr<std::byte[]>(new std::byte[bytes]));  // not zeroed
      return large.back().get();
    }
    if (blocks.empty() || used + bytes > kBlockBytes) {
      if (!blocks.empty()) ++block;
      if (block == blocks.size())
        blocks.push_back(std::unique_ptr<std::byte[]>(new std::byte[kBlockBytes]));  // not zeroed
      used = 0;
    }
    void* p = blocks[block].get() + used;
    used += bytes;
    return p;
  }

  template <class T>
  T* node() {
    auto* n = static_cast<T*>(allocate(sizeof(T)));
    std::memset(n, 0, sizeof(T));
    return n;
  }

  // A NUL-terminated copy holding what a parser reads back from the escaped text.
  xmlChar* characters(std::string_view text) {
    if (xmltext::is_plain(text)) return copy(text);
    std::string clean;
    xmltext::append_characters(clean, text);
    return copy(clean);
  }
  xmlChar* copy(std::string_view text) {
    auto* p = static_cast<char*>(allocate(text.size() + 1));
    if (!text.empty()) std::memcpy(p, text.data(), text.size());
    p[text.size()] = '\0';
    return reinterpret_cast<xmlChar*>(p);
  }

  xmlNodePtr text_node(std::string_view content, xmlNodePtr parent, unsigned at_line) {
    auto* t = node<xmlNode>();
    t->type = XML_TEXT_NODE;
    t->name = xmlStringText;
    t->content = copy(content);
    t->parent = parent;
    t->line = static_cast<unsigned short>(std::min(at_line, kMaxLine));
    return t;
  }

  static void append_child(xmlNodePtr parent, xmlNodePtr child) {
    child->parent = parent;
    if (parent->last == nullptr) {
      parent->children = child;
    } else {
      parent->last->next = child;
      child->prev = parent->last;
    }
    parent->last = child;
  }

  void flush_text() {
    if (pending.empty()) return;
    if (open != nullptr) append_child(open, text_node(pending, open, pending_line));
    pending.clear();
  }

  void reset() {
    block = 0;
    used = 0;
    total = 0;
    large.clear();
    root = nullptr;
    open = nullptr;
    last_attribute = nullptr;
    pending.clear();
    line = 1;
    malformed = false;
  }

  // Lends the tree to a new document shell for one transform.
  xmlDocPtr lend(const std::string& url) const {
    xmlDocPtr doc = xmlNewDoc(as_xml("1.0"));
    if (doc == nullptr) return nullptr;
    doc->URL = xmlStrdup(as_xml(url.c_str()));
    doc->children = doc->last = root;
    set_document(doc);
    root->parent = reinterpret_cast<xmlNodePtr>(doc);
    return doc;
  }
  // Takes it back and frees the shell.
  void take_back(xmlDocPtr doc) const {
    if (doc == nullptr) return;
    doc->children = doc->last = nullptr;
    root->parent = nullptr;
    xmlFreeDoc(doc);
  }

  void set_document(xmlDocPtr doc) const {
    walk(
        root,
        [doc](xmlNodePtr n, std::size_t) {
          n->doc = doc;
          for (xmlAttrPtr a = n->properties; a != nullptr; a = a->next) {
            a->doc = doc;
            for (xmlNodePtr v = a->children; v != nullptr; v = v->next) v->doc = doc;
          }
        },
        [](xmlNodePtr, std::size_t) {});
  }
};

InputTree::InputTree() : impl_(std::make_unique<Impl>()) {}
InputTree::~InputTree() = default;

void InputTree::start_element(std::string_view name) {
  Impl& t = *impl_;
  t.flush_text();
  auto* e = t.node<xmlNode>();
  e->type = XML_ELEMENT_NODE;
  e->name = t.copy(name);
  e->line = static_cast<unsigned short>(std::min(t.line, kMaxLine));
  if (t.open != nullptr) {
    Impl::append_child(t.open, e);
  } else if (t.root == nullptr) {
    t.root = e;
  } else {
    t.malformed = true;  // a second root element: kept out of the document
  }
  t.open = e;
  t.last_attribute = nullptr;
}

void InputTree::attribute(std::string_view name, std::string_view value) {
  Impl& t = *impl_;
  xmlNodePtr e = t.open;
  if (e == nullptr || e->children != nullptr || !t.pending.empty()) {
    t.malformed = true;
    return;
  }
  auto* a = t.node<xmlAttr>();
  a->type = XML_ATTRIBUTE_NODE;
  a->name = t.copy(name);
  a->parent = e;
  // The parser gives every attribute one text child, also an empty one.
  xmlNodePtr value_node = t.text_node({}, reinterpret_cast<xmlNodePtr>(a), t.line);
  value_node->content = t.characters(value);
  a->children = a->last = value_node;
  if (t.last_attribute == nullptr) {
    e->properties = a;
  } else {
    t.last_attribute->next = a;
    a->prev = t.last_attribute;
  }
  t.last_attribute = a;
}

void InputTree::text(std::string_view characters) {
  Impl& t = *impl_;
  if (t.open != nullptr && !characters.empty()) {
    if (t.pending.empty()) t.pending_line = t.line;
    if (xmltext::is_plain(characters))
      t.pending.append(characters);
    else
      xmltext::append_characters(t.pending, characters);
  }
  t.line += static_cast<unsigned>(std::count(characters.begin(), characters.end(), '\n'));
}

void InputTree::end_element() {
  Impl& t = *impl_;
  t.flush_text();
  if (t.open == nullptr) {
    t.malformed = true;
    return;
  }
  t.open = t.open->parent;
  t.last_attribute = nullptr;
}

void InputTree::clear() {
  impl_->reset();
}

bool InputTree::complete() const noexcept {
  return impl_->root != nullptr && impl_->open == nullptr && !impl_->malformed;
}

std::size_t InputTree::bytes() const noexcept {
  return impl_->total;
}

namespace {

std::string_view view(const xmlChar* s) {
  return s == nullptr ? std::string_view("(null)") : reinterpret_cast<const char*>(s);
}

std::string describe_tree(xmlNodePtr root) {
  std::string out;
  walk(
      root,
      [&out](xmlNodePtr n, std::size_t depth) {
        out.append(depth * 2, ' ');
        if (n->type == XML_ELEMENT_NODE) {
          out += "element ";
          out += view(n->name);
          out += " line " + std::to_string(n->line) + '\n';
          for (xmlAttrPtr a = n->properties; a != nullptr; a = a->next) {
            out.append(depth * 2 + 2, ' ');
            out += "@";
            out += view(a->name);
            for (xmlNodePtr v = a->children; v != nullptr; v = v->next) {
              out += v->type == XML_TEXT_NODE ? " text=[" : " other=[";
              out += view(v->content);
              out += ']';
            }
            out += '\n';
          }
        } else {
          out +=
              n->type == XML_TEXT_NODE ? "text [" : "node type " + std::to_string(n->type) + " [";
          out += view(n->content);
          out += "]\n";
        }
      },
      [](xmlNodePtr, std::size_t) {});
  return out;
}

}  // namespace

std::string InputTree::to_xml() const {
  std::string out;
  if (impl_->root == nullptr) return out;
  walk(
      impl_->root,
      [&out](xmlNodePtr n, std::size_t) {
        if (n->type != XML_ELEMENT_NODE) {
          xmltext::append_escaped(out, view(n->content), false);
          return;
        }
        out += '<';
        out += view(n->name);
        for (xmlAttrPtr a = n->properties; a != nullptr; a = a->next) {
          out += ' ';
          out += view(a->name);
          out += "=\"";
          if (a->children != nullptr)
            xmltext::append_escaped(out, view(a->children->content), true);
          out += '"';
        }
        out += n->children == nullptr ? "/>" : ">";
      },
      [&out](xmlNodePtr n, std::size_t) {
        if (n->children == nullptr) return;
        out += "</";
        out += view(n->name);
        out += '>';
      });
  return out;
}

std::string InputTree::describe() const {
  return impl_->root == nullptr ? std::string() : describe_tree(impl_->root);
}

std::string describe_parsed(std::string_view xml) {
  xmlDocPtr doc = xmlReadMemory(xml.data(), static_cast<int>(xml.size()), "input.xml", nullptr,
                                detail::kParseOptions);
  if (doc == nullptr) return {};
  std::string out = describe_tree(xmlDocGetRootElement(doc));
  xmlFreeDoc(doc);
  return out;
}

namespace detail {

xmlDocPtr lend_tree(const InputTree& tree, const std::string& url) {
  return Access::tree(tree).lend(url);
}
void take_back_tree(const InputTree& tree, xmlDocPtr doc) {
  Access::tree(tree).take_back(doc);
}

}  // namespace detail
}  // namespace ncpost::xslt
