// EXPRESS-X writer: walks a SchemaSet and streams the XML form of each declaration, in source
// order. Element names follow the XSLT post-processor paper (entity_decl, subtype_of,
// explicit_attr_block, base_type, list_type, bound_spec, ...); every element names its EXPRESS
// grammar production in `express-production`. See docs/express.md for the vocabulary.

#include <algorithm>
#include <ostream>

#include "ncpost/express/express_x.hpp"
#include "xml_out.hpp"

namespace ncpost::express {
namespace {

using detail::XmlOut;

constexpr std::string_view kEntityRefType = "refid (entity_id)";
constexpr std::string_view kTypeRefType = "refid (type_id)";
constexpr std::string_view kAttributeRefType = "refid (attribute_id)";
constexpr std::string_view kSchemaRefType = "refid (schema_id)";

bool is_integer_literal(std::string_view text) {
  return !text.empty() &&
         std::all_of(text.begin(), text.end(), [](char c) { return c >= '0' && c <= '9'; });
}

// One top-level declaration of a schema, for writing them in source order.
struct Item {
  SourcePos pos;
  DeclKind kind;
  std::uint32_t index;
};

class ExpressXWriter {
 public:
  ExpressXWriter(const SchemaSet& set, const ExpressXOptions& options, std::string& buffer,
                 std::ostream* sink)
      : set_(set), options_(options), buffer_(buffer), xml_(buffer), sink_(sink) {}

  void write() {
    xml_.declaration();
    xml_.open("express", "syntax");
    for (std::uint32_t s = 0; s < set_.schemas().size(); ++s) schema(s);
    xml_.close();
    flush();
  }

 private:
  void flush() {
    if (sink_ == nullptr) return;
    sink_->write(buffer_.data(), static_cast<std::streamsize>(buffer_.size()));
    buffer_.clear();
  }

  void schema(std::uint32_t s) {
    const Schema& schema = set_.schemas()[s];
    xml_.open("schema_decl", "schema_decl");
    xml_.leaf("schema_id", "schema_id", schema.name);
    if (!schema.version.empty())
      xml_.leaf("schema_version_id", "schema_version_id", schema.version);
    xml_.open("schema_body", "schema_body");
    for (const Interface& interface : schema.interfaces) interface_spec(interface);
    flush();
    if (!schema.constants.empty()) {
      constant_decl(s);
      flush();
    }
    for (const Item& item : items_in_source_order(schema)) {
      switch (item.kind) {
        case DeclKind::Entity:
          entity_decl(schema.entities[item.index]);
          break;
        case DeclKind::Type:
          type_decl(schema.types[item.index]);
          break;
        default:
          algorithm_decl(s, schema.algorithms[item.index]);
          break;
      }
      flush();
    }
    xml_.close();  // schema_body
    xml_.close();  // schema_decl
  }

  std::vector<Item> items_in_source_order(const Schema& schema) const {
    std::vector<Item> items;
    for (std::uint32_t i = 0; i < schema.types.size(); ++i)
      items.push_back({schema.types[i].pos, DeclKind::Type, i});
    for (std::uint32_t i = 0; i < schema.entities.size(); ++i)
      items.push_back({schema.entities[i].pos, DeclKind::Entity, i});
    if (options_.include_algorithms)
      for (std::uint32_t i = 0; i < schema.algorithms.size(); ++i)
        items.push_back({schema.algorithms[i].pos, DeclKind::Function, i});
    std::stable_sort(items.begin(), items.end(), [](const Item& a, const Item& b) {
      return a.pos.line != b.pos.line ? a.pos.line < b.pos.line : a.pos.column < b.pos.column;
    });
    return items;
  }

  // ---- interface specifications ----

