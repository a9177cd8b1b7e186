#pragma once
// The Linker turns the schemas as written into a consistent SchemaSet:
//   1. indexes declarations per schema (duplicates: EXP-020/021);
//   2. resolves USE FROM / REFERENCE FROM between the schemas, to a fixpoint, so that items
//      imported into one schema can be imported from it again (EXP-032/033);
//   3. resolves SUBTYPE OF (EXP-030), breaks inheritance cycles (EXP-036), and, supertypes
//      before subtypes, computes ancestors and the flattened attribute lists (EXP-034);
//   4. checks every remaining reference: attribute types, SELECT items, BASED_ON, INVERSE,
//      SUPERTYPE OF (EXP-031/035/037/038/039).
// Names that a schema imports from a schema missing from the source cannot be checked; they
// are reported once, at the import, and not again at each use.

#include <cstdint>
#include <optional>
#include <string>
#include <unordered_set>
#include <vector>

#include "ncpost/diag/diagnostic.hpp"
#include "ncpost/express/parse.hpp"
#include "ncpost/express/schema.hpp"

namespace ncpost::express::detail {

class Linker {
 public:
  Linker(SchemaSet& set, diag::DiagnosticList& diagnostics, const ParseLimits& limits)
      : set_(set), diagnostics_(diagnostics), limits_(limits) {}

  void link(std::vector<Schema> schemas);

 private:
  void index_declarations();
  void resolve_interfaces();
  void resolve_supertypes();
  // Post-order over SUBTYPE OF: every entity comes after all of its supertypes.
  [[nodiscard]] std::vector<DeclRef> inheritance_order();
  // Entities deeper than ParseLimits::max_inheritance_depth lose their SUBTYPE OF links (EXP-041).
  void limit_inheritance_depth(const std::vector<DeclRef>& order);
  void compute_ancestors(Entity& entity);
  void flatten(Entity& entity);
  void apply_explicit_redeclaration(Entity& entity, const ExplicitAttribute& attribute);
  void apply_derived_redeclaration(Entity& entity, const DerivedAttribute& attribute);
  void check_inverse_redeclaration(const Entity& entity, const InverseAttribute& attribute);
  // The named supertype of `entity` in `SELF\supertype.attr`, or nullptr (reported).
  [[nodiscard]] const Entity* redeclared_supertype(const Entity& entity,
                                                   const QualifiedAttribute& qualified);
  void check_local_attribute_names(const Entity& entity);
  void check_references();
  void check_type(std::uint32_t schema, const TypeSpec& type);
  void check_entity_references(const Entity& entity);
  void check_supertype_expression(std::uint32_t schema, const SupertypeExpression& expression,
                                  std::uint32_t depth);
  void check_type_decl(const TypeDecl& decl);
  void check_type_cycles();

  // Lookup in a schema's visible names; nullopt for names imported from a missing schema too.
  [[nodiscard]] std::optional<DeclRef> lookup(std::uint32_t schema, const std::string& name) const;
  // True when a failed lookup must not be reported: the name may come from a missing schema.
  [[nodiscard]] bool unknowable(std::uint32_t schema, const std::string& name) const;
  [[nodiscard]] Entity& entity(DeclRef ref);
  void report(diag::Code code, SourcePos pos, std::string message);

  SchemaSet& set_;
  diag::DiagnosticList& diagnostics_;
  const ParseLimits& limits_;
  // Per schema: names imported from a schema that is not in the source, and whether a whole
  // schema that is not in the source was imported (then every unknown name is unknowable).
  std::vector<std::unordered_set<std::string>> external_names_;
  std::vector<bool> imports_missing_schema_;
};

}  // namespace ncpost::express::detail
