// P28 XML (either binding) → P21 model, with libxml2's streaming reader: no DOM, and the
// document's nesting becomes an explicit stack of frames. See p28.hpp for the safety rules.

#include <libxml/parser.h>
#include <libxml/xmlreader.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstring>
#include <limits>
#include <optional>
#include <unordered_map>

#include "binding.hpp"
#include "ncpost/express/parse.hpp"
#include "ncpost/p21/strings.hpp"
#include "ncpost/p28/p28.hpp"

namespace ncpost::p28 {
namespace {

using detail::EntityPlan;
using detail::TypePlan;
using diag::Code;
using Kind = TypePlan::Kind;
using p21::Instance;
using p21::Value;
using p21::ValueKind;

constexpr std::string_view kWrapperSuffix = "-wrapper";
constexpr std::string_view kLateNamespace = "urn:ncpost:iso10303-28:late-binding";
constexpr std::string_view kExNamespace =
    "urn:iso.org:standard:10303:part(28):version(2):xmlschema:common";

// What the text of a literal element is read as.
enum class LiteralKind : std::uint8_t {
  Integer,
  Real,
  String,
  Binary,
  Enumeration,
  Logical,
  Resource,
  ByType,  // early binding: the declared type decides
};

// Element names that say how a literal is read, by table.
template <std::size_t N>
using LiteralNames = std::array<std::pair<std::string_view, LiteralKind>, N>;

template <std::size_t N>
std::optional<LiteralKind> literal_named(const LiteralNames<N>& names, std::string_view element) {
  for (const auto& [name, kind] : names)
    if (name == element) return kind;
  return std::nullopt;
}

// The simple types the common namespace wraps (`ex:double-wrapper`, ...), by XML Schema name.
std::optional<LiteralKind> simple_wrapper_kind(std::string_view xsd_type) {
  static constexpr LiteralNames<8> kKinds = {{
      {"double", LiteralKind::Real},
      {"long", LiteralKind::Integer},
      {"integer", LiteralKind::Integer},
      {"hexBinary", LiteralKind::Binary},
      {"boolean", LiteralKind::Logical},
      {"logical", LiteralKind::Logical},
      {"enumeration", LiteralKind::Enumeration},
      {"string", LiteralKind::String},
  }};
  return literal_named(kKinds, xsd_type);
}

// The namespaces of ISO 10303-28's common elements, over the generations of the standard.
bool is_common_namespace(std::string_view ns) {
  return ns == kExNamespace || ns.starts_with("urn:oid:1.0.10303.28") ||
         ns.find("10303:part(28)") != std::string_view::npos;
}

std::string_view view(const xmlChar* s) {
  return s ? std::string_view(reinterpret_cast<const char*>(s)) : std::string_view();
}

bool is_p21_real(std::string_view s) {
  std::size_t i = 0;
  if (i < s.size() && (s[i] == '+' || s[i] == '-')) ++i;
  const std::size_t digits = i;
  while (i < s.size() && std::isdigit(static_cast<unsigned char>(s[i]))) ++i;
  if (i == digits || i >= s.size() || s[i] != '.') return false;
  ++i;
  while (i < s.size() && std::isdigit(static_cast<unsigned char>(s[i]))) ++i;
  if (i < s.size() && (s[i] == 'E' || s[i] == 'e')) {
    ++i;
    if (i < s.size() && (s[i] == '+' || s[i] == '-')) ++i;
    const std::size_t exponent = i;
    while (i < s.size() && std::isdigit(static_cast<unsigned char>(s[i]))) ++i;
    if (i == exponent) return false;
  }
  return i == s.size();
}

bool is_p21_integer(std::string_view s) {
  std::size_t i = (!s.empty() && (s[0] == '+' || s[0] == '-')) ? 1 : 0;
  if (i == s.size()) return false;
  for (; i < s.size(); ++i)
    if (!std::isdigit(static_cast<unsigned char>(s[i]))) return false;
  return true;
}

std::string_view trim(std::string_view s) {
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.remove_prefix(1);
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.remove_suffix(1);
  return s;
}

// An xs:double (or integer) as an ISO 10303-21 real, or nullopt when it is not a finite number.
std::optional<std::string> p21_real(std::string_view text) {
  text = trim(text);
  if (is_p21_real(text)) return std::string(text);
  if (is_p21_integer(text)) return std::string(text) + ".";
  double value = 0;
  const char* begin = text.data() + (!text.empty() && text[0] == '+' ? 1 : 0);
  const auto [end, ec] = std::from_chars(begin, text.data() + text.size(), value);
  if (ec != std::errc() || end != text.data() + text.size() || !std::isfinite(value))
    return std::nullopt;
  std::array<char, 40> buffer{};
  auto [stop, ec2] = std::to_chars(buffer.data(), buffer.data() + buffer.size(), value);
  std::string out(buffer.data(), stop);
  // to_chars writes 1e+20 or 15 or 0.5; P21 wants a digit, a point, then an optional E.
  const std::size_t e = out.find('e');
  std::string mantissa = out.substr(0, e);
  std::string exponent = e == std::string::npos ? "" : out.substr(e + 1);
  if (mantissa.find('.') == std::string::npos) mantissa += '.';
  if (!exponent.empty() && exponent[0] == '+') exponent.erase(0, 1);
  return exponent.empty() ? mantissa : mantissa + "E" + exponent;
}

// True when a <!DOCTYPE appears before the root element. Checked before libxml2 sees the
// document, so an entity bomb in the internal subset is never even parsed.
bool prolog_has_doctype(std::string_view xml) {
  std::size_t i = xml.rfind("\xEF\xBB\xBF", 0) == 0 ? 3 : 0;
  while (i < xml.size()) {
    while (i < xml.size() && std::isspace(static_cast<unsigned char>(xml[i]))) ++i;
    const std::string_view rest = xml.substr(i);
    if (rest.starts_with("<?")) {
      const std::size_t end = rest.find("?>");
      if (end == std::string_view::npos) return false;
      i += end + 2;
    } else if (rest.starts_with("<!--")) {
      const std::size_t end = rest.find("-->");
      if (end == std::string_view::npos) return false;
      i += end + 3;
    } else {
      return rest.starts_with("<!DOCTYPE") || rest.starts_with("<!doctype");
    }
  }
  return false;
}

class Reader {
 public:
  Reader(std::string_view xml, const express::SchemaSet* schemas, const ReadOptions& options)
      : xml_(xml),
        options_(options),
        binding_(schemas),
        diagnostics_(options.max_errors),
        builder_(std::string(), xml.size() / 8 + 16, xml.size() / 64 + 16) {}