  void interface_spec(const Interface& interface) {
    const bool use = interface.kind == InterfaceKind::Use;
    xml_.open(use ? "use_clause" : "reference_clause", use ? "use_clause" : "reference_clause");
    xml_.leaf("schema_ref", "schema_ref", interface.schema.name, {{"refType", kSchemaRefType}});
    const Schema* source = set_.find_schema(interface.schema.name);
    for (const InterfaceItem& item : interface.items) {
      const std::string_view wrapper = use ? "named_type_or_rename" : "resource_or_rename";
      xml_.open(wrapper, wrapper);
      if (source != nullptr && source->find_entity(item.item.name) != nullptr) {
        xml_.leaf("entity_ref", "entity_ref", item.item.name, {{"refType", kEntityRefType}});
      } else if (source != nullptr && source->find_type(item.item.name) != nullptr) {
        xml_.leaf("type_ref", "type_ref", item.item.name, {{"refType", kTypeRefType}});
      } else {
        xml_.leaf("resource_ref", "resource_ref", item.item.name);
      }
      if (!item.alias.empty()) xml_.leaf("rename_id", "rename_id", item.alias);
      xml_.close();
    }
    xml_.close();
  }

  // ---- constants ----

  void constant_decl(std::uint32_t s) {
    xml_.open("constant_decl", "constant_decl");
    for (const Constant& constant : set_.schemas()[s].constants) {
      xml_.open("constant_body", "constant_body");
      xml_.leaf("constant_id", "constant_id", constant.name);
      base_type(s, constant.type);
      expression(constant.value.text);
      xml_.close();
    }
    xml_.close();
  }

  // ---- TYPE ----

  void type_decl(const TypeDecl& decl) {
    xml_.open("type_decl", "type_decl");
    xml_.leaf("type_id", "type_id", decl.name);
    xml_.open("underlying_type", "underlying_type");
    if (decl.underlying.kind == TypeKind::Select) {
      select_type(decl);
    } else if (decl.underlying.kind == TypeKind::Enumeration) {
      enumeration_type(decl);
    } else {
      type_spec(decl.schema, decl.underlying);
    }
    xml_.close();
    where_clause(decl.where_rules);
    xml_.close();
  }

  void select_type(const TypeDecl& decl) {
    const SelectSpec& select = decl.select;
    if (select.extensible && select.generic_entity) {
      xml_.open("select_type", "select_type", {{"extensible", "true"}, {"generic_entity", "true"}});
    } else if (select.extensible) {
      xml_.open("select_type", "select_type", {{"extensible", "true"}});
    } else {
      xml_.open("select_type", "select_type");
    }
    if (select.based_on) {
      xml_.open("select_extension", "select_extension");
      xml_.leaf("type_ref", "type_ref", select.based_on->name, {{"refType", kTypeRefType}});
      if (!select.items.empty()) select_list(decl);
      xml_.close();
    } else if (!select.items.empty()) {
      select_list(decl);
    }
    xml_.close();
  }

  void select_list(const TypeDecl& decl) {
    xml_.open("select_list", "select_list");
    for (const NamedRef& item : decl.select.items) named_ref(decl.schema, item.name);
    xml_.close();
  }

  void enumeration_type(const TypeDecl& decl) {
    const EnumerationSpec& enumeration = decl.enumeration;
    if (enumeration.extensible) {
      xml_.open("enumeration_type", "enumeration_type", {{"extensible", "true"}});
    } else {
      xml_.open("enumeration_type", "enumeration_type");
    }
    if (enumeration.based_on) {
      xml_.open("enumeration_extension", "enumeration_extension");
      xml_.leaf("type_ref", "type_ref", enumeration.based_on->name, {{"refType", kTypeRefType}});
      if (!enumeration.items.empty()) enumeration_items(enumeration);
      xml_.close();
    } else if (!enumeration.items.empty()) {
      enumeration_items(enumeration);
    }
    xml_.close();
  }

  void enumeration_items(const EnumerationSpec& enumeration) {
    xml_.open("enumeration_items", "enumeration_items");
    for (const std::string& item : enumeration.items)
      xml_.leaf("enumeration_id", "enumeration_id", item);
    xml_.close();
  }

