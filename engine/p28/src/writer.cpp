// P21 model → P28 XML, streamed. See p28.hpp and docs/p28.md for the two forms.

#include <array>
#include <charconv>
#include <optional>
#include <unordered_set>

#include "binding.hpp"
#include "ncpost/p21/strings.hpp"
#include "ncpost/p28/p28.hpp"
#include "ncpost/xmltext/escape.hpp"

namespace ncpost::p28 {
namespace {

using detail::AttributePlan;
using detail::EntityPlan;
using detail::TypePlan;
using Kind = TypePlan::Kind;
using p21::Instance;
using p21::Value;
using p21::ValueKind;

constexpr std::size_t kFlushAt = 64 * 1024;
constexpr std::string_view kLateNamespace = "urn:ncpost:iso10303-28:late-binding";
constexpr std::string_view kExNamespace =
    "urn:iso.org:standard:10303:part(28):version(2):xmlschema:common";

// The attribute names of the ISO 10303-21 header entities, which no data schema declares.
const std::array<std::pair<std::string_view, std::vector<std::string_view>>, 3> kHeaderAttributes =
    {{
        {"file_description", {"description", "implementation_level"}},
        {"file_name",
         {"name", "time_stamp", "author", "organization", "preprocessor_version",
          "originating_system", "authorization"}},
        {"file_schema", {"schema_identifiers"}},
    }};

std::string_view aggregate_name(express::AggregateKind kind) {
  switch (kind) {
    case express::AggregateKind::Set:
      return "set";
    case express::AggregateKind::Bag:
      return "bag";
    case express::AggregateKind::Array:
      return "array";
    default:
      return "list";
  }
}

class Writer {
 public:
  Writer(const p21::Model& model, const express::SchemaSet* schemas, Binding binding,
         const p21::TextSink& sink)
      : model_(model), binding_(schemas), form_(binding), sink_(sink) {
    out_.reserve(kFlushAt + 4096);
  }

  std::vector<diag::Diagnostic> run() {
    put("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n");
    if (form_ == Binding::Late) {
      late_document();
    } else {
      early_document();
    }
    flush();
    return std::move(notes_);
  }

 private:
  // ---- output ----
  void put(std::string_view s) { out_ += s; }
  void maybe_flush() {
    if (out_.size() >= kFlushAt) flush();
  }
  void flush() {
    if (!out_.empty()) sink_(out_);
    out_.clear();
  }
  void text(std::string_view s) { xmltext::append_escaped(out_, s); }
  void attr(std::string_view s) { xmltext::append_escaped(out_, s, true); }
  void string_content(Value v) {
    decoded_.clear();
    model_.append_string(v, decoded_);
    text(decoded_);
  }
  void id_number(std::uint64_t id) {
    std::array<char, 24> digits{};
    auto [end, ec] = std::to_chars(digits.data(), digits.data() + digits.size(), id);
    out_.append(digits.data(), end);
  }

  // Lower-case entity names and plans, cached per keyword: looked up once per distinct entity,
  // not once per instance or reference.
  const std::string& lower_name(p21::KeywordId keyword) {
    if (keyword >= lower_names_.size()) lower_names_.resize(model_.keyword_count());
    std::string& name = lower_names_[keyword];
    if (name.empty()) name = detail::lower(model_.keyword(keyword));
    return name;
  }

  const EntityPlan& plan_of(const Instance& inst) {
    if (inst.keyword >= plans_.size()) plans_.resize(model_.keyword_count(), nullptr);
    const EntityPlan*& cached = plans_[inst.keyword];
    if (cached != nullptr && cached->attributes.size() >= inst.count) return *cached;
    cached = &binding_.entity(model_.type_name(inst), inst.count);
    const EntityPlan& plan = *cached;
    if (!plan.known && binding_.has_schema() && noted_.insert(plan.name).second)
      notes_.push_back(diag::make(diag::Code::P28NoSchemaEntity, 0, 0,
                                  "entity " + plan.name +
                                      " is not in the schema; its attributes are written by "
                                      "position"));
    if (plan.known && inst.count < plan.attributes.size() && short_.insert(plan.name).second)
      notes_.push_back(diag::make(diag::Code::P28AttributeCount, 0, 0,
                                  "#" + std::to_string(inst.id) + " (" + plan.name + ") has " +
                                      std::to_string(inst.count) + " parameters; the schema says " +
                                      std::to_string(plan.attributes.size())));
    return plan;
  }

