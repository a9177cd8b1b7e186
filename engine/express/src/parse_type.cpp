// TYPE declarations (defined types, SELECT, ENUMERATION) and type specifications (simple,
// named, aggregate, generic).

#include "parser.hpp"
#include "text.hpp"

namespace ncpost::express::detail {

// TYPE name = underlying_type ; [WHERE rules] END_TYPE ;
bool Parser::parse_type_decl(Schema& schema) {
  const Token& head = take();
  TypeDecl decl;
  decl.pos = pos(head);
  bool ok = true;
  if (auto name = expect_identifier("type name")) {
    decl.name = std::move(name->name);
  } else {
    ok = false;
  }
  ok = ok && expect_punct("=", "after the type name");
  if (ok) {
    const bool extensible = accept(Keyword::Extensible);
    const bool generic_entity = extensible && accept(Keyword::GenericEntity);
    if (at(Keyword::Select)) {
      ok = parse_select(decl, extensible, generic_entity);
    } else if (at(Keyword::Enumeration) && !generic_entity) {
      ok = parse_enumeration(decl, extensible);
    } else if (extensible) {
      syntax_error("SELECT or ENUMERATION after EXTENSIBLE");
      ok = false;
    } else if (auto type = parse_type(0)) {
      decl.underlying = std::move(*type);
    } else {
      ok = false;
    }
  }
  ok = ok && expect_punct(";", "after the underlying type");
  if (!ok) skip_statement();

  if (accept(Keyword::Where)) parse_where_clause(decl.where_rules);
  if (!accept(Keyword::EndType)) {
    report(diag::Code::ExpMissingEnd, head,
           cat("TYPE ", decl.name, " is not closed by END_TYPE (found '",
               at_end() ? std::string_view("end of input") : text(peek()), "')"));
    // Resume at the next declaration; what lies between is one broken statement.
    while (!at_block_boundary()) take();
    return false;
  }
  if (!expect_punct(";", "after END_TYPE")) skip_statement();
  if (!ok || decl.name.empty()) return false;
  schema.types.push_back(std::move(decl));
  return true;
}

// SELECT (a, b)  |  SELECT BASED_ON s [WITH (c, d)]  |  SELECT  (an empty extensible select)
bool Parser::parse_select(TypeDecl& decl, bool extensible, bool generic_entity) {
  decl.underlying.pos = pos(take());  // SELECT
  decl.underlying.kind = TypeKind::Select;
  decl.select.extensible = extensible;
  decl.select.generic_entity = generic_entity;
  if (accept(Keyword::BasedOn)) {
    auto base = expect_identifier("name of the extended SELECT");
    if (!base) return false;
    decl.select.based_on = std::move(*base);
    if (!accept(Keyword::With)) return true;
  } else if (!at_punct("(")) {
    if (extensible) return true;
    syntax_error("'(' and the SELECT items");
    return false;
  }
  auto items = parse_name_list("a type or entity name");
  if (!items) return false;
  decl.select.items = std::move(*items);
  return true;
}

// ENUMERATION OF (a, b)  |  ENUMERATION BASED_ON e [WITH (c, d)]  |  ENUMERATION (extensible)
bool Parser::parse_enumeration(TypeDecl& decl, bool extensible) {
  decl.underlying.pos = pos(take());  // ENUMERATION
  decl.underlying.kind = TypeKind::Enumeration;
  decl.enumeration.extensible = extensible;
  std::optional<std::vector<NamedRef>> items;
  if (accept(Keyword::BasedOn)) {
    auto base = expect_identifier("name of the extended ENUMERATION");
    if (!base) return false;
    decl.enumeration.based_on = std::move(*base);
    if (!accept(Keyword::With)) return true;
    items = parse_name_list("an enumeration item");
  } else if (accept(Keyword::Of)) {
    items = parse_name_list("an enumeration item");
  } else {
    if (extensible) return true;
    syntax_error("OF and the enumeration items");
    return false;
  }
  if (!items) return false;
  for (auto& item : *items) decl.enumeration.items.push_back(std::move(item.name));
  return true;
}

// '(' name { ',' name } ')'
std::optional<std::vector<NamedRef>> Parser::parse_name_list(std::string_view what) {
  if (!expect_punct("(", "")) return std::nullopt;
  std::vector<NamedRef> names;
  do {
    auto name = expect_identifier(what);
    if (!name) return std::nullopt;
    names.push_back(std::move(*name));
  } while (accept_punct(","));
  if (!expect_punct(")", "closing the list")) return std::nullopt;
  return names;
}

std::optional<TypeSpec> Parser::parse_type(std::uint32_t depth) {
  if (depth >= limits_.max_nesting_depth) {
    report(diag::Code::ExpNestingTooDeep, peek(),
           cat("types nested deeper than ", std::to_string(limits_.max_nesting_depth)));
    return std::nullopt;
  }
  const Token& head = peek();
  TypeSpec type;
  type.pos = pos(head);
  switch (head.keyword) {
    case Keyword::Integer:
    case Keyword::Number:
    case Keyword::Boolean:
    case Keyword::Logical:
      take();
      type.kind = head.keyword == Keyword::Integer   ? TypeKind::Integer
                  : head.keyword == Keyword::Number  ? TypeKind::Number
                  : head.keyword == Keyword::Boolean ? TypeKind::Boolean
                                                     : TypeKind::Logical;
      return type;
    case Keyword::Real:
    case Keyword::String:
    case Keyword::Binary:
      take();
      type.kind = head.keyword == Keyword::Real     ? TypeKind::Real
                  : head.keyword == Keyword::String ? TypeKind::String
                                                    : TypeKind::Binary;
      if (!parse_width(type)) return std::nullopt;
      return type;
    case Keyword::List:
    case Keyword::Set:
    case Keyword::Bag:
    case Keyword::Array:
    case Keyword::Aggregate:
      take();
      return parse_aggregate(head, depth);
    case Keyword::Generic:
    case Keyword::GenericEntity:
      take();
      type.kind = head.keyword == Keyword::Generic ? TypeKind::Generic : TypeKind::GenericEntity;
      if (accept_punct(":")) {
        auto label = expect_identifier("type label");
        if (!label) return std::nullopt;
        type.name = std::move(label->name);
      }
      return type;
    default:
      break;
  }
  auto name = expect_identifier("a type");
  if (!name) return std::nullopt;
  type.kind = TypeKind::Named;
  type.name = std::move(name->name);
  return type;
}

// LIST [l:u] OF [UNIQUE] t, SET [l:u] OF t, BAG [l:u] OF t, ARRAY [l:u] OF [OPTIONAL] [UNIQUE] t,
// AGGREGATE [: label] OF t. Bounds are optional except for ARRAY.
std::optional<TypeSpec> Parser::parse_aggregate(const Token& head, std::uint32_t depth) {
  TypeSpec type;
  type.kind = TypeKind::Aggregate;
  type.pos = pos(head);
  switch (head.keyword) {
    case Keyword::List:
      type.aggregate = AggregateKind::List;
      break;
    case Keyword::Set:
      type.aggregate = AggregateKind::Set;
      break;
    case Keyword::Bag:
      type.aggregate = AggregateKind::Bag;
      break;
    case Keyword::Array:
      type.aggregate = AggregateKind::Array;
      break;
    default:
      type.aggregate = AggregateKind::Aggregate;
      break;
  }
  if (type.aggregate == AggregateKind::Aggregate) {
    if (accept_punct(":")) {
      auto label = expect_identifier("type label");
      if (!label) return std::nullopt;
      type.name = std::move(label->name);
    }
  } else if (at_punct("[")) {
    if (!parse_bound_spec(type.lower, type.upper)) return std::nullopt;
  } else if (type.aggregate == AggregateKind::Array) {
    syntax_error("'[' and the bounds of the ARRAY");
    return std::nullopt;
  }
  if (!expect(Keyword::Of, "")) return std::nullopt;
  type.optional_elements = accept(Keyword::Optional);
  type.unique_elements = accept(Keyword::Unique);
  auto element = parse_type(depth + 1);
  if (!element) return std::nullopt;
  type.element = std::make_shared<const TypeSpec>(std::move(*element));
  return type;
}

// '[' bound ':' bound ']'
bool Parser::parse_bound_spec(std::optional<Bound>& lower, std::optional<Bound>& upper) {
  if (!expect_punct("[", "")) return false;
  lower = parse_bound(":");
  if (!lower || !expect_punct(":", "between the bounds")) return false;
  upper = parse_bound("]");
  return upper && expect_punct("]", "after the bounds");
}

// REAL (precision)  STRING (width) [FIXED]  BINARY (width) [FIXED]
bool Parser::parse_width(TypeSpec& type) {
  if (accept_punct("(")) {
    type.width = parse_expression(")");
    if (!type.width || !expect_punct(")", "after the width")) return false;
  }
  if (type.kind != TypeKind::Real) type.fixed = accept(Keyword::Fixed);
  return true;
}

}  // namespace ncpost::express::detail
