// Parser: token cursor, error recovery, and the schema-level declarations (SCHEMA, USE/REFERENCE,
// CONSTANT, and the algorithm blocks that are skipped as balanced units).

#include "parser.hpp"

#include <array>

#include "text.hpp"

namespace ncpost::express::detail {

Parser::Parser(std::string_view source, std::vector<Token> tokens,
               diag::DiagnosticList& diagnostics, const ParseLimits& limits)
    : source_(source), tokens_(std::move(tokens)), diagnostics_(diagnostics), limits_(limits) {}

// ---------------------------------------------------------------------------------------------
// Cursor

const Token& Parser::peek(std::size_t ahead) const noexcept {
  // Once the error limit is reached every loop sees the end of input and unwinds.
  if (stopped_) return tokens_.back();
  const std::size_t index = next_ + ahead;
  return index < tokens_.size() ? tokens_[index] : tokens_.back();
}

bool Parser::at_punct(std::string_view punct) const noexcept {
  const Token& token = peek();
  return token.kind == TokenKind::Punct && text(token) == punct;
}

bool Parser::at_identifier() const noexcept {
  const Token& token = peek();
  return token.kind == TokenKind::Identifier && token.keyword == Keyword::None;
}

bool Parser::at_block_boundary() const noexcept {
  switch (peek().keyword) {
    case Keyword::EndEntity:
    case Keyword::EndType:
    case Keyword::EndSchema:
    case Keyword::EndConstant:
    case Keyword::EndFunction:
    case Keyword::EndProcedure:
    case Keyword::EndRule:
    case Keyword::EndSubtypeConstraint:
    case Keyword::Entity:
    case Keyword::Type:
    case Keyword::Schema:
    case Keyword::Constant:
    case Keyword::Function:
    case Keyword::Procedure:
    case Keyword::Rule:
    case Keyword::SubtypeConstraint:
      return true;
    default:
      return at_end();
  }
}

const Token& Parser::take() noexcept {
  const Token& token = peek();
  if (!stopped_ && next_ + 1 < tokens_.size()) ++next_;
  return token;
}

bool Parser::accept(Keyword keyword) noexcept {
  if (!at(keyword)) return false;
  take();
  return true;
}

bool Parser::accept_punct(std::string_view punct) noexcept {
  if (!at_punct(punct)) return false;
  take();
  return true;
}

bool Parser::expect(Keyword keyword, std::string_view context) {
  if (accept(keyword)) return true;
  syntax_error(context.empty() ? std::string(keyword_spelling(keyword))
                               : cat(keyword_spelling(keyword), " ", context));
  return false;
}

bool Parser::expect_punct(std::string_view punct, std::string_view context) {
  if (accept_punct(punct)) return true;
  syntax_error(context.empty() ? cat("'", punct, "'") : cat("'", punct, "' ", context));
  return false;
}

std::optional<NamedRef> Parser::expect_identifier(std::string_view what) {
  if (!at_identifier()) {
    syntax_error(what);
    return std::nullopt;
  }
  const Token& token = take();
  return NamedRef{to_lower(text(token)), pos(token)};
}

std::string_view Parser::text(const Token& token) const noexcept {
  return source_.substr(token.offset, token.length);
}

void Parser::syntax_error(std::string_view expected) {
  const Token& found = peek();
  std::string message = "expected ";
  message.append(expected).append(", found ");
  if (found.kind == TokenKind::End) {
    message.append("end of input");
  } else {
    message.append(1, '\'').append(text(found)).append(1, '\'');
  }
  report(diag::Code::ExpSyntax, found, std::move(message));
}

void Parser::report(diag::Code code, const Token& at, std::string message) {
  if (stopped_) return;
  diagnostics_.add(code, at.line, at.column, std::move(message));
  check_error_limit();
}

void Parser::check_error_limit() {
  if (stopped_ || !diagnostics_.full()) return;
  const Token& at = tokens_[next_];
  diagnostics_.add(diag::Code::ExpTooManyErrors, at.line, at.column,
                   "too many errors; the rest of the schema was not read");
  stopped_ = true;
}

void Parser::skip_statement() {
  while (!at_block_boundary()) {
    const Token& token = take();
    if (token.kind == TokenKind::Punct && text(token) == ";") return;
  }
}

// ---------------------------------------------------------------------------------------------
// SCHEMA

std::vector<Schema> Parser::parse_schemas() {
  std::vector<Schema> schemas;
  while (!at_end()) {
    if (at(Keyword::Schema)) {
      Schema schema;
      parse_schema(schema);
      schemas.push_back(std::move(schema));
      continue;
    }
    syntax_error("SCHEMA");
    // One message for a run of stray text: skip to the next SCHEMA.
    while (!at_end() && !at(Keyword::Schema)) take();
  }
  if (schemas.empty() && !stopped_)
    report(diag::Code::ExpNoSchema, peek(), "the source contains no SCHEMA declaration");
  return schemas;
}

bool Parser::parse_schema(Schema& schema) {
  const Token& head = take();
  schema.pos = pos(head);
  if (auto name = expect_identifier("schema name")) schema.name = std::move(name->name);
  if (peek().kind == TokenKind::String) {
    const std::string_view quoted = text(take());
    schema.version = std::string(quoted.substr(1, quoted.size() >= 2 ? quoted.size() - 2 : 0));
  }
  if (!expect_punct(";", "after the schema name")) skip_statement();

  for (;;) {
    if (at(Keyword::EndSchema)) {
      take();
      if (!expect_punct(";", "after END_SCHEMA")) skip_statement();
      return true;
    }
    if (at_end() || at(Keyword::Schema)) {
      report(diag::Code::ExpMissingEnd, head,
             cat("SCHEMA ", schema.name, " is not closed by END_SCHEMA"));
      return false;
    }
    switch (peek().keyword) {
      case Keyword::Use:
      case Keyword::Reference:
        parse_interface(schema);
        break;
      case Keyword::Constant:
        parse_constant_block(schema);
        break;
      case Keyword::Entity:
        parse_entity(schema);
        break;
      case Keyword::Type:
        parse_type_decl(schema);
        break;
      case Keyword::Function:
      case Keyword::Procedure:
      case Keyword::Rule:
      case Keyword::SubtypeConstraint:
        parse_algorithm(schema);
        break;
      default:
        syntax_error("a declaration or END_SCHEMA");
        take();  // a stray END_x is a block boundary; consume it so that the loop advances
        skip_statement();
        break;
    }
  }
}

// USE FROM s [(a, b AS c)] ;   REFERENCE FROM s [(f, g AS h)] ;
bool Parser::parse_interface(Schema& schema) {
  Interface interface;
  interface.kind = take().keyword == Keyword::Use ? InterfaceKind::Use : InterfaceKind::Reference;
  bool ok = expect(Keyword::From, "");
  std::optional<NamedRef> source;
  if (ok) source = expect_identifier("schema name");
  ok = ok && source.has_value();
  if (ok) interface.schema = std::move(*source);
  if (ok && accept_punct("(")) {
    do {
      auto item = expect_identifier("name of an imported declaration");
      if (!item) {
        ok = false;
        break;
      }
      InterfaceItem imported{std::move(*item), {}};
      if (accept(Keyword::As)) {
        auto alias = expect_identifier("alias after AS");
        if (!alias) {
          ok = false;
          break;
        }
        imported.alias = std::move(alias->name);
      }
      interface.items.push_back(std::move(imported));
    } while (accept_punct(","));
    ok = ok && expect_punct(")", "closing the import list");
  }
  ok = ok && expect_punct(";", "after the import");
  if (!ok) {
    skip_statement();
    return false;
  }
  schema.interfaces.push_back(std::move(interface));
  return true;
}

// ---------------------------------------------------------------------------------------------
// CONSTANT

void Parser::parse_constant_block(Schema& schema) {
  const Token& head = take();
  for (;;) {
    if (accept(Keyword::EndConstant)) break;
    if (at_block_boundary()) {
      report(diag::Code::ExpMissingEnd, head, "CONSTANT block is not closed by END_CONSTANT");
      return;
    }
    if (!parse_constant(schema)) skip_statement();
  }
  if (!expect_punct(";", "after END_CONSTANT")) skip_statement();
}

// name : type := expression ;
bool Parser::parse_constant(Schema& schema) {
  auto name = expect_identifier("constant name");
  if (!name || !expect_punct(":", "after the constant name")) return false;
  auto type = parse_type(0);
  if (!type || !expect_punct(":=", "before the constant value")) return false;
  auto value = parse_expression(";");
  if (!value || !expect_punct(";", "after the constant value")) return false;
  schema.constants.push_back(
      Constant{std::move(name->name), name->pos, std::move(*type), std::move(*value)});
  return true;
}

// ---------------------------------------------------------------------------------------------
// FUNCTION, PROCEDURE, RULE, SUBTYPE_CONSTRAINT: kept by name, body skipped as a balanced block.

namespace {

struct AlgorithmBlock {
  Keyword open;
  Keyword close;
  AlgorithmKind kind;
};

constexpr std::array kAlgorithmBlocks = {
    AlgorithmBlock{Keyword::Function, Keyword::EndFunction, AlgorithmKind::Function},
    AlgorithmBlock{Keyword::Procedure, Keyword::EndProcedure, AlgorithmKind::Procedure},
    AlgorithmBlock{Keyword::Rule, Keyword::EndRule, AlgorithmKind::Rule},
    AlgorithmBlock{Keyword::SubtypeConstraint, Keyword::EndSubtypeConstraint,
                   AlgorithmKind::SubtypeConstraint},
};

const AlgorithmBlock* block_opened_by(Keyword keyword) noexcept {
  for (const auto& block : kAlgorithmBlocks)
    if (block.open == keyword) return &block;
  return nullptr;
}

const AlgorithmBlock* block_closed_by(Keyword keyword) noexcept {
  for (const auto& block : kAlgorithmBlocks)
    if (block.close == keyword) return &block;
  return nullptr;
}

}  // namespace

bool Parser::parse_algorithm(Schema& schema) {
  const Token& head = take();
  const AlgorithmBlock* block = block_opened_by(head.keyword);
  Algorithm algorithm;
  algorithm.kind = block->kind;
  algorithm.pos = pos(head);
  if (auto name = expect_identifier("name")) algorithm.name = std::move(name->name);

  // RULE r FOR (e1, e2);  SUBTYPE_CONSTRAINT c FOR e;  -- kept: they name the entities.
  if (block->kind == AlgorithmKind::Rule && accept(Keyword::For) && accept_punct("(")) {
    do {
      if (auto entity = expect_identifier("entity name")) algorithm.applies_to.push_back(*entity);
    } while (accept_punct(","));
  } else if (block->kind == AlgorithmKind::SubtypeConstraint && accept(Keyword::For)) {
    if (auto entity = expect_identifier("entity name")) algorithm.applies_to.push_back(*entity);
  }
  const bool ok = skip_algorithm_body(head);
  if (!algorithm.name.empty()) schema.algorithms.push_back(std::move(algorithm));
  return ok;
}

// Skips to the END_x that closes `head`, keeping a stack of the blocks opened inside (local
// functions and procedures nest). Stops in front of END_SCHEMA if the block is never closed.
bool Parser::skip_algorithm_body(const Token& head) {
  std::vector<Keyword> open_blocks{block_opened_by(head.keyword)->close};
  while (!open_blocks.empty()) {
    const Token& token = peek();
    if (token.kind == TokenKind::End || token.keyword == Keyword::EndSchema) {
      report(diag::Code::ExpMissingEnd, head,
             cat(text(head), " block is not closed by ",
                 keyword_spelling(block_opened_by(head.keyword)->close)));
      return false;
    }
    take();
    if (const AlgorithmBlock* inner = block_opened_by(token.keyword)) {
      if (open_blocks.size() >= limits_.max_nesting_depth) {
        report(
            diag::Code::ExpNestingTooDeep, token,
            cat("algorithm blocks nested deeper than ", std::to_string(limits_.max_nesting_depth)));
        while (!at_end() && !at(Keyword::EndSchema)) take();
        return false;
      }
      open_blocks.push_back(inner->close);
    } else if (block_closed_by(token.keyword) != nullptr) {
      if (token.keyword != open_blocks.back()) {
        report(
            diag::Code::ExpSyntax, token,
            cat("expected ", keyword_spelling(open_blocks.back()), ", found '", text(token), "'"));
      }
      open_blocks.pop_back();
    }
  }
  if (!expect_punct(";", "after the end of the block")) {
    skip_statement();
    return false;
  }
  return true;
}

}  // namespace ncpost::express::detail