  // ---- types as used by attributes, constants and aggregates ----

  void base_type(std::uint32_t schema, const TypeSpec& type) {
    xml_.open("base_type", "base_type");
    type_spec(schema, type);
    xml_.close();
  }

  // Nesting depth is bounded by the parser's max_nesting_depth.
  void type_spec(std::uint32_t schema, const TypeSpec& type) {
    switch (type.kind) {
      case TypeKind::Named:
        named_ref(schema, type.name);
        return;
      case TypeKind::Aggregate:
        aggregate_type(schema, type);
        return;
      case TypeKind::Generic:
      case TypeKind::GenericEntity: {
        const bool entity = type.kind == TypeKind::GenericEntity;
        const std::string_view name = entity ? "generic_entity_type" : "generic_type";
        if (type.name.empty()) {
          xml_.leaf(name, name, {});
        } else {
          xml_.open(name, name);
          xml_.leaf("type_label", "type_label", type.name);
          xml_.close();
        }
        return;
      }
      case TypeKind::Select:
      case TypeKind::Enumeration:
        return;  // only as the underlying type of a TYPE, written by type_decl
      default:
        simple_type(type);
        return;
    }
  }

  void simple_type(const TypeSpec& type) {
    static constexpr std::string_view kNames[] = {"integer_type", "real_type",   "number_type",
                                                  "string_type",  "binary_type", "boolean_type",
                                                  "logical_type"};
    const std::string_view name = kNames[static_cast<std::size_t>(type.kind)];
    if (!type.width) {
      xml_.leaf(name, name, {});
      return;
    }
    xml_.open(name, name);
    const bool precision = type.kind == TypeKind::Real;
    const std::string_view spec = precision ? "precision_spec" : "width_spec";
    if (type.fixed) {
      xml_.open(spec, spec, {{"fixed", "true"}});
    } else {
      xml_.open(spec, spec);
    }
    value(type.width->text);
    xml_.close();
    xml_.close();
  }

  void aggregate_type(std::uint32_t schema, const TypeSpec& type) {
    static constexpr std::string_view kNames[] = {"list_type", "set_type", "bag_type", "array_type",
                                                  "aggregate_type"};
    const std::string_view name = kNames[static_cast<std::size_t>(type.aggregate)];
    if (type.optional_elements && type.unique_elements) {
      xml_.open(name, name, {{"optional", "true"}, {"unique", "true"}});
    } else if (type.optional_elements) {
      xml_.open(name, name, {{"optional", "true"}});
    } else if (type.unique_elements) {
      xml_.open(name, name, {{"unique", "true"}});
    } else {
      xml_.open(name, name);
    }
    if (type.aggregate == AggregateKind::Aggregate && !type.name.empty())
      xml_.leaf("type_label", "type_label", type.name);
    if (type.lower && type.upper) bound_spec(*type.lower, *type.upper);
    if (type.element) base_type(schema, *type.element);
    xml_.close();
  }

  void bound_spec(const Bound& lower, const Bound& upper) {
    xml_.open("bound_spec", "bound_spec");
    xml_.open("lower_bound", "bound_1");
    value(lower.text);
    xml_.close();
    xml_.open("upper_bound", "bound_2");
    value(upper.text);
    xml_.close();
    xml_.close();
  }

  // An integer literal, the indeterminate `?`, or any other expression as text.
  void value(const std::string& text) {
    if (is_integer_literal(text)) {
      xml_.leaf("integer_literal", "integer_literal", text);
    } else if (text == "?") {
      xml_.leaf("builtin_constant", "built_in_constant", text);
    } else {
      expression(text);
    }
  }

  void expression(const std::string& text) { xml_.leaf("expression", "expression", text); }

  void named_ref(std::uint32_t schema, std::string_view name) {
    const auto ref = set_.resolve(schema, name);
    if (ref && ref->kind == DeclKind::Entity) {
      xml_.leaf("entity_ref", "entity_ref", name, {{"refType", kEntityRefType}});
    } else {
      xml_.leaf("type_ref", "type_ref", name, {{"refType", kTypeRefType}});
    }
  }

