#include "ncpost/express/types.hpp"

namespace ncpost::express {

std::string_view simple_type_keyword(TypeKind kind) noexcept {
  switch (kind) {
    case TypeKind::Integer:
      return "INTEGER";
    case TypeKind::Real:
      return "REAL";
    case TypeKind::Number:
      return "NUMBER";
    case TypeKind::String:
      return "STRING";
    case TypeKind::Binary:
      return "BINARY";
    case TypeKind::Boolean:
      return "BOOLEAN";
    case TypeKind::Logical:
      return "LOGICAL";
    default:
      return {};
  }
}

std::string_view aggregate_keyword(AggregateKind kind) noexcept {
  switch (kind) {
    case AggregateKind::List:
      return "LIST";
    case AggregateKind::Set:
      return "SET";
    case AggregateKind::Bag:
      return "BAG";
    case AggregateKind::Array:
      return "ARRAY";
    case AggregateKind::Aggregate:
      return "AGGREGATE";
  }
  return {};
}

std::string to_express(const TypeSpec& type) {
  std::string out;
  // Aggregates nest through `element`: a loop, so no recursion on deep types.
  for (const TypeSpec* current = &type; current != nullptr;) {
    switch (current->kind) {
      case TypeKind::Named:
        out += current->name;
        return out;
      case TypeKind::Select:
        out += "SELECT";
        return out;
      case TypeKind::Enumeration:
        out += "ENUMERATION";
        return out;
      case TypeKind::Generic:
      case TypeKind::GenericEntity:
        out += current->kind == TypeKind::Generic ? "GENERIC" : "GENERIC_ENTITY";
        if (!current->name.empty()) out.append(" : ").append(current->name);
        return out;
      case TypeKind::Aggregate:
        out += aggregate_keyword(current->aggregate);
        if (current->aggregate == AggregateKind::Aggregate && !current->name.empty())
          out.append(" : ").append(current->name);
        if (current->lower && current->upper)
          out.append(" [")
              .append(current->lower->text)
              .append(":")
              .append(current->upper->text)
              .append("]");
        out += " OF ";
        if (current->optional_elements) out += "OPTIONAL ";
        if (current->unique_elements) out += "UNIQUE ";
        current = current->element.get();
        break;
      default:  // simple types
        out += simple_type_keyword(current->kind);
        if (current->width) out.append(" (").append(current->width->text).append(")");
        if (current->fixed) out += " FIXED";
        return out;
    }
  }
  return out;
}

}  // namespace ncpost::express