  p21::ReadResult run();

 private:
  enum class FrameKind : std::uint8_t {
    Root,
    Skip,         // an element whose content is not model data
    Header,       // late: <header>
    Section,      // late <data_section>, early <uos>
    Instance,     // an entity instance (also header entities)
    Partial,      // a partial record of a complex instance
    Attribute,    // late attribute_instance, early attribute element
    Aggregate,    // list/set/bag/array literal or ex:cType element
    TypeLiteral,  // late type_literal, early typed item
    Literal,      // collects text
    Values,       // section parameters, anchors: a bare list of values
  };
  struct Frame {
    FrameKind kind = FrameKind::Root;
    const TypePlan* type = nullptr;  // expected type of the value(s) inside
    std::uint32_t stack_base = 0;    // scratch values of aggregates and instances start here
    std::uint32_t depth = 0;
    std::uint32_t slot = 0;      // Attribute: the position in the instance
    std::optional<Value> value;  // Attribute, TypeLiteral: the value once read
    LiteralKind literal = LiteralKind::String;
    std::string name;  // Instance/Partial: entity; TypeLiteral: type; Values: anchor
    const EntityPlan* plan = nullptr;  // Instance
    std::uint64_t id = 0;              // Instance
    bool header = false;               // Instance: a header entity
    bool positional = false;           // Instance: attributes are taken in document order
    bool early = false;                // Attribute: early binding element
    bool implicit = false;             // TypeLiteral: wraps the declared type (no typed param)
    std::uint32_t next_position = 0;   // positional attributes
    std::string text;                  // Literal, early Attribute: collected text
    std::vector<Value> slots;          // Instance: one per attribute
    std::vector<Value> records;        // complex Instance: Typed values
    bool items_by_position = false;    // early Attribute holding pos="n" items without ex:cType
    std::vector<Value> items;          // ... and those items
  };

  // ---- diagnostics ----
  void error(Code code, std::string message) {
    const int line = reader_ ? xmlTextReaderGetParserLineNumber(reader_) : 0;
    const int column = reader_ ? xmlTextReaderGetParserColumnNumber(reader_) : 0;
    diagnostics_.add(code, static_cast<std::uint32_t>(std::max(line, 0)),
                     static_cast<std::uint32_t>(std::max(column, 0)), std::move(message));
  }
  static void on_xml_error(void* self, const char* message, xmlParserSeverities severity,
                           xmlTextReaderLocatorPtr locator) {
    auto* reader = static_cast<Reader*>(self);
    std::string text = message ? message : "XML error";
    while (!text.empty() && (text.back() == '\n' || text.back() == ' ')) text.pop_back();
    int line = xmlTextReaderLocatorLineNumber(locator);
    if (line <= 0 && reader->reader_) line = xmlTextReaderGetParserLineNumber(reader->reader_);
    const bool fatal = severity == XML_PARSER_SEVERITY_ERROR;
    if (!fatal) return;                           // warnings from libxml2 are not about the model
    if (text == reader->last_xml_error_) return;  // libxml2 repeats itself while unwinding
    reader->last_xml_error_ = text;
    reader->diagnostics_.add(Code::P28XmlError, static_cast<std::uint32_t>(std::max(line, 0)), 0,
                             text);
  }

  // ---- element helpers ----
  std::string attribute(const char* name) {
    xmlChar* v = xmlTextReaderGetAttribute(reader_, reinterpret_cast<const xmlChar*>(name));
    std::string out = v ? reinterpret_cast<const char*>(v) : "";
    xmlFree(v);
    return out;
  }
  // An attribute by local name in whatever namespace (ex:cType, exp:cType, pos, exp:pos).
  std::string attribute_local(std::string_view name) {
    std::string out;
    if (xmlTextReaderMoveToFirstAttribute(reader_) == 1) {
      do {
        if (view(xmlTextReaderConstLocalName(reader_)) == name) {
          out = view(xmlTextReaderConstValue(reader_));
          break;
        }
      } while (xmlTextReaderMoveToNextAttribute(reader_) == 1);
      xmlTextReaderMoveToElement(reader_);
    }
    return out;
  }
  bool has_attribute(const char* name) {
    xmlChar* v = xmlTextReaderGetAttribute(reader_, reinterpret_cast<const xmlChar*>(name));
    const bool has = v != nullptr;
    xmlFree(v);
    return has;
  }

  std::uint64_t instance_number(std::string_view id) {
    // "Id66" (late) and "i66" (early) keep their number; other ids get one of their own.
    std::size_t digits = id.size();
    while (digits > 0 && std::isdigit(static_cast<unsigned char>(id[digits - 1]))) --digits;
    const std::string_view prefix = id.substr(0, digits);
    if (digits < id.size() && (prefix == "i" || prefix == "Id") && id.size() - digits < 18) {
      std::uint64_t n = 0;
      std::from_chars(id.data() + digits, id.data() + id.size(), n);
      return n;
    }
    auto [it, inserted] = named_ids_.emplace(std::string(id), next_named_id_);
    if (inserted) ++next_named_id_;
    return it->second;
  }

  Value text_value(ValueKind kind, std::string_view p21_text, bool needs_decoding = false) {
    if (p21_text.size() > Value::kMaxSliceLength) {
      error(Code::P28BadValue, "literal is too long");
      return Value::omitted();
    }
    const std::uint32_t offset = builder_.append_text(p21_text);
    return Value::slice(kind, offset, static_cast<std::uint32_t>(p21_text.size()), needs_decoding);
  }

