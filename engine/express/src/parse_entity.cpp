// ENTITY declarations: the SUPERTYPE/SUBTYPE header and the explicit, DERIVE, INVERSE, UNIQUE
// and WHERE clauses of the body.

#include "parser.hpp"
#include "text.hpp"

namespace ncpost::express::detail {

// ENTITY name [ABSTRACT [SUPERTYPE [OF (...)]] | SUPERTYPE OF (...)] [SUBTYPE OF (...)] ;
//   body
// END_ENTITY ;
bool Parser::parse_entity(Schema& schema) {
  const Token& head = take();
  Entity entity;
  entity.pos = pos(head);
  bool ok = true;
  if (auto name = expect_identifier("entity name")) {
    entity.name = std::move(name->name);
  } else {
    ok = false;
  }
  ok = ok && parse_subsuper(entity);
  ok = ok && expect_punct(";", "after the entity header");
  if (!ok) skip_statement();

  parse_entity_body(entity);
  if (!accept(Keyword::EndEntity)) {
    report(diag::Code::ExpMissingEnd, head,
           cat("ENTITY ", entity.name, " is not closed by END_ENTITY (found '",
               at_end() ? std::string_view("end of input") : text(peek()), "')"));
  } else if (!expect_punct(";", "after END_ENTITY")) {
    skip_statement();
  }
  if (entity.name.empty()) return false;
  schema.entities.push_back(std::move(entity));
  return ok;
}

bool Parser::parse_subsuper(Entity& entity) {
  for (;;) {
    if (accept(Keyword::Abstract)) {
      entity.is_abstract = true;
      if (!accept(Keyword::Supertype)) continue;  // ISO 10303-11:2004 `ABSTRACT` alone
      entity.declares_supertype = true;
      if (!accept(Keyword::Of)) continue;  // `ABSTRACT SUPERTYPE;`
    } else if (accept(Keyword::Supertype)) {
      entity.declares_supertype = true;
      if (!expect(Keyword::Of, "after SUPERTYPE")) return false;
    } else if (accept(Keyword::Subtype)) {
      if (!expect(Keyword::Of, "after SUBTYPE")) return false;
      auto supertypes = parse_name_list("a supertype name");
      if (!supertypes) return false;
      entity.supertypes = std::move(*supertypes);
      continue;
    } else {
      return true;
    }
    // SUPERTYPE OF ( supertype_expression )
    if (!expect_punct("(", "before the subtype expression")) return false;
    entity.subtype_constraint = parse_supertype_expression(0);
    if (!entity.subtype_constraint) return false;
    if (!expect_punct(")", "after the subtype expression")) return false;
  }
}

// supertype_expression = factor { ANDOR factor } ; factor = term { AND term }
std::optional<SupertypeExpression> Parser::parse_supertype_expression(std::uint32_t depth) {
  auto first = parse_supertype_factor(depth);
  if (!first || !at(Keyword::AndOr)) return first;
  SupertypeExpression andor;
  andor.op = SupertypeExpression::Op::AndOr;
  andor.operands.push_back(std::move(*first));
  while (accept(Keyword::AndOr)) {
    auto next = parse_supertype_factor(depth);
    if (!next) return std::nullopt;
    andor.operands.push_back(std::move(*next));
  }
  return andor;
}

std::optional<SupertypeExpression> Parser::parse_supertype_factor(std::uint32_t depth) {
  auto first = parse_supertype_term(depth);
  if (!first || !at(Keyword::And)) return first;
  SupertypeExpression conjunction;
  conjunction.op = SupertypeExpression::Op::And;
  conjunction.operands.push_back(std::move(*first));
  while (accept(Keyword::And)) {
    auto next = parse_supertype_term(depth);
    if (!next) return std::nullopt;
    conjunction.operands.push_back(std::move(*next));
  }
  return conjunction;
}

// term = entity_ref | ONEOF ( expr { , expr } ) | ( expr )
std::optional<SupertypeExpression> Parser::parse_supertype_term(std::uint32_t depth) {
  if (depth >= limits_.max_nesting_depth) {
    report(
        diag::Code::ExpNestingTooDeep, peek(),
        cat("SUPERTYPE expression nested deeper than ", std::to_string(limits_.max_nesting_depth)));
    return std::nullopt;
  }
  if (accept(Keyword::OneOf)) {
    SupertypeExpression one_of;
    one_of.op = SupertypeExpression::Op::OneOf;
    if (!expect_punct("(", "after ONEOF")) return std::nullopt;
    do {
      auto operand = parse_supertype_expression(depth + 1);
      if (!operand) return std::nullopt;
      one_of.operands.push_back(std::move(*operand));
    } while (accept_punct(","));
    if (!expect_punct(")", "closing ONEOF")) return std::nullopt;
    return one_of;
  }
  if (accept_punct("(")) {
    auto inner = parse_supertype_expression(depth + 1);
    if (!inner || !expect_punct(")", "in the SUPERTYPE expression")) return std::nullopt;
    return inner;
  }
  auto name = expect_identifier("a subtype name, ONEOF or '('");
  if (!name) return std::nullopt;
  SupertypeExpression ref;
  ref.entity = std::move(*name);
  return ref;
}

void Parser::parse_entity_body(Entity& entity) {
  // The clauses come in this order; each keyword switches what the following items are.
  enum class Clause { Explicit, Derive, Inverse, Unique, Where };
  Clause clause = Clause::Explicit;
  while (!at_block_boundary()) {
    std::optional<Clause> next;
    switch (peek().keyword) {
      case Keyword::Derive:
        next = Clause::Derive;
        break;
      case Keyword::Inverse:
        next = Clause::Inverse;
        break;
      case Keyword::Unique:
        next = Clause::Unique;
        break;
      case Keyword::Where:
        next = Clause::Where;
        break;
      default:
        break;
    }
    if (next) {
      if (*next <= clause && clause != Clause::Explicit)
        report(diag::Code::ExpSyntax, peek(),
               cat(text(peek()), " clause out of order or repeated"));
      take();
      clause = *next;
      continue;
    }
    bool ok = false;
    switch (clause) {
      case Clause::Explicit:
        ok = parse_explicit_attribute(entity);
        break;
      case Clause::Derive:
        ok = parse_derived_attribute(entity);
        break;
      case Clause::Inverse:
        ok = parse_inverse_attribute(entity);
        break;
      case Clause::Unique:
        ok = parse_unique_rule(entity);
        break;
      case Clause::Where:
        ok = parse_domain_rule(entity.where_rules);
        break;
    }
    if (!ok) skip_statement();
  }
}

// attribute_id | SELF\entity.attribute [RENAMED attribute_id]
std::optional<Parser::AttributeName> Parser::parse_attribute_decl() {
  if (at(Keyword::Self)) {
    auto qualified = parse_qualified_attribute();
    if (!qualified) return std::nullopt;
    AttributeName decl{qualified->attribute, qualified->pos, std::move(*qualified)};
    if (accept(Keyword::Renamed)) {
      auto renamed = expect_identifier("new attribute name after RENAMED");
      if (!renamed) return std::nullopt;
      decl.name = std::move(renamed->name);
    }
    return decl;
  }
  auto name = expect_identifier("an attribute name");
  if (!name) return std::nullopt;
  return AttributeName{std::move(name->name), name->pos, std::nullopt};
}

// SELF \ entity . attribute
std::optional<QualifiedAttribute> Parser::parse_qualified_attribute() {
  const Token& self = take();
  if (!expect_punct("\\", "after SELF")) return std::nullopt;
  auto entity = expect_identifier("a supertype name");
  if (!entity || !expect_punct(".", "after the supertype name")) return std::nullopt;
  auto attribute = expect_identifier("an attribute name");
  if (!attribute) return std::nullopt;
  return QualifiedAttribute{std::move(entity->name), std::move(attribute->name), pos(self)};
}

// a, b : [OPTIONAL] type ;
bool Parser::parse_explicit_attribute(Entity& entity) {
  std::vector<AttributeName> names;
  do {
    auto name = parse_attribute_decl();
    if (!name) return false;
    names.push_back(std::move(*name));
  } while (accept_punct(","));
  if (!expect_punct(":", "after the attribute name")) return false;
  const bool optional = accept(Keyword::Optional);
  auto type = parse_type(0);
  if (!type || !expect_punct(";", "after the attribute type")) return false;
  for (auto& name : names) {
    entity.explicit_attributes.push_back(ExplicitAttribute{std::move(name.name), name.pos, *type,
                                                           optional, std::move(name.redeclares)});
  }
  return true;
}

// a : type := expression ;
bool Parser::parse_derived_attribute(Entity& entity) {
  auto name = parse_attribute_decl();
  if (!name || !expect_punct(":", "after the derived attribute name")) return false;
  auto type = parse_type(0);
  if (!type || !expect_punct(":=", "before the derivation")) return false;
  auto expression = parse_expression(";");
  if (!expression || !expect_punct(";", "after the derivation")) return false;
  entity.derived_attributes.push_back(DerivedAttribute{std::move(name->name), name->pos,
                                                       std::move(*type), std::move(*expression),
                                                       std::move(name->redeclares)});
  return true;
}

// a : [SET|BAG [l:u] OF] entity FOR [entity .] attribute ;
bool Parser::parse_inverse_attribute(Entity& entity) {
  auto name = parse_attribute_decl();
  if (!name || !expect_punct(":", "after the inverse attribute name")) return false;
  InverseAttribute inverse;
  inverse.name = std::move(name->name);
  inverse.pos = name->pos;
  inverse.redeclares = std::move(name->redeclares);
  if (at(Keyword::Set) || at(Keyword::Bag)) {
    inverse.aggregate = take().keyword == Keyword::Set ? AggregateKind::Set : AggregateKind::Bag;
    if (at_punct("[") && !parse_bound_spec(inverse.lower, inverse.upper)) return false;
    if (!expect(Keyword::Of, "")) return false;
  }
  auto referencing = expect_identifier("the referencing entity");
  if (!referencing || !expect(Keyword::For, "")) return false;
  inverse.entity = std::move(*referencing);
  auto attribute = expect_identifier("the attribute the inverse is for");
  if (!attribute) return false;
  if (accept_punct(".")) {  // FOR entity.attribute (ISO 10303-11:2004)
    attribute = expect_identifier("the attribute the inverse is for");
    if (!attribute) return false;
  }
  inverse.for_attribute = std::move(attribute->name);
  if (!expect_punct(";", "after the inverse attribute")) return false;
  entity.inverse_attributes.push_back(std::move(inverse));
  return true;
}

// [label :] a, SELF\e.b ;
bool Parser::parse_unique_rule(Entity& entity) {
  UniqueRule rule;
  rule.pos = pos(peek());
  if (at_identifier() && peek(1).kind == TokenKind::Punct && text(peek(1)) == ":") {
    rule.label = to_lower(text(take()));
    take();
  }
  do {
    if (at(Keyword::Self)) {
      auto qualified = parse_qualified_attribute();
      if (!qualified) return false;
      rule.attributes.push_back(std::move(*qualified));
    } else {
      auto name = expect_identifier("an attribute name");
      if (!name) return false;
      rule.attributes.push_back(QualifiedAttribute{{}, std::move(name->name), name->pos});
    }
  } while (accept_punct(","));
  if (!expect_punct(";", "after the UNIQUE rule")) return false;
  entity.unique_rules.push_back(std::move(rule));
  return true;
}

void Parser::parse_where_clause(std::vector<DomainRule>& rules) {
  while (!at_block_boundary())
    if (!parse_domain_rule(rules)) skip_statement();
}

// [label :] expression ;
bool Parser::parse_domain_rule(std::vector<DomainRule>& rules) {
  DomainRule rule;
  if (at_identifier() && peek(1).kind == TokenKind::Punct && text(peek(1)) == ":") {
    rule.label = to_lower(text(take()));
    take();
  }
  auto expression = parse_expression(";");
  if (!expression || !expect_punct(";", "after the WHERE rule")) return false;
  rule.expression = std::move(*expression);
  rules.push_back(std::move(rule));
  return true;
}

}  // namespace ncpost::express::detail
