#pragma once
// EXPRESS-X: the XML form of an EXPRESS schema in the style of ISO 10303-28 (first edition),
// as the XSLT post-processor paper shows it for `cartesian_point`: one element per grammar
// production, each carrying `express-production="<production name>"`, e.g.
//
//   <entity_decl express-production="entity_decl">
//     <entity_id express-production="entity_id">cartesian_point</entity_id>
//     <subtype_of express-production="subtype_declaration">
//       <entity_ref express-production="entity_ref" refType="refid (entity_id)">point</entity_ref>
//   ...
//
// The full element vocabulary is in docs/express.md. The writer streams: it never builds a
// document tree, and the ostream form flushes after every declaration.

#include <iosfwd>
#include <string>

#include "ncpost/express/schema.hpp"

namespace ncpost::express {

struct ExpressXOptions {
  // Also write FUNCTION / PROCEDURE / RULE / SUBTYPE_CONSTRAINT declarations (by name only).
  bool include_algorithms = true;
};

// The whole set as one XML document (root element `express`).
void write_express_x(const SchemaSet& set, std::ostream& out, const ExpressXOptions& options = {});
[[nodiscard]] std::string to_express_x(const SchemaSet& set, const ExpressXOptions& options = {});

}  // namespace ncpost::express