  // ================= late binding =================
  void late_document() {
    put("<iso_10303_28 xmlns=\"");
    put(kLateNamespace);
    put("\" representation=\"late_binding\">\n<header>\n");
    for (const Instance& h : model_.header()) late_header_entity(h);
    put("</header>\n");
    for (const p21::Anchor& a : model_.anchors()) {
      put("<anchor name=\"");
      attr(model_.text().substr(a.name_offset, a.name_length));
      put("\">");
      late_value(a.item, binding_.unknown());
      put("</anchor>\n");
    }
    for (const p21::DataSection& section : model_.sections()) {
      put("<data_section>\n");
      if (section.param_count > 0) {
        put("<section_parameters>");
        for (Value v : model_.all_values().subspan(section.first_param, section.param_count))
          late_value(v, binding_.unknown());
        put("</section_parameters>\n");
      }
      for (std::uint32_t i = section.first_instance; i < section.end_instance; ++i) {
        late_instance(model_.instances()[i]);
        maybe_flush();
      }
      put("</data_section>\n");
    }
    put("</iso_10303_28>\n");
  }

  void late_header_entity(const Instance& h) {
    const std::string name = detail::lower(model_.type_name(h));
    put("<entity_instance express_entity_name=\"");
    attr(name);
    put("\">");
    const std::vector<std::string_view>* names = nullptr;
    for (const auto& [entity, attributes] : kHeaderAttributes)
      if (entity == name) names = &attributes;
    const auto params = model_.params(h);
    for (std::size_t i = 0; i < params.size(); ++i) {
      put("<attribute_instance express_attribute_name=\"");
      if (names && i < names->size())
        put((*names)[i]);
      else
        put(detail::positional_name(i));
      put("\">");
      late_value(params[i], binding_.unknown());
      put("</attribute_instance>");
    }
    put("</entity_instance>\n");
  }

  void late_instance(const Instance& inst) {
    if (inst.keyword == p21::Model::kExternalKeyword) {
      put("<reference id=\"Id");
      id_number(inst.id);
      put("\" uri=\"");
      attr(model_.slice(model_.params(inst)[0]));
      put("\"/>\n");
      return;
    }
    if (model_.is_complex(inst)) {
      put("<entity_instance id=\"Id");
      id_number(inst.id);
      put("\">");
      for (Value record : model_.params(inst)) {
        put("<partial_entity_instance express_entity_name=\"");
        attr(detail::lower(model_.keyword(record.keyword_id())));
        put("\">");
        const auto params = model_.items(model_.typed_child(record));
        for (std::size_t i = 0; i < params.size(); ++i) late_positional(params[i], i);
        put("</partial_entity_instance>");
      }
      put("</entity_instance>\n");
      return;
    }
    const EntityPlan& plan = plan_of(inst);
    put("<entity_instance express_entity_name=\"");
    attr(plan.name);
    put("\" id=\"Id");
    id_number(inst.id);
    put("\">");
    const auto params = model_.params(inst);
    for (std::size_t i = 0; i < params.size(); ++i) {
      const AttributePlan& a = plan.attributes[i];
      if (!plan.known) {
        late_positional(params[i], i);
        continue;
      }
      if (params[i].is_omitted()) continue;  // the reader restores $ from the schema
      put(a.inherited ? "<inherited_attribute_instance" : "<attribute_instance");
      put(" express_attribute_name=\"");
      put(a.name);
      put("\">");
      late_value(params[i], a.type);
      put(a.inherited ? "</inherited_attribute_instance>" : "</attribute_instance>");
    }
    put("</entity_instance>\n");
  }

  void late_positional(Value v, std::size_t index) {
    put("<attribute_instance express_attribute_name=\"");
    put(detail::positional_name(index));
    put("\">");
    late_value(v, binding_.unknown());
    put("</attribute_instance>");
  }

  void literal(std::string_view element, std::string_view content) {
    put("<");
    put(element);
    put(">");
    text(content);
    put("</");
    put(element);
    put(">");
  }

