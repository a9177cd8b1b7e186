#pragma once
// Shared by the P28 tests: schemas, conversions and well-formedness.

#include <libxml/parser.h>

#include <memory>
#include <string>

#include "corpus.hpp"
#include "ncpost/express/parse.hpp"
#include "ncpost/p21/compare.hpp"
#include "ncpost/p21/reader.hpp"
#include "ncpost/p28/p28.hpp"
#include "xml_check.hpp"

namespace ncpost::p28::test {

inline const express::SchemaSet& own_schema() {
  static const express::ParseResult parsed = express::parse_express(
      ncpost::test::read_file(ncpost::test::source_dir() / "schemas/iso14649.exp"));
  return parsed.schemas;
}

inline std::string to_p28(const p21::Model& model, const express::SchemaSet* schemas,
                          Binding binding) {
  std::string xml;
  const auto notes = write(model, schemas, binding, [&](std::string_view piece) { xml += piece; });
  (void)notes;
  return xml;
}

using ncpost::test::well_formed;

inline std::string dump(const std::vector<diag::Diagnostic>& diagnostics) {
  std::string out;
  for (const auto& d : diagnostics) out += diag::format(d, "xml") + "\n";
  return out;
}

}  // namespace ncpost::p28::test
