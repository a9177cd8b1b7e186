#include "xml_out.hpp"

#include "ncpost/xmltext/escape.hpp"

namespace ncpost::express::detail {

void append_escaped(std::string& out, std::string_view text, bool quote) {
  xmltext::append_escaped(out, text, quote);
}

void XmlOut::declaration() {
  out_ += "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
}

void XmlOut::indent() {
  out_.append(open_.size() * 2, ' ');
}

void XmlOut::start_tag(std::string_view name, std::string_view production,
                       std::initializer_list<XmlAttribute> attributes) {
  indent();
  out_ += '<';
  out_ += name;
  out_ += " express-production=\"";
  out_ += production;
  out_ += '"';
  for (const XmlAttribute& attribute : attributes) {
    out_ += ' ';
    out_ += attribute.name;
    out_ += "=\"";
    append_escaped(out_, attribute.value, true);
    out_ += '"';
  }
}

void XmlOut::open(std::string_view name, std::string_view production,
                  std::initializer_list<XmlAttribute> attributes) {
  start_tag(name, production, attributes);
  out_ += ">\n";
  open_.push_back(name);
}

void XmlOut::close() {
  const std::string_view name = open_.back();
  open_.pop_back();
  indent();
  out_ += "</";
  out_ += name;
  out_ += ">\n";
}

void XmlOut::leaf(std::string_view name, std::string_view production, std::string_view text,
                  std::initializer_list<XmlAttribute> attributes) {
  start_tag(name, production, attributes);
  if (text.empty()) {
    out_ += "/>\n";
    return;
  }
  out_ += '>';
  append_escaped(out_, text, false);
  out_ += "</";
  out_ += name;
  out_ += ">\n";
}

}  // namespace ncpost::express::detail