  // A literal's text as a P21 value of the given kind; errors give `$` and a diagnostic.
  Value literal_value(LiteralKind kind, const TypePlan* type, std::string_view raw);
  Value string_value(std::string_view utf8) {
    scratch_text_.clear();
    p21::encode_string(utf8, scratch_text_);
    const bool needs = scratch_text_.find_first_of("'\\") != std::string::npos;
    return text_value(ValueKind::String, scratch_text_, needs);
  }

  void start_element();
  void end_element();
  void close_frame();
  void deliver(Value v);  // a finished value goes to the frame on top of the stack
  void start_value_element(std::string_view local, std::string_view ns, bool empty);
  void start_early_item(std::string_view local, std::string_view ns, bool empty);
  void start_instance(Frame& f, std::string_view local);
  std::string entity_name(std::string name);
  Frame typed_value_frame(std::string_view element, std::string_view type_name,
                          std::uint32_t depth);
  void finish_instance(Frame& f);
  void build_header_from_ed2();
  const TypePlan* expected_type() const { return frames_.back().type; }
  void push(Frame f) { frames_.push_back(std::move(f)); }

  std::string_view xml_;
  const ReadOptions& options_;
  detail::Binding binding_;
  diag::DiagnosticList diagnostics_;
  p21::ModelBuilder builder_;
  xmlTextReaderPtr reader_ = nullptr;