  // Recursion follows the value's lists, which the readers cap (Model::max_depth).
  void late_value(Value v, const TypePlan* type) {
    // A declared defined type wraps the literal, as in the paper's example.
    if (type->kind == Kind::Defined && v.kind() != ValueKind::Typed && !v.is_omitted() &&
        v.kind() != ValueKind::Derived) {
      put("<type_literal express_type_name=\"");
      put(type->name);
      put("\">");
      late_value(v, type->underlying);
      put("</type_literal>");
      return;
    }
    switch (v.kind()) {
      case ValueKind::Omitted:
        put("<unset_literal/>");
        return;
      case ValueKind::Derived:
        put("<derived_literal/>");
        return;
      case ValueKind::Integer:
        // An integer written where the schema wants a REAL stays a real on the way back.
        if (type->kind == Kind::Real) {
          put("<real_literal>");
          text(model_.slice(v));
          put(".</real_literal>");
        } else {
          literal("integer_literal", model_.slice(v));
        }
        return;
      case ValueKind::Real:
        literal("real_literal", model_.slice(v));
        return;
      case ValueKind::String:
        put("<string_literal>");
        string_content(v);
        put("</string_literal>");
        return;
      case ValueKind::Binary:
        literal("binary_literal", model_.slice(v));
        return;
      case ValueKind::Enumeration: {
        const std::string_view e = model_.slice(v);
        if (type->kind == Kind::Boolean || type->kind == Kind::Logical) {
          put(type->kind == Kind::Boolean ? "<boolean_literal>" : "<logical_literal>");
          put(e == "T" || e == "t" ? "TRUE" : e == "F" || e == "f" ? "FALSE" : "UNKNOWN");
          put(type->kind == Kind::Boolean ? "</boolean_literal>" : "</logical_literal>");
        } else {
          literal("enumeration_literal", e);
        }
        return;
      }
      case ValueKind::Reference:
        put("<entity_instance_ref refid=\"Id");
        id_number(v.id());
        put("\"/>");
        return;
      case ValueKind::ConstantName:
        put("<constant_ref name=\"");
        attr(model_.slice(v));
        put("\"/>");
        return;
      case ValueKind::ValueName:
        put("<value_instance_ref name=\"");
        attr(model_.slice(v));
        put("\"/>");
        return;
      case ValueKind::Resource:
        put("<resource_literal>");
        text(model_.slice(v));
        put("</resource_literal>");
        return;
      case ValueKind::List: {
        const bool typed = type->kind == Kind::Aggregate;
        const std::string_view name = typed ? aggregate_name(type->aggregate) : "list";
        const TypePlan* element = typed ? type->element : binding_.unknown();
        put("<");
        put(name);
        put("_literal>");
        for (Value item : model_.items(v)) late_value(item, element);
        put("</");
        put(name);
        put("_literal>");
        return;
      }
      case ValueKind::Typed: {
        const std::string_view keyword = model_.keyword(v.keyword_id());
        put("<type_literal express_type_name=\"");
        const std::string name = detail::lower(keyword);
        attr(name);
        put("\">");
        const TypePlan* named = binding_.named_type(name);
        late_value(model_.typed_child(v), named->kind == Kind::Defined ? named->underlying : named);
        put("</type_literal>");
        return;
      }
    }
  }

  // ================= early binding =================
  void early_document() {
    put("<ex:iso_10303_28 version=\"2.0\" xmlns:ex=\"");
    put(kExNamespace);
    put("\" xmlns:xsi=\"http://www.w3.org/2001/XMLSchema-instance\">\n");
    early_header();
    std::string schema_name = "unknown";
    if (const Instance* fs = model_.header_entity("FILE_SCHEMA"); fs && fs->count > 0) {
      const Value list = model_.params(*fs)[0];
      if (list.is_list() && list.count() > 0) {
        // 'AUTOMOTIVE_DESIGN { 1 0 10303 214 ... }': the name without its object identifier.
        schema_name = detail::lower(model_.as_string(model_.items(list)[0]));
        schema_name = schema_name.substr(0, schema_name.find_first_of(" {"));
      }
    }
    for (const p21::Anchor& a : model_.anchors()) {
      put("<ex:anchor name=\"");
      attr(model_.text().substr(a.name_offset, a.name_length));
      put("\">");
      early_item(a.item, binding_.unknown(), std::nullopt);
      put("</ex:anchor>\n");
    }
    std::size_t section_number = 0;
    for (const p21::DataSection& section : model_.sections()) {
      put("<uos id=\"uos_");
      id_number(++section_number);
      put("\" configuration=\"default\" xmlns=\"urn:ncpost:express:");
      attr(schema_name);
      put("\">\n");
      if (section.param_count > 0) {
        put("<ex:section_parameters>");
        const auto params = model_.all_values().subspan(section.first_param, section.param_count);
        for (std::size_t i = 0; i < params.size(); ++i)
          early_item(params[i], binding_.unknown(), i);
        put("</ex:section_parameters>\n");
      }
      for (std::uint32_t i = section.first_instance; i < section.end_instance; ++i) {
        early_instance(model_.instances()[i]);
        maybe_flush();
      }
      put("</uos>\n");
    }
    put("</ex:iso_10303_28>\n");
  }

