// parse_express: lexer → parser → linker, all diagnostics collected in one bounded list.

#include "ncpost/express/parse.hpp"

#include <algorithm>
#include <string>

#include "lexer.hpp"
#include "linker.hpp"
#include "parser.hpp"
#include "text.hpp"

namespace ncpost::express {

ParseResult parse_express(std::string_view source, const ParseLimits& limits) {
  ParseResult result;
  diag::DiagnosticList diagnostics(limits.max_errors);
  // Token offsets are 32-bit; the configured limit is far below that.
  const std::size_t hard_limit = std::size_t{0xFFFFFFFF};
  if (source.size() > limits.max_input_bytes || source.size() > hard_limit) {
    diagnostics.add(diag::Code::ExpInputTooLarge, 0, 0,
                    detail::cat("schema source is ", std::to_string(source.size()),
                                " bytes; the limit is ", std::to_string(limits.max_input_bytes)));
    result.diagnostics = std::move(diagnostics).take();
    return result;
  }
  std::vector<detail::Token> tokens = detail::tokenize(source, diagnostics);
  std::vector<Schema> schemas;
  if (diagnostics.full()) {
    diagnostics.add(diag::Code::ExpTooManyErrors, 0, 0,
                    "too many lexical errors; the schema was not parsed");
  } else {
    detail::Parser parser(source, std::move(tokens), diagnostics, limits);
    schemas = parser.parse_schemas();
  }
  detail::Linker linker(result.schemas, diagnostics, limits);
  linker.link(std::move(schemas));
  result.diagnostics = std::move(diagnostics).take();
  // Linking reports after parsing; present everything in source order.
  std::stable_sort(result.diagnostics.begin(), result.diagnostics.end(),
                   [](const diag::Diagnostic& a, const diag::Diagnostic& b) {
                     return a.line != b.line ? a.line < b.line : a.column < b.column;
                   });
  return result;
}

}  // namespace ncpost::express
