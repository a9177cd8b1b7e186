#include "xml_out.hpp"

#include <cstdint>

namespace ncpost::express::detail {
namespace {

constexpr std::string_view kReplacement = "\xEF\xBF\xBD";  // U+FFFD in UTF-8

// Length of the well-formed UTF-8 sequence at the start of `text` that XML 1.0 allows, or 0.
std::size_t valid_utf8_length(std::string_view text) {
  const auto byte = [&](std::size_t i) { return static_cast<std::uint8_t>(text[i]); };
  const std::uint8_t lead = byte(0);
  std::size_t length = 0;
  std::uint32_t code = 0;
  if (lead < 0x80) return 1;
  if (lead >= 0xC2 && lead <= 0xDF) {
    length = 2;
    code = lead & 0x1Fu;
  } else if (lead >= 0xE0 && lead <= 0xEF) {
    length = 3;
    code = lead & 0x0Fu;
  } else if (lead >= 0xF0 && lead <= 0xF4) {
    length = 4;
    code = lead & 0x07u;
  } else {
    return 0;
  }
  if (text.size() < length) return 0;
  for (std::size_t i = 1; i < length; ++i) {
    if ((byte(i) & 0xC0u) != 0x80u) return 0;
    code = (code << 6) | (byte(i) & 0x3Fu);
  }
  const bool overlong = (length == 3 && code < 0x800) || (length == 4 && code < 0x10000);
  const bool surrogate = code >= 0xD800 && code <= 0xDFFF;
  const bool not_xml = code == 0xFFFE || code == 0xFFFF || code > 0x10FFFF;
  return overlong || surrogate || not_xml ? 0 : length;
}

}  // namespace

void append_escaped(std::string& out, std::string_view text, bool quote) {
  for (std::size_t i = 0; i < text.size();) {
    const char c = text[i];
    switch (c) {
      case '&':
        out += "&amp;";
        ++i;
        continue;
      case '<':
        out += "&lt;";
        ++i;
        continue;
      case '>':
        out += "&gt;";
        ++i;
        continue;
      case '"':
        out += quote ? "&quot;" : "\"";
        ++i;
        continue;
      case '\t':
      case '\n':
      case '\r':
        // In attributes these would be normalised to spaces by XML readers; keep them exact.
        if (quote) {
          out += c == '\t' ? "&#9;" : c == '\n' ? "&#10;" : "&#13;";
        } else {
          out += c;
        }
        ++i;
        continue;
      default:
        break;
    }
    if (static_cast<std::uint8_t>(c) < 0x20) {
      out += kReplacement;
      ++i;
      continue;
    }
    const std::size_t length = valid_utf8_length(text.substr(i));
    if (length == 0) {
      out += kReplacement;
      ++i;
    } else {
      out.append(text.substr(i, length));
      i += length;
    }
  }
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