  // The ed.2 header holds FILE_NAME's fields; FILE_DESCRIPTION and FILE_SCHEMA, and any other
  // header entity, travel as ex:header_entity elements so that nothing of the P21 header is lost.
  void early_header() {
    put("<ex:iso_10303_28_header>\n");
    if (const Instance* fn = model_.header_entity("FILE_NAME")) {
      static constexpr std::array<std::string_view, 7> kFields = {
          "name",         "time_stamp",           "author",
          "organization", "preprocessor_version", "originating_system",
          "authorization"};
      const auto params = model_.params(*fn);
      for (std::size_t i = 0; i < kFields.size() && i < params.size(); ++i) {
        const Value v = params[i];
        const auto one = [&](Value s) {
          put("<ex:");
          put(kFields[i]);
          put(">");
          if (s.kind() == ValueKind::String) string_content(s);
          put("</ex:");
          put(kFields[i]);
          put(">\n");
        };
        if (v.is_list()) {
          for (Value s : model_.items(v)) one(s);
        } else {
          one(v);
        }
      }
    }
    put("</ex:iso_10303_28_header>\n");
    for (const Instance& h : model_.header()) {
      put("<ex:header_entity express_entity_name=\"");
      attr(detail::lower(model_.type_name(h)));
      put("\">");
      const auto params = model_.params(h);
      for (std::size_t i = 0; i < params.size(); ++i)
        early_attribute(detail::positional_name(i), params[i], binding_.unknown());
      put("</ex:header_entity>\n");
    }
  }

  void early_instance(const Instance& inst) {
    if (inst.keyword == p21::Model::kExternalKeyword) {
      put("<ex:reference id=\"i");
      id_number(inst.id);
      put("\" uri=\"");
      attr(model_.slice(model_.params(inst)[0]));
      put("\"/>\n");
      return;
    }
    if (model_.is_complex(inst)) {
      put("<ex:complex_entity_instance id=\"i");
      id_number(inst.id);
      put("\">");
      for (Value record : model_.params(inst)) {
        put("<ex:partial_entity express_entity_name=\"");
        attr(detail::lower(model_.keyword(record.keyword_id())));
        put("\">");
        const auto params = model_.items(model_.typed_child(record));
        for (std::size_t i = 0; i < params.size(); ++i) {
          if (params[i].is_omitted() && i + 1 != params.size()) continue;
          early_attribute(detail::positional_name(i), params[i], binding_.unknown());
        }
        put("</ex:partial_entity>");
      }
      put("</ex:complex_entity_instance>\n");
      return;
    }
    const EntityPlan& plan = plan_of(inst);
    put("<");
    put(plan.name);
    put(" id=\"i");
    id_number(inst.id);
    put("\">");
    const auto params = model_.params(inst);
    for (std::size_t i = 0; i < params.size(); ++i) {
      const AttributePlan& a = plan.attributes[i];
      // An absent element means unset. Without a schema the last position is written even when
      // unset, so that the reader knows how many parameters the instance has.
      const bool keep_count = !plan.known && i + 1 == params.size();
      if (params[i].is_omitted() && !keep_count) continue;
      early_attribute(a.name, params[i], a.type);
    }
    put("</");
    put(plan.name);
    put(">\n");
  }

  void early_attribute(std::string_view name, Value v, const TypePlan* type) {
    put("<");
    put(name);
    early_body(v, type, std::nullopt, true);
    put("</");
    put(name);
    put(">");
  }

  // Writes the rest of an element whose name is already out ("<name"): attributes, '>', and
  // content. `pos` is the position inside an aggregate.
  void early_body(Value v, const TypePlan* type, std::optional<std::size_t> pos, bool attribute) {
    const auto close_start = [&] {
      if (pos) {
        put(" pos=\"");
        id_number(*pos);
        put("\"");
      }
      put(">");
    };
    while (type->kind == Kind::Defined) type = type->underlying;
    switch (v.kind()) {
      case ValueKind::List: {
        put(" ex:cType=\"");
        put(type->kind == Kind::Aggregate ? aggregate_name(type->aggregate) : "list");
        put("\"");
        close_start();
        const TypePlan* element =
            type->kind == Kind::Aggregate ? type->element : binding_.unknown();
        const auto items = model_.items(v);
        for (std::size_t i = 0; i < items.size(); ++i) early_item(items[i], element, i);
        return;
      }
      case ValueKind::Reference:
      case ValueKind::Typed:
        if (attribute) {
          // A reference or a select value sits in its own element inside the attribute's.
          close_start();
          early_item(v, type, std::nullopt);
          return;
        }
        break;
      default:
        if (attribute && type->kind == Kind::Unknown) {
          // Without a declared type the text alone would not say whether '12' is a number or
          // a string: a wrapper element names the kind.
          close_start();
          early_item(v, type, std::nullopt);
          return;
        }
        break;
    }
    close_start();
    early_text(v, type);
  }