  // ---- ENTITY ----

  void entity_decl(const Entity& e) {
    xml_.open("entity_decl", "entity_decl");
    xml_.leaf("entity_id", "entity_id", e.name);
    supertype_constraint(e);
    if (!e.supertypes.empty()) {
      xml_.open("subtype_of", "subtype_declaration");
      for (const NamedRef& super : e.supertypes)
        xml_.leaf("entity_ref", "entity_ref", super.name, {{"refType", kEntityRefType}});
      xml_.close();
    }
    if (!e.explicit_attributes.empty()) {
      xml_.open("explicit_attr_block", "explicit_attr_block");
      for (const ExplicitAttribute& attribute : e.explicit_attributes) explicit_attr(e, attribute);
      xml_.close();
    }
    if (!e.derived_attributes.empty()) {
      xml_.open("derive_clause", "derive_clause");
      for (const DerivedAttribute& attribute : e.derived_attributes) {
        xml_.open("derived_attr", "derived_attr");
        attribute_decl(attribute.name, attribute.redeclares);
        base_type(e.schema, attribute.type);
        expression(attribute.expression.text);
        xml_.close();
      }
      xml_.close();
    }
    if (!e.inverse_attributes.empty()) {
      xml_.open("inverse_clause", "inverse_clause");
      for (const InverseAttribute& attribute : e.inverse_attributes) inverse_attr(attribute);
      xml_.close();
    }
    if (!e.unique_rules.empty()) {
      xml_.open("unique_clause", "unique_clause");
      for (const UniqueRule& rule : e.unique_rules) unique_rule(rule);
      xml_.close();
    }
    where_clause(e.where_rules);
    xml_.close();
  }

  void supertype_constraint(const Entity& e) {
    if (e.is_abstract && !e.declares_supertype) {
      xml_.leaf("abstract_entity", "abstract_entity_declaration", {});
      return;
    }
    if (!e.declares_supertype) return;
    if (e.is_abstract) {
      xml_.open("abstract_supertype", "abstract_supertype_declaration");
    } else {
      xml_.open("supertype_of", "supertype_rule");
    }
    if (e.subtype_constraint) {
      xml_.open("subtype_constraint", "subtype_constraint");
      supertype_expression(*e.subtype_constraint);
      xml_.close();
    }
    xml_.close();
  }

  // Depth is bounded by the parser's max_nesting_depth.
  void supertype_expression(const SupertypeExpression& expression) {
    switch (expression.op) {
      case SupertypeExpression::Op::Entity:
        xml_.leaf("entity_ref", "entity_ref", expression.entity.name,
                  {{"refType", kEntityRefType}});
        return;
      case SupertypeExpression::Op::OneOf:
        xml_.open("one_of", "one_of");
        break;
      case SupertypeExpression::Op::And:
        xml_.open("and", "supertype_factor");
        break;
      case SupertypeExpression::Op::AndOr:
        xml_.open("andor", "supertype_expression");
        break;
    }
    for (const auto& operand : expression.operands) supertype_expression(operand);
    xml_.close();
  }

  void explicit_attr(const Entity& e, const ExplicitAttribute& attribute) {
    if (attribute.optional) {
      xml_.open("explicit_attr", "explicit_attr", {{"optional", "true"}});
    } else {
      xml_.open("explicit_attr", "explicit_attr");
    }
    attribute_decl(attribute.name, attribute.redeclares);
    base_type(e.schema, attribute.type);
    xml_.close();
  }

  void attribute_decl(const std::string& name,
                      const std::optional<QualifiedAttribute>& redeclares) {
    if (!redeclares) {
      xml_.leaf("attribute_id", "attribute_id", name);
      return;
    }
    xml_.open("redeclared_attribute", "redeclared_attribute");
    qualified_attribute(*redeclares);
    if (name != redeclares->attribute) xml_.leaf("rename_id", "attribute_id", name);
    xml_.close();
  }

