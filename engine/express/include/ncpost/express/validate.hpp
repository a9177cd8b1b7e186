#pragma once
// Checks a Model (read from P21 or P28) against an EXPRESS schema.
//
// In:  a Model and the SchemaSet that describes it (SchemaRegistry::select_for picks it).
// Out: diagnostics EXP-058 .. EXP-069, each at the instance's line:column, naming `#id`, the
//      entity and the attribute. An empty list means every instance fits the schema as far as
//      these checks go:
//
//  - the entity is declared (EXP-060, a warning, once per entity name), and not ABSTRACT (EXP-059);
//  - the parameter count is the flattened explicit attribute count (EXP-061);
//  - `$` only for OPTIONAL attributes and OPTIONAL aggregate elements (EXP-062);
//  - each value is of a kind the declared type allows (EXP-063): integers are accepted for REAL
//    and NUMBER; a SELECT value that is not an entity is written typed, `LENGTH_MEASURE(5.)`;
//  - a reference names an instance of the declared entity or a subtype, or of an entity of the
//    declared SELECT (EXP-064; a complex instance fits when one of its partial records does);
//  - aggregate sizes are within the declared bounds (EXP-065): integer bounds, and bounds that
//    are an INTEGER attribute of the same instance (`ARRAY [1:SELF\mesh.index_count]`); other
//    expressions are not evaluated; an ARRAY has exactly hi - lo + 1 elements;
//  - enumeration values belong to the enumeration (with its extensions), BOOLEAN takes .T./.F.,
//    LOGICAL also .U. (EXP-066);
//  - `*` exactly where a subtype re-declares the attribute as DERIVE (EXP-067 for a `*`
//    elsewhere, an error; EXP-068 for a value or `$` where `*` belongs, a warning);
//  - a typed parameter names a member of the declared SELECT (EXP-069).
//
// Complex instances `(A(...) B(...))`: each partial record is checked against the explicit
// attributes its own entity declares (ISO 10303-21 external mapping), with redeclarations by the
// other records' entities applied; bounds that are attribute expressions are not evaluated there.
// Instances of undeclared entities, ed.3 references, constants and value instances are skipped.
//
// With ValidateOptions::tolerant, EXP-059, EXP-062 and EXP-064 are warnings aggregated per
// entity and attribute instead.
//
// Cost: one pass over the instances and their values; types, SELECT closures and enumeration
// items are resolved once per declaration, for the pass or, with a CheckPlan, for good.

#include <atomic>
#include <cstddef>
#include <memory>
#include <span>
#include <string_view>
#include <vector>

#include "ncpost/diag/diagnostic.hpp"
#include "ncpost/express/schema.hpp"
#include "ncpost/p21/model.hpp"
#include "ncpost/parallel/pieces.hpp"

namespace ncpost::express {

// What a check learns about a schema set's types (what each declared type stands for, the
// members of each SELECT, the items of each ENUMERATION), learnt for all of them once. Without a
// plan every check learns what it needs again: on a small file that is most of its work.
// Immutable once made: any number of checks may read one plan at once.
class CheckPlan {
 public:
  explicit CheckPlan(const SchemaSet& set);
  ~CheckPlan();
  CheckPlan(const CheckPlan&) = delete;
  CheckPlan& operator=(const CheckPlan&) = delete;

  [[nodiscard]] const SchemaSet& set() const noexcept;

  class Impl;
  [[nodiscard]] const Impl& impl() const noexcept { return *impl_; }

 private:
  std::unique_ptr<const Impl> impl_;
};

// A name other systems write, read as a name the schema declares (lower case both): the table is
// engine/stepnc's (stepnc/variants.hpp), the schema layer only applies it.
struct NameAlias {
  std::string_view written;
  std::string_view read_as;
};

struct ValidateOptions {
  // At most this many diagnostics are returned; after them one EXP-058 says how many more
  // problems there were. A large file that was written for another schema would otherwise give
  // a diagnostic per instance.
  std::size_t max_diagnostics = 1000;
  // Set by another thread to stop the check (a job that was cancelled): looked at every few
  // thousand instances. A cancelled check returns what it found so far, which is no verdict;
  // the caller knows that it cancelled. Null: never cancelled.
  const std::atomic<bool>* cancel = nullptr;
  // Threads lent to check a large model in pieces (null: one thread); the diagnostics are the
  // same either way.
  const parallel::Helpers* helpers = nullptr;
  // No piece has fewer instances than this: below it, starting threads costs more than it saves.
  std::size_t min_piece_instances = 50000;
  // The plan for the schema set checked against (ignored when it was made for another set);
  // null: the check learns the types it meets.
  const CheckPlan* plan = nullptr;
  // Programs from other systems leave out what machining never reads (a person's id, a
  // setup's instructions) and use supertypes where ISO 14649 names subtypes. Tolerant, the
  // deviations the interpreter and the feature generators check again where they read a value
  // (EXP-059 an ABSTRACT entity instantiated, EXP-062 '$' where the attribute is not OPTIONAL,
  // EXP-064 a reference to an entity of another type) are warnings, one per code, entity and
  // attribute with a count and the first instance, after the other diagnostics and outside
  // max_diagnostics (there are at most as many as the schema has attributes). False: one error
  // per instance (`--strict`). docs/interoperability.md, "Tolerant and strict".
  bool tolerant = false;
  // Entities the schema does not declare that are checked as the entity each alias names (an
  // instance of TOOL_DIMENSION checked as a MILLING_TOOL_DIMENSION, and referenced where one is
  // wanted); the strings must outlive the check. Empty: undeclared entities are EXP-060.
  std::span<const NameAlias> entity_aliases;
};

[[nodiscard]] std::vector<diag::Diagnostic> validate(const p21::Model& model,
                                                     const SchemaSet& schema,
                                                     const ValidateOptions& options = {});

}  // namespace ncpost::express
