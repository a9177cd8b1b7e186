#pragma once
// Recursive-descent parser over the token vector. It builds the declarations of each SCHEMA as
// written; resolving names and flattening attributes is the Linker's job (linker.hpp).
//
// Error handling: a parse function that meets an unexpected token reports EXP-010 once and
// returns false; its caller resynchronises with skip_statement(), which consumes up to and
// including the next `;` but stops in front of a block boundary (END_x, ENTITY, TYPE, ...), so
// a missing END_ENTITY costs one diagnostic and the next declaration still parses. Every loop
// consumes at least one token per turn, so recovery is linear.
//
// Recursion is used only for nested types and SUPERTYPE expressions, both bounded by
// ParseLimits::max_nesting_depth. Expressions are not parsed into trees: they are scanned
// iteratively for balance and kept as normalised text.

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "lexer.hpp"
#include "ncpost/diag/diagnostic.hpp"
#include "ncpost/express/parse.hpp"
#include "ncpost/express/schema.hpp"

namespace ncpost::express::detail {

class Parser {
 public:
  Parser(std::string_view source, std::vector<Token> tokens, diag::DiagnosticList& diagnostics,
         const ParseLimits& limits);

  // Every SCHEMA of the source, in order.
  [[nodiscard]] std::vector<Schema> parse_schemas();

 private:
  // ---- cursor (parser.cpp) ----
  [[nodiscard]] const Token& peek(std::size_t ahead = 0) const noexcept;
  [[nodiscard]] bool at(Keyword keyword) const noexcept { return peek().keyword == keyword; }
  [[nodiscard]] bool at_punct(std::string_view punct) const noexcept;
  [[nodiscard]] bool at_identifier() const noexcept;
  [[nodiscard]] bool at_end() const noexcept { return peek().kind == TokenKind::End; }
  // END_x and the words that open a declaration: where recovery stops.
  [[nodiscard]] bool at_block_boundary() const noexcept;
  const Token& take() noexcept;
  bool accept(Keyword keyword) noexcept;
  bool accept_punct(std::string_view punct) noexcept;
  [[nodiscard]] bool expect(Keyword keyword, std::string_view context);
  [[nodiscard]] bool expect_punct(std::string_view punct, std::string_view context);
  [[nodiscard]] std::optional<NamedRef> expect_identifier(std::string_view what);
  [[nodiscard]] std::string_view text(const Token& token) const noexcept;
  [[nodiscard]] static SourcePos pos(const Token& token) noexcept {
    return SourcePos{token.line, token.column};
  }
  void syntax_error(std::string_view expected);
  void report(diag::Code code, const Token& at, std::string message);
  void skip_statement();
  [[nodiscard]] bool stopped() const noexcept { return stopped_; }
  void check_error_limit();

  // ---- schema level (parser.cpp) ----
  bool parse_schema(Schema& schema);
  bool parse_interface(Schema& schema);
  void parse_constant_block(Schema& schema);
  bool parse_constant(Schema& schema);
  bool parse_algorithm(Schema& schema);
  bool skip_algorithm_body(const Token& head);

  // ---- entities (parse_entity.cpp) ----
  bool parse_entity(Schema& schema);
  bool parse_subsuper(Entity& entity);
  std::optional<SupertypeExpression> parse_supertype_expression(std::uint32_t depth);
  std::optional<SupertypeExpression> parse_supertype_factor(std::uint32_t depth);
  std::optional<SupertypeExpression> parse_supertype_term(std::uint32_t depth);
  void parse_entity_body(Entity& entity);
  struct AttributeName {
    std::string name;
    SourcePos pos;
    std::optional<QualifiedAttribute> redeclares;
  };
  std::optional<AttributeName> parse_attribute_decl();
  std::optional<QualifiedAttribute> parse_qualified_attribute();
  bool parse_explicit_attribute(Entity& entity);
  bool parse_derived_attribute(Entity& entity);
  bool parse_inverse_attribute(Entity& entity);
  bool parse_unique_rule(Entity& entity);
  // WHERE rules of a TYPE, up to END_TYPE.
  void parse_where_clause(std::vector<DomainRule>& rules);
  bool parse_domain_rule(std::vector<DomainRule>& rules);

  // ---- types (parse_type.cpp) ----
  bool parse_type_decl(Schema& schema);
  bool parse_select(TypeDecl& decl, bool extensible, bool generic_entity);
  bool parse_enumeration(TypeDecl& decl, bool extensible);
  std::optional<std::vector<NamedRef>> parse_name_list(std::string_view what);
  std::optional<TypeSpec> parse_type(std::uint32_t depth);
  std::optional<TypeSpec> parse_aggregate(const Token& head, std::uint32_t depth);
  bool parse_bound_spec(std::optional<Bound>& lower, std::optional<Bound>& upper);
  bool parse_width(TypeSpec& type);

  // ---- expressions (parse_expression.cpp) ----
  // Scans a balanced expression up to (not including) one of the one-character `stops` at
  // nesting depth 0, and returns it as normalised text. Reports and returns nullopt when the
  // expression is empty, unbalanced, too deep, or runs into a block boundary.
  std::optional<Expression> parse_expression(std::string_view stops);
  std::optional<Bound> parse_bound(std::string_view stops);

  std::string_view source_;
  std::vector<Token> tokens_;
  std::size_t next_ = 0;
  diag::DiagnosticList& diagnostics_;
  const ParseLimits& limits_;
  bool stopped_ = false;  // error limit reached: every loop unwinds
};

}  // namespace ncpost::express::detail