  std::vector<Frame> frames_;
  std::vector<Value> stack_;  // scratch: values of open aggregates
  bool early_ = false;
  bool stopped_ = false;
  bool said_foreign_wrapper_ = false;
  std::optional<p21::DataSection> section_;
  std::unordered_map<std::string, std::uint64_t> named_ids_;
  std::uint64_t next_named_id_ = std::uint64_t{1} << 40;
  std::string scratch_text_;
  // ed.2 header fields of foreign documents (no ex:header_entity): name → values.
  std::vector<std::pair<std::string, std::string>> ed2_header_;
  bool saw_header_entities_ = false;
  bool schema_chosen_ = false;
  std::string last_xml_error_;
};

Value Reader::literal_value(LiteralKind kind, const TypePlan* type, std::string_view raw) {
  while (type && type->kind == Kind::Defined) type = type->underlying;
  if (kind == LiteralKind::ByType) {
    switch (type ? type->kind : Kind::Unknown) {
      case Kind::Integer:
        kind = LiteralKind::Integer;
        break;
      case Kind::Real:
        kind = LiteralKind::Real;
        break;
      case Kind::Binary:
        kind = LiteralKind::Binary;
        break;
      case Kind::Boolean:
      case Kind::Logical:
        kind = LiteralKind::Logical;
        break;
      case Kind::Enumeration:
        kind = LiteralKind::Enumeration;
        break;
      case Kind::String:
        kind = LiteralKind::String;
        break;
      default: {
        // No schema information: a number stays a number, a spelling of NaN or infinity is a
        // (bad) number, everything else is a string.
        const std::string_view t = trim(raw);
        const std::string u = detail::upper(t);
        const bool not_finite = u.find("NAN") != std::string::npos || u == "INF" || u == "-INF" ||
                                u == "INFINITY" || u == "-INFINITY";
        kind = is_p21_integer(t)           ? LiteralKind::Integer
               : p21_real(t) || not_finite ? LiteralKind::Real
                                           : LiteralKind::String;
        break;
      }
    }
  }
  const std::string_view t = trim(raw);
  switch (kind) {
    case LiteralKind::Integer:
      if (type && type->kind == Kind::Real) return literal_value(LiteralKind::Real, type, raw);
      if (!is_p21_integer(t)) {
        error(Code::P28BadValue, "'" + std::string(t.substr(0, 40)) + "' is not an integer");
        return Value::omitted();
      }
      {
        std::int64_t check = 0;
        const char* begin = t.data() + (t[0] == '+' ? 1 : 0);
        if (std::from_chars(begin, t.data() + t.size(), check).ec != std::errc()) {
          error(Code::P28BadValue, "integer '" + std::string(t) + "' does not fit in 64 bits");
          return Value::omitted();
        }
      }
      return text_value(ValueKind::Integer, t);
    case LiteralKind::Real: {
      auto real = p21_real(t);
      if (!real) {
        error(Code::P28BadValue, "'" + std::string(t.substr(0, 40)) +
                                     "' is not a finite number (NaN and infinities have no "
                                     "ISO 10303-21 form)");
        return Value::omitted();
      }
      return text_value(ValueKind::Real, *real);
    }
    case LiteralKind::String:
      return string_value(raw);
    case LiteralKind::Binary:
      if (t.empty() || t[0] < '0' || t[0] > '3' || !std::all_of(t.begin() + 1, t.end(), [](char c) {
            return std::isxdigit(static_cast<unsigned char>(c));
          })) {
        error(Code::P28BadValue, "'" + std::string(t.substr(0, 40)) + "' is not a binary");
        return Value::omitted();
      }
      return text_value(ValueKind::Binary, detail::upper(t));
    case LiteralKind::Logical: {
      const std::string u = detail::upper(t);
      if (u == "TRUE" || u == "T") return text_value(ValueKind::Enumeration, "T");
      if (u == "FALSE" || u == "F") return text_value(ValueKind::Enumeration, "F");
      if (u == "UNKNOWN" || u == "U") return text_value(ValueKind::Enumeration, "U");
      error(Code::P28BadValue, "'" + std::string(t.substr(0, 40)) + "' is not a logical value");
      return Value::omitted();
    }
    case LiteralKind::Enumeration: {
      const std::string u = detail::upper(t);
      const bool ok = !u.empty() && std::all_of(u.begin(), u.end(), [](char c) {
        return std::isalnum(static_cast<unsigned char>(c)) || c == '_';
      });
      if (!ok) {
        error(Code::P28BadValue,
              "'" + std::string(t.substr(0, 40)) + "' is not an enumeration value");
        return Value::omitted();
      }
      return text_value(ValueKind::Enumeration, u);
    }
    case LiteralKind::Resource:
      return text_value(ValueKind::Resource, t);
    case LiteralKind::ByType:
      break;
  }
  return Value::omitted();
}

p21::ReadResult Reader::run() {
  if (xml_.size() > options_.max_bytes ||
      xml_.size() > static_cast<std::size_t>(std::numeric_limits<int>::max())) {
    diagnostics_.add(Code::P28TooLarge, 0, 0,
                     "document of " + std::to_string(xml_.size()) + " bytes exceeds the limit of " +
                         std::to_string(options_.max_bytes));
    return {std::move(builder_).finish(), std::move(diagnostics_).take()};
  }
  if (prolog_has_doctype(xml_)) {
    diagnostics_.add(Code::P28DtdRejected, 1, 1,
                     "documents with a DTD (<!DOCTYPE>) are not accepted: P28 needs none, and "
                     "DTDs are where entity bombs and external entities live");
    return {std::move(builder_).finish(), std::move(diagnostics_).take()};
  }
  // No NOENT (entities stay unexpanded), no DTDLOAD, no HUGE; NONET for good measure.
  const int parse_options = XML_PARSE_NONET | XML_PARSE_NOCDATA | XML_PARSE_COMPACT;
  reader_ = xmlReaderForMemory(xml_.data(), static_cast<int>(xml_.size()), nullptr, nullptr,
                               parse_options);
  if (reader_ == nullptr) {
    diagnostics_.add(Code::P28XmlError, 0, 0, "the XML reader could not be created");
    return {std::move(builder_).finish(), std::move(diagnostics_).take()};
  }
  xmlTextReaderSetErrorHandler(reader_, &Reader::on_xml_error, this);
  push(Frame{});
  int status = 0;
  std::uint32_t nodes = 0;
  bool cancelled = false;
  while (!stopped_ && !diagnostics_.full() && (status = xmlTextReaderRead(reader_)) == 1) {
    if (options_.cancel != nullptr && (++nodes & 4095u) == 0 &&
        options_.cancel->load(std::memory_order_relaxed)) {
      cancelled = true;
      break;
    }
    const int depth = xmlTextReaderDepth(reader_);
    if (depth > static_cast<int>(options_.max_depth)) {
      error(Code::P28TooDeep, "elements nested deeper than " + std::to_string(options_.max_depth));
      break;
    }
    switch (xmlTextReaderNodeType(reader_)) {
      case XML_READER_TYPE_DOCUMENT_TYPE:
        // A DTD is where entity bombs and external entities live; P28 needs none.
        error(Code::P28DtdRejected, "documents with a DTD (<!DOCTYPE>) are not accepted");
        stopped_ = true;
        break;
      case XML_READER_TYPE_ENTITY_REFERENCE:
        error(Code::P28DtdRejected, "entity references are not accepted");
        stopped_ = true;
        break;
      case XML_READER_TYPE_ELEMENT: {
        const bool empty = xmlTextReaderIsEmptyElement(reader_) == 1;
        start_element();
        if (empty && !stopped_) end_element();
        break;
      }
      case XML_READER_TYPE_END_ELEMENT:
        end_element();
        break;
      case XML_READER_TYPE_TEXT:
      case XML_READER_TYPE_CDATA:
      case XML_READER_TYPE_SIGNIFICANT_WHITESPACE: {
        Frame& f = frames_.back();
        if (f.kind == FrameKind::Literal || (f.kind == FrameKind::Attribute && f.early))
          f.text += view(xmlTextReaderConstValue(reader_));
        break;
      }
      default:
        break;
    }
  }
  if (status < 0 && !diagnostics_.has_errors())
    error(Code::P28XmlError, "the document is not well-formed XML");
  xmlFreeTextReader(reader_);
  reader_ = nullptr;
  if (cancelled) {
    p21::ReadResult stopped;
    stopped.cancelled = true;
    return stopped;
  }
  if (section_) {
    section_->end_instance = builder_.instance_count();
    builder_.add_section(*section_);
    section_.reset();
  }
  if (!saw_header_entities_) build_header_from_ed2();
  const auto duplicates = builder_.build_indexes();
  for (const auto& d : duplicates)
    diagnostics_.add(Code::P21DuplicateId, 0, 0,
                     "#" + std::to_string(builder_.model().instances()[d.duplicate_index].id) +
                         " is defined twice; the first is kept");
  // References to ids the document does not define.
  const p21::Model& model = builder_.model();
  for (Value v : model.all_values()) {
    if (diagnostics_.full()) break;
    if (v.is_reference() && model.find(v.id()) == nullptr)
      diagnostics_.add(Code::P21DanglingReference, 0, 0,
                       "#" + std::to_string(v.id()) + " is referenced but not defined");
  }
  if (model.sections().empty() && !diagnostics_.has_errors())
    diagnostics_.add(Code::P28NotP28, 1, 1,
                     "no ISO 10303-28 data: expected a late-bound <iso_10303_28> or an ed.2 <uos>");
  return {std::move(builder_).finish(), std::move(diagnostics_).take()};
}

void Reader::start_element() {
  const std::string_view local = view(xmlTextReaderConstLocalName(reader_));
  const std::string_view ns = view(xmlTextReaderConstNamespaceUri(reader_));
  const bool empty = xmlTextReaderIsEmptyElement(reader_) == 1;
  Frame& top = frames_.back();
  Frame f;
  f.depth = static_cast<std::uint32_t>(xmlTextReaderDepth(reader_));
  switch (top.kind) {
    case FrameKind::Root:
      if (local == "iso_10303_28" && frames_.size() == 1 && f.depth == 0) {
        early_ = ns != kLateNamespace;
        f.kind = FrameKind::Root;  // stay at document level
        push(std::move(f));
        return;
      }
      if (local == "ifcXML" && frames_.size() == 1 && f.depth == 0) {
        // ifcXML 4 puts attributes into XML attributes and types into xsi:type: reading it
        // needs the IFC4 schema's attribute order, which ncpost does not ship.
        error(Code::P28NotSupported,
              "ifcXML 4 (the ISO 10303-28 ed.3 IFC configuration) is not supported; edition 2 "
              "(<iso_10303_28>/<uos>) and the late-bound form are");
        stopped_ = true;
        return;
      } else if (local == "header" && !early_) {
        f.kind = FrameKind::Header;
      } else if (local == "data_section" || local == "uos") {
        if (!schema_chosen_ && options_.schema_for_header && !binding_.has_schema())
          binding_.set_schemas(options_.schema_for_header(builder_.model()));
        schema_chosen_ = true;
        if (section_) {
          section_->end_instance = builder_.instance_count();
          builder_.add_section(*section_);
        }
        section_ = p21::DataSection{};
        section_->first_instance = builder_.instance_count();
        f.kind = FrameKind::Section;
      } else if (local == "header_entity" && early_) {
        f.kind = FrameKind::Instance;
        f.header = true;
        f.positional = true;
        f.name = entity_name(attribute("express_entity_name"));
        f.stack_base = static_cast<std::uint32_t>(stack_.size());
        saw_header_entities_ = true;
      } else if (local == "iso_10303_28_header") {
        f.kind = FrameKind::Skip;
        f.name = "ed2_header";
      } else if (local == "anchor") {
        f.kind = FrameKind::Values;
        f.name = attribute("name");
        f.type = binding_.unknown();
        f.stack_base = static_cast<std::uint32_t>(stack_.size());
      } else if (frames_.size() == 1 && f.depth == 0) {
        error(Code::P28NotP28,
              "root element <" + std::string(local) + "> is not an ISO 10303-28 document");
        stopped_ = true;
        return;
      } else {
        f.kind = FrameKind::Skip;  // doc:express, schema_population and the like
      }
      push(std::move(f));
      return;
    case FrameKind::Skip:
      if (top.name == "ed2_header") {
        f.kind = FrameKind::Literal;
        f.name = std::string(local);
        f.literal = LiteralKind::String;
        push(std::move(f));
        return;
      }
      f.kind = FrameKind::Skip;
      push(std::move(f));
      return;
    case FrameKind::Header:
      if (local != "entity_instance") break;
      f.kind = FrameKind::Instance;
      f.header = true;
      f.positional = true;
      f.name = entity_name(attribute("express_entity_name"));
      f.stack_base = static_cast<std::uint32_t>(stack_.size());
      saw_header_entities_ = true;
      push(std::move(f));
      return;
    case FrameKind::Section: {
      if (local == "section_parameters") {
        f.kind = FrameKind::Values;
        f.type = binding_.unknown();
        f.stack_base = static_cast<std::uint32_t>(stack_.size());
        push(std::move(f));
        return;
      }
      if (local == "reference") {
        Instance external;
        external.id = instance_number(attribute("id"));
        external.keyword = p21::Model::kExternalKeyword;
        const Value uri = text_value(ValueKind::Resource, attribute("uri"));
        external.first = builder_.push_values(std::span<const Value>(&uri, 1));
        external.count = 1;
        builder_.add_instance(external);
        f.kind = FrameKind::Skip;
        push(std::move(f));
        return;
      }
      start_instance(f, local);
      return;
    }
    case FrameKind::Instance:
    case FrameKind::Partial: {
      if (local == "partial_entity_instance" || local == "partial_entity") {
        f.kind = FrameKind::Partial;
        f.name = entity_name(attribute("express_entity_name"));
        f.positional = true;
        push(std::move(f));
        return;
      }
      f.kind = FrameKind::Attribute;
      f.early = early_;
      const std::string name = early_ ? std::string(local) : attribute("express_attribute_name");
      // Attribute position: by name from the schema plan, or attr_N, or document order.
      std::optional<std::size_t> index;
      if (name.rfind("attr_", 0) == 0) {
        std::size_t n = 0;
        std::from_chars(name.data() + 5, name.data() + name.size(), n);
        if (n > 0) index = n - 1;
      } else if (top.plan != nullptr) {
        if (auto it = top.plan->index_of.find(name); it != top.plan->index_of.end())
          index = it->second;
      } else if (top.header) {
        static const std::array<std::pair<std::string_view, std::vector<std::string_view>>, 3>
            kHeader = {{{"file_description", {"description", "implementation_level"}},
                        {"file_name",
                         {"name", "time_stamp", "author", "organization", "preprocessor_version",
                          "originating_system", "authorization"}},
                        {"file_schema", {"schema_identifiers"}}}};
        for (const auto& [entity, names] : kHeader)
          if (entity == top.name)
            for (std::size_t i = 0; i < names.size(); ++i)
              if (names[i] == name) index = i;
      }
      if (!index) {
        if (top.plan != nullptr && top.plan->known) {
          error(Code::P28UnknownAttribute,
                "entity " + top.name + " has no attribute '" + name + "'");
          f.kind = FrameKind::Skip;
          push(std::move(f));
          return;
        }
        index = top.next_position;  // schema-less: document order
      }
      top.next_position = static_cast<std::uint32_t>(*index + 1);
      f.slot = static_cast<std::uint32_t>(*index);
      f.type = (top.plan != nullptr && *index < top.plan->attributes.size())
                   ? top.plan->attributes[*index].type
                   : binding_.unknown();
      if (early_) {
        const std::string ctype = attribute_local("cType");
        if (!ctype.empty()) {
          // The attribute element is the aggregate itself.
          f.kind = FrameKind::Aggregate;
          f.stack_base = static_cast<std::uint32_t>(stack_.size());
          const TypePlan* t = f.type;
          while (t->kind == Kind::Defined) t = t->underlying;
          f.type = t->kind == Kind::Aggregate ? t->element : binding_.unknown();
          Frame attribute_frame;
          attribute_frame.kind = FrameKind::Attribute;
          attribute_frame.slot = f.slot;
          attribute_frame.depth = f.depth;
          attribute_frame.early = true;
          attribute_frame.name = "(aggregate)";
          push(std::move(attribute_frame));
          f.depth = f.depth;  // same element closes both frames
          push(std::move(f));
          return;
        }
      }
      push(std::move(f));
      return;
    }
    case FrameKind::Attribute:
    case FrameKind::Aggregate:
    case FrameKind::TypeLiteral:
    case FrameKind::Values:
      if (early_) {
        start_early_item(local, ns, empty);
      } else {
        start_value_element(local, ns, empty);
      }
      return;
    case FrameKind::Literal:
      error(Code::P28UnexpectedElement, "<" + std::string(local) + "> inside a literal");
      f.kind = FrameKind::Skip;
      push(std::move(f));
      return;
  }
  error(Code::P28UnexpectedElement, "unexpected element <" + std::string(local) + ">");
  f.kind = FrameKind::Skip;
  push(std::move(f));
}

void Reader::start_value_element(std::string_view local, std::string_view, bool) {
  Frame f;
  f.depth = static_cast<std::uint32_t>(xmlTextReaderDepth(reader_));
  const TypePlan* expected = expected_type();
  static constexpr LiteralNames<8> kLiterals = {{
      {"integer_literal", LiteralKind::Integer},
      {"real_literal", LiteralKind::Real},
      {"string_literal", LiteralKind::String},
      {"binary_literal", LiteralKind::Binary},
      {"enumeration_literal", LiteralKind::Enumeration},
      {"logical_literal", LiteralKind::Logical},
      {"boolean_literal", LiteralKind::Logical},
      {"resource_literal", LiteralKind::Resource},
  }};
  if (const auto kind = literal_named(kLiterals, local)) {
    f.kind = FrameKind::Literal;
    f.literal = *kind;
    f.type = expected;
    push(std::move(f));
    return;
  }
  f.kind = FrameKind::Skip;  // the value is delivered now; the element only needs closing
  if (local == "unset_literal") {
    deliver(Value::omitted());
  } else if (local == "derived_literal") {
    deliver(Value::derived());
  } else if (local == "entity_instance_ref") {
    deliver(Value::reference(instance_number(attribute("refid"))));
  } else if (local == "constant_ref") {
    deliver(text_value(ValueKind::ConstantName, attribute("name")));
  } else if (local == "value_instance_ref") {
    deliver(text_value(ValueKind::ValueName, attribute("name")));
  } else if (local == "list_literal" || local == "set_literal" || local == "bag_literal" ||
             local == "array_literal") {
    f.kind = FrameKind::Aggregate;
    const TypePlan* t = expected;
    while (t && t->kind == Kind::Defined) t = t->underlying;
    f.type = t && t->kind == Kind::Aggregate ? t->element : binding_.unknown();
    f.stack_base = static_cast<std::uint32_t>(stack_.size());
  } else if (local == "type_literal") {
    f.kind = FrameKind::TypeLiteral;
    f.name = attribute("express_type_name");
    // The name becomes a P21 keyword: without a valid one the value would be written as a bare
    // list and read back as something else.
    if (!express::can_name_a_declaration(f.name))
      error(Code::P28BadValue, "type_literal without a valid express_type_name ('" + f.name + "')");
    const TypePlan* named = binding_.named_type(f.name);
    // The paper's form wraps a literal in the attribute's own defined type: that is not a
    // typed parameter. Any other type name is a SELECT member, i.e. a P21 typed parameter.
    f.implicit =
        expected && expected->kind == Kind::Defined && expected->name == detail::lower(f.name);
    f.type = named->kind == Kind::Defined ? named->underlying : named;
  } else {
    error(Code::P28UnexpectedElement, "<" + std::string(local) + "> is not a value");
  }
  push(std::move(f));
}

void Reader::start_early_item(std::string_view local, std::string_view ns, bool) {
  Frame f;
  f.depth = static_cast<std::uint32_t>(xmlTextReaderDepth(reader_));
  const TypePlan* expected = expected_type();
  const Frame& top = frames_.back();
  f.kind = FrameKind::Skip;
  if (top.kind == FrameKind::Attribute && !attribute_local("pos").empty())
    frames_.back().items_by_position = true;  // ifcXML lists without ex:cType
  const std::string ref = attribute("ref");
  if (!ref.empty()) {
    deliver(Value::reference(instance_number(ref)));
    push(std::move(f));
    return;
  }
  if (const std::string id = attribute("id"); !id.empty()) {
    // An instance written inline, inside the attribute that refers to it (ed.2 allows it).
    deliver(Value::reference(instance_number(id)));
    start_instance(f, local);
    return;
  }
  const bool ex = is_common_namespace(ns);
  if (ex && local == "unset") {
    deliver(Value::omitted());
    push(std::move(f));
    return;
  }
  if (ex && local == "derived") {
    deliver(Value::derived());
    push(std::move(f));
    return;
  }
  const std::string ctype = attribute_local("cType");
  // Ed.2 names a wrapped simple value `<type>-wrapper`: the common namespace's own types
  // (`ex:double-wrapper`), or a schema's defined type (ifcXML's `IfcLabel-wrapper`).
  const bool wrapper = local.ends_with(kWrapperSuffix);
  const std::string_view type_name =
      wrapper ? local.substr(0, local.size() - kWrapperSuffix.size()) : local;
  const std::optional<LiteralKind> common_wrapper =
      wrapper ? simple_wrapper_kind(type_name) : std::nullopt;
  if (!ex && common_wrapper && !said_foreign_wrapper_) {
    // The common namespace's own wrapper in another: the writer's namespace URI is wrong. Said
    // once per document, and each such value read as its wrapper says, so that no other error
    // follows from it.
    said_foreign_wrapper_ = true;
    error(Code::P28BadValue, "<" + std::string(local) +
                                 "> is a wrapper of the ISO 10303-28 common namespace, but is "
                                 "in namespace '" +
                                 std::string(ns.substr(0, 100)) + "'");
  }
  if ((ex || common_wrapper) && wrapper && ctype.empty()) {
    f.kind = FrameKind::Literal;
    f.type = expected;
    f.literal = common_wrapper.value_or(LiteralKind::String);
    push(std::move(f));
    return;
  }
  if (ex && (local == "constant" || local == "value-instance" || local == "resource")) {
    f.kind = FrameKind::Literal;
    f.literal = LiteralKind::Resource;
    f.name = std::string(local);
    push(std::move(f));
    return;
  }
  // An element named after a type: the declared type itself (implicit), or a SELECT member.
  const std::string name = detail::lower(type_name);
  const TypePlan* named = binding_.named_type(name);
  const TypePlan* declared = expected;
  bool implicit = false;
  if (declared && declared->kind == Kind::Defined && declared->name == name) {
    implicit = true;
  } else if (declared && (declared->kind == Kind::Select)) {
    implicit = false;
  } else if (!declared || declared->kind == Kind::Unknown) {
    // No schema: inside an aggregate the wrapper names the element type; directly under an
    // attribute it is a SELECT member (the ed.2 convention).
    implicit = top.kind == FrameKind::Aggregate;
  } else {
    implicit = true;  // the schema declares a plain type here; the element only wraps it
  }
  if (!ctype.empty()) {
    f.kind = FrameKind::Aggregate;
    const TypePlan* t =
        implicit ? declared : (named->kind == Kind::Defined ? named->underlying : named);
    while (t && t->kind == Kind::Defined) t = t->underlying;
    f.type = t && t->kind == Kind::Aggregate ? t->element : binding_.unknown();
    f.stack_base = static_cast<std::uint32_t>(stack_.size());
    if (!implicit) push(typed_value_frame(local, type_name, f.depth));
    push(std::move(f));
    return;
  }
  f.kind = FrameKind::Literal;
  f.literal = LiteralKind::ByType;
  if (implicit) {
    f.type = declared && declared->kind != Kind::Unknown ? declared : named;
  } else {
    push(typed_value_frame(local, type_name, f.depth));
    f.type = named->kind == Kind::Defined ? named->underlying : named;
  }
  push(std::move(f));
}

// In the early binding an element's name types the value inside it (a SELECT member). The name
// becomes a P21 keyword, so one that cannot name a type (`string` from a `string-wrapper` whose
// common namespace is misspelt, `a-b`) would be written as something P21 reads otherwise.
Reader::Frame Reader::typed_value_frame(std::string_view element, std::string_view type_name,
                                        std::uint32_t depth) {
  if (!express::can_name_a_declaration(type_name))
    error(Code::P28BadValue, "<" + std::string(element.substr(0, 60)) +
                                 "> names no EXPRESS type, so it cannot type a value");
  Frame typed;
  typed.kind = FrameKind::TypeLiteral;
  typed.name = std::string(type_name);
  typed.depth = depth;
  return typed;
}

// An entity's name becomes a P21 keyword: one that is no EXPRESS name would be written as
// something P21 reads otherwise (or not at all).
std::string Reader::entity_name(std::string name) {
  if (!express::can_name_a_declaration(name))
    error(Code::P28UnexpectedElement, "'" + name + "' is not an EXPRESS entity name");
  return name;
}

void Reader::start_instance(Frame& f, std::string_view local) {
  f.kind = FrameKind::Instance;
  f.id = instance_number(attribute("id"));
  f.stack_base = static_cast<std::uint32_t>(stack_.size());
  if (local == "complex_entity_instance" || (!early_ && !has_attribute("express_entity_name"))) {
    f.name.clear();  // complex: partial records follow
  } else {
    f.name = entity_name(early_ ? std::string(local) : attribute("express_entity_name"));
    f.plan = &binding_.entity(f.name);
    f.positional = !f.plan->known;
    f.slots.assign(f.plan->attributes.size(), Value::omitted());
    for (std::size_t i = 0; i < f.plan->attributes.size(); ++i)
      if (f.plan->attributes[i].derived) f.slots[i] = Value::derived();
  }
  push(std::move(f));
}

void Reader::deliver(Value v) {
  Frame& top = frames_.back();
  switch (top.kind) {
    case FrameKind::Attribute:
      if (top.items_by_position) {
        top.items.push_back(v);
        return;
      }
      [[fallthrough]];
    case FrameKind::TypeLiteral:
      if (top.value) {
        error(Code::P28UnexpectedElement, "more than one value where one is expected");
        return;
      }
      top.value = v;
      return;
    case FrameKind::Aggregate:
    case FrameKind::Values:
      stack_.push_back(v);
      return;
    default:
      error(Code::P28UnexpectedElement, "a value outside an attribute");
      return;
  }
}

void Reader::finish_instance(Frame& f) {
  Instance inst;
  inst.id = f.id;
  inst.offset = 0;
  if (f.name.empty()) {
    if (f.records.empty()) {
      error(Code::P21EmptyComplex,
            "complex instance #" + std::to_string(f.id) + " has no partial records");
      return;
    }
    inst.keyword = p21::Model::kComplexKeyword;
    inst.first = builder_.push_values(f.records);
    inst.count = static_cast<std::uint32_t>(f.records.size());
  } else {
    inst.keyword = builder_.intern(detail::upper(f.name));
    inst.first = builder_.push_values(f.slots);
    inst.count = static_cast<std::uint32_t>(f.slots.size());
  }
  if (f.header) {
    builder_.add_header(inst);
  } else {
    builder_.add_instance(inst);
  }
}

void Reader::end_element() {
  // One element may have opened two frames (a typed value's TypeLiteral and its content);
  // closing it closes every frame it opened.
  const std::uint32_t depth = frames_.back().depth;
  do {
    close_frame();
  } while (frames_.size() > 1 && frames_.back().depth == depth &&
           frames_.back().kind != FrameKind::Root);
}

void Reader::close_frame() {
  if (frames_.size() <= 1) return;
  Frame f = std::move(frames_.back());
  frames_.pop_back();
  switch (f.kind) {
    case FrameKind::Literal: {
      if (frames_.back().kind == FrameKind::Skip && frames_.back().name == "ed2_header") {
        ed2_header_.emplace_back(f.name, f.text);
        return;
      }
      Value v = literal_value(f.literal, f.type, f.text);
      if (f.literal == LiteralKind::Resource && !f.name.empty()) {
        v = f.name == "constant"         ? text_value(ValueKind::ConstantName, trim(f.text))
            : f.name == "value-instance" ? text_value(ValueKind::ValueName, trim(f.text))
                                         : v;
      }
      deliver(v);
      break;
    }
    case FrameKind::Aggregate: {
      const auto n = static_cast<std::uint32_t>(stack_.size()) - f.stack_base;
      const std::uint32_t first =
          builder_.push_values(std::span<const Value>(stack_.data() + f.stack_base, n));
      stack_.resize(f.stack_base);
      builder_.note_depth(static_cast<std::uint32_t>(frames_.size()));
      deliver(Value::list(first, n));
      break;
    }
    case FrameKind::TypeLiteral: {
      if (!f.value) {
        error(Code::P28BadValue, "type_literal " + f.name + " holds no value");
        f.value = Value::omitted();
      }
      if (f.implicit) {
        deliver(*f.value);
      } else {
        const std::uint32_t child = builder_.push_values(std::span<const Value>(&*f.value, 1));
        deliver(Value::typed(builder_.intern(detail::upper(f.name)), child));
      }
      break;
    }
    case FrameKind::Attribute: {
      Frame& owner = frames_.back();
      Value v = Value::omitted();
      if (f.items_by_position) {
        const std::uint32_t first = builder_.push_values(f.items);
        v = Value::list(first, static_cast<std::uint32_t>(f.items.size()));
      } else if (f.value) {
        v = *f.value;
      } else if (f.early && f.name != "(aggregate)") {
        v = literal_value(LiteralKind::ByType, f.type, f.text);
      } else if (!f.early) {
        error(Code::P28BadValue, "attribute holds no value");
      }
      std::vector<Value>& slots = owner.slots;
      if (f.slot >= slots.size()) {
        if (f.slot > 100000) {
          error(Code::P28UnknownAttribute, "attribute position beyond any entity");
          break;
        }
        slots.resize(f.slot + 1, Value::omitted());
      }
      slots[f.slot] = v;
      break;
    }
    case FrameKind::Partial: {
      Frame& owner = frames_.back();
      const std::uint32_t first = builder_.push_values(f.slots);
      const Value list = Value::list(first, static_cast<std::uint32_t>(f.slots.size()));
      const std::uint32_t at = builder_.push_values(std::span<const Value>(&list, 1));
      owner.records.push_back(Value::typed(builder_.intern(detail::upper(f.name)), at));
      break;
    }
    case FrameKind::Instance:
      finish_instance(f);
      break;
    case FrameKind::Values: {
      const auto n = static_cast<std::uint32_t>(stack_.size()) - f.stack_base;
      const std::uint32_t first =
          builder_.push_values(std::span<const Value>(stack_.data() + f.stack_base, n));
      stack_.resize(f.stack_base);
      if (!f.name.empty()) {  // an anchor: its one item
        p21::Anchor anchor;
        anchor.name_offset = builder_.append_text(f.name);
        anchor.name_length = static_cast<std::uint32_t>(f.name.size());
        anchor.item = n == 1 ? builder_.model().all_values()[first] : Value::omitted();
        builder_.add_anchor(anchor);
      } else if (section_) {
        section_->first_param = first;
        section_->param_count = n;
      }
      break;
    }
    default:
      break;
  }
}

// Foreign ed.2 documents carry only the ex:iso_10303_28_header fields; FILE_NAME is rebuilt
// from them, and FILE_DESCRIPTION and FILE_SCHEMA from what is known.
void Reader::build_header_from_ed2() {
  const auto strings_of = [&](std::string_view field) {
    std::vector<Value> out;
    for (const auto& [name, text] : ed2_header_)
      if (name == field) out.push_back(string_value(text));
    return out;
  };
  const auto list_of = [&](std::vector<Value> values) {
    const std::uint32_t first = builder_.push_values(values);
    return Value::list(first, static_cast<std::uint32_t>(values.size()));
  };
  const auto one_of = [&](std::string_view field) {
    auto v = strings_of(field);
    return v.empty() ? string_value("") : v.front();
  };
  std::vector<Value> description = {list_of(strings_of("documentation")), string_value("2;1")};
  Instance fd;
  fd.keyword = builder_.intern("FILE_DESCRIPTION");
  fd.first = builder_.push_values(description);
  fd.count = 2;
  builder_.add_header(fd);
  std::vector<Value> name = {one_of("name"),
                             one_of("time_stamp"),
                             list_of(strings_of("author")),
                             list_of(strings_of("organization")),
                             one_of("preprocessor_version"),
                             one_of("originating_system"),
                             one_of("authorization")};
  Instance fn;
  fn.keyword = builder_.intern("FILE_NAME");
  fn.first = builder_.push_values(name);
  fn.count = 7;
  builder_.add_header(fn);
}

// Every external resource (DTD, entity, XInclude) is refused: inputs are untrusted. Returning
// no input makes libxml2 report the load as failed.
xmlParserInputPtr refuse_entity(const char*, const char*, xmlParserCtxtPtr) {
  return nullptr;
}

}  // namespace

p21::ReadResult read(std::string_view xml, const express::SchemaSet* schemas,
                     const ReadOptions& options) {
  return Reader(xml, schemas, options).run();
}

void initialise_xml() {
  xmlInitParser();
  xmlSetExternalEntityLoader(refuse_entity);
}

}  // namespace ncpost::p28