  void qualified_attribute(const QualifiedAttribute& qualified) {
    xml_.open("qualified_attribute", "qualified_attribute");
    xml_.leaf("entity_ref", "entity_ref", qualified.entity, {{"refType", kEntityRefType}});
    xml_.leaf("attribute_ref", "attribute_ref", qualified.attribute,
              {{"refType", kAttributeRefType}});
    xml_.close();
  }

  void inverse_attr(const InverseAttribute& attribute) {
    xml_.open("inverse_attr", "inverse_attr");
    attribute_decl(attribute.name, attribute.redeclares);
    if (attribute.aggregate) {
      const bool set = *attribute.aggregate == AggregateKind::Set;
      xml_.open(set ? "set_type" : "bag_type", set ? "set_type" : "bag_type");
      if (attribute.lower && attribute.upper) bound_spec(*attribute.lower, *attribute.upper);
      xml_.close();
    }
    xml_.leaf("entity_ref", "entity_ref", attribute.entity.name, {{"refType", kEntityRefType}});
    xml_.leaf("attribute_ref", "attribute_ref", attribute.for_attribute,
              {{"refType", kAttributeRefType}});
    xml_.close();
  }

  void unique_rule(const UniqueRule& rule) {
    xml_.open("unique_rule", "unique_rule");
    if (!rule.label.empty()) xml_.leaf("rule_label_id", "rule_label_id", rule.label);
    for (const QualifiedAttribute& attribute : rule.attributes) {
      xml_.open("referenced_attribute", "referenced_attribute");
      if (attribute.entity.empty()) {
        xml_.leaf("attribute_ref", "attribute_ref", attribute.attribute,
                  {{"refType", kAttributeRefType}});
      } else {
        qualified_attribute(attribute);
      }
      xml_.close();
    }
    xml_.close();
  }

  void where_clause(const std::vector<DomainRule>& rules) {
    if (rules.empty()) return;
    xml_.open("where_clause", "where_clause");
    for (const DomainRule& rule : rules) {
      xml_.open("domain_rule", "domain_rule");
      if (!rule.label.empty()) xml_.leaf("rule_label_id", "rule_label_id", rule.label);
      expression(rule.expression.text);
      xml_.close();
    }
    xml_.close();
  }

  // ---- FUNCTION / PROCEDURE / RULE / SUBTYPE_CONSTRAINT (by name) ----

  void algorithm_decl(std::uint32_t schema, const Algorithm& algorithm) {
    struct Names {
      std::string_view decl, head, id;
    };
    static constexpr Names kNames[] = {
        {"function_decl", "function_head", "function_id"},
        {"procedure_decl", "procedure_head", "procedure_id"},
        {"rule_decl", "rule_head", "rule_id"},
        {"subtype_constraint_decl", "subtype_constraint_head", "subtype_constraint_id"},
    };
    const Names& names = kNames[static_cast<std::size_t>(algorithm.kind)];
    xml_.open(names.decl, names.decl);
    xml_.open(names.head, names.head);
    xml_.leaf(names.id, names.id, algorithm.name);
    for (const NamedRef& target : algorithm.applies_to) named_ref(schema, target.name);
    xml_.close();
    xml_.close();
  }

  const SchemaSet& set_;
  const ExpressXOptions& options_;
  std::string& buffer_;
  XmlOut xml_;
  std::ostream* sink_;
};

}  // namespace

void write_express_x(const SchemaSet& set, std::ostream& out, const ExpressXOptions& options) {
  std::string buffer;
  ExpressXWriter(set, options, buffer, &out).write();
}

std::string to_express_x(const SchemaSet& set, const ExpressXOptions& options) {
  std::string buffer;
  ExpressXWriter(set, options, buffer, nullptr).write();
  return buffer;
}

}  // namespace ncpost::express