  // One element standing for a value: inside an aggregate (pos set), under an attribute for
  // references and select values, or in anchors and section parameters.
  void early_item(Value v, const TypePlan* type, std::optional<std::size_t> pos) {
    const TypePlan* declared = type;
    switch (v.kind()) {
      case ValueKind::Reference: {
        const Instance* target = model_.find(v.id());
        put("<");
        put(target && !model_.is_complex(*target) ? std::string_view(lower_name(target->keyword))
                                                  : std::string_view("ex:entity"));
        put(" ref=\"i");
        id_number(v.id());
        put("\" xsi:nil=\"true\"");
        if (pos) {
          put(" pos=\"");
          id_number(*pos);
          put("\"");
        }
        put("/>");
        return;
      }
      case ValueKind::Typed: {
        const std::string name = detail::lower(model_.keyword(v.keyword_id()));
        put("<");
        put(name);
        early_body(model_.typed_child(v), binding_.named_type(name), pos, false);
        put("</");
        put(name);
        put(">");
        return;
      }
      default:
        break;
    }
    // Element name: the declared defined type if there is one, else a wrapper for the kind.
    std::string name;
    if (declared->kind == Kind::Defined) {
      name = declared->name;
    } else {
      switch (v.kind()) {
        case ValueKind::Omitted:
          name = "ex:unset";
          break;
        case ValueKind::Derived:
          name = "ex:derived";
          break;
        case ValueKind::Integer:
          name = declared->kind == Kind::Real ? "ex:double-wrapper" : "ex:long-wrapper";
          break;
        case ValueKind::Real:
          name = "ex:double-wrapper";
          break;
        case ValueKind::String:
          name = "ex:string-wrapper";
          break;
        case ValueKind::Binary:
          name = "ex:hexBinary-wrapper";
          break;
        case ValueKind::Enumeration:
          name = declared->kind == Kind::Boolean   ? "ex:boolean-wrapper"
                 : declared->kind == Kind::Logical ? "ex:logical-wrapper"
                                                   : "ex:enumeration-wrapper";
          break;
        case ValueKind::List:
          name = "ex:aggregate-wrapper";
          break;
        case ValueKind::ConstantName:
          name = "ex:constant";
          break;
        case ValueKind::ValueName:
          name = "ex:value-instance";
          break;
        case ValueKind::Resource:
          name = "ex:resource";
          break;
        default:
          name = "ex:unknown";
          break;
      }
    }
    put("<");
    put(name);
    early_body(v, declared, pos, false);
    put("</");
    put(name);
    put(">");
  }

  void early_text(Value v, const TypePlan* type) {
    switch (v.kind()) {
      case ValueKind::Integer:
        text(model_.slice(v));
        if (type->kind == Kind::Real) put(".");
        return;
      case ValueKind::Real:
      case ValueKind::Binary:
      case ValueKind::ConstantName:
      case ValueKind::ValueName:
      case ValueKind::Resource:
        text(model_.slice(v));
        return;
      case ValueKind::String:
        string_content(v);
        return;
      case ValueKind::Enumeration: {
        const std::string_view e = model_.slice(v);
        if (type->kind == Kind::Boolean || type->kind == Kind::Logical) {
          put(e == "T" || e == "t" ? "true" : e == "F" || e == "f" ? "false" : "unknown");
        } else {
          text(detail::lower(e));
        }
        return;
      }
      default:
        return;  // $ and * have no content
    }
  }

  const p21::Model& model_;
  detail::Binding binding_;
  Binding form_;
  const p21::TextSink& sink_;
  std::string out_;
  std::string decoded_;
  std::vector<diag::Diagnostic> notes_;
  std::vector<std::string> lower_names_;
  std::vector<const EntityPlan*> plans_;
  std::unordered_set<std::string> noted_;
  std::unordered_set<std::string> short_;
};

}  // namespace

std::vector<diag::Diagnostic> write(const p21::Model& model, const express::SchemaSet* schemas,
                                    Binding binding, const p21::TextSink& sink) {
  return Writer(model, schemas, binding, sink).run();
}

}  // namespace ncpost::p28
