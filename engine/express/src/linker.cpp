#include "linker.hpp"

#include <algorithm>
#include <string>
#include <unordered_map>
#include <utility>

#include "lexer.hpp"
#include "text.hpp"

namespace ncpost::express::detail {
namespace {

std::string kind_name(DeclKind kind) {
  switch (kind) {
    case DeclKind::Entity:
      return "ENTITY";
    case DeclKind::Type:
      return "TYPE";
    case DeclKind::Constant:
      return "CONSTANT";
    case DeclKind::Function:
      return "FUNCTION";
    case DeclKind::Procedure:
      return "PROCEDURE";
    case DeclKind::Rule:
      return "RULE";
    case DeclKind::SubtypeConstraint:
      return "SUBTYPE_CONSTRAINT";
  }
  return "declaration";
}

DeclKind decl_kind(AlgorithmKind kind) {
  switch (kind) {
    case AlgorithmKind::Function:
      return DeclKind::Function;
    case AlgorithmKind::Procedure:
      return DeclKind::Procedure;
    case AlgorithmKind::Rule:
      return DeclKind::Rule;
    case AlgorithmKind::SubtypeConstraint:
      return DeclKind::SubtypeConstraint;
  }
  return DeclKind::Function;
}

bool contains(const std::vector<DeclRef>& refs, DeclRef ref) {
  return std::find(refs.begin(), refs.end(), ref) != refs.end();
}

}  // namespace

void Linker::link(std::vector<Schema> schemas) {
  set_.schemas_ = std::move(schemas);
  const std::size_t count = set_.schemas_.size();
  set_.visible_.assign(count, {});
  external_names_.assign(count, {});
  imports_missing_schema_.assign(count, false);
  for (std::uint32_t s = 0; s < count; ++s) {
    Schema& schema = set_.schemas_[s];
    for (auto& e : schema.entities) e.schema = s;
    for (auto& t : schema.types) t.schema = s;
  }
  index_declarations();
  resolve_interfaces();
  resolve_supertypes();
  const std::vector<DeclRef> order = inheritance_order();
  limit_inheritance_depth(order);
  for (const DeclRef ref : order) {
    Entity& e = entity(ref);
    compute_ancestors(e);
    flatten(e);
    for (const DeclRef super : e.supertype_refs) entity(super).subtypes.push_back(ref);
  }
  check_references();
  check_type_cycles();
}

void Linker::report(diag::Code code, SourcePos pos, std::string message) {
  if (diagnostics_.full()) return;
  diagnostics_.add(code, pos.line, pos.column, std::move(message));
}

Entity& Linker::entity(DeclRef ref) {
  return set_.schemas_[ref.schema].entities[ref.index];
}

std::optional<DeclRef> Linker::lookup(std::uint32_t schema, const std::string& name) const {
  const auto& visible = set_.visible_[schema];
  const auto it = visible.find(name);
  if (it == visible.end()) return std::nullopt;
  return it->second;
}

bool Linker::unknowable(std::uint32_t schema, const std::string& name) const {
  return imports_missing_schema_[schema] || external_names_[schema].count(name) != 0;
}

// ---------------------------------------------------------------------------------------------
// 1. Declarations

void Linker::index_declarations() {
  std::unordered_set<std::string> schema_names;
  for (std::uint32_t s = 0; s < set_.schemas_.size(); ++s) {
    Schema& schema = set_.schemas_[s];
    if (!schema_names.insert(schema.name).second)
      report(diag::Code::ExpDuplicateSchema, schema.pos,
             cat("SCHEMA ", schema.name, " is declared twice; the first is used for imports"));
    std::unordered_map<std::string, SourcePos> first_seen;
    auto add = [&](const std::string& name, SourcePos pos, DeclRef ref) {
      const auto [it, inserted] = schema.declarations.emplace(name, ref);
      if (inserted) {
        first_seen.emplace(name, pos);
        return;
      }
      report(diag::Code::ExpDuplicateDeclaration, pos,
             cat(kind_name(ref.kind), " ", name, " is declared again; the ",
                 kind_name(it->second.kind), " of line ", std::to_string(first_seen[name].line),
                 " is kept"));
    };
    for (std::uint32_t i = 0; i < schema.entities.size(); ++i)
      add(schema.entities[i].name, schema.entities[i].pos, DeclRef{DeclKind::Entity, s, i});
    for (std::uint32_t i = 0; i < schema.types.size(); ++i)
      add(schema.types[i].name, schema.types[i].pos, DeclRef{DeclKind::Type, s, i});
    for (std::uint32_t i = 0; i < schema.constants.size(); ++i)
      add(schema.constants[i].name, schema.constants[i].pos, DeclRef{DeclKind::Constant, s, i});
    for (std::uint32_t i = 0; i < schema.algorithms.size(); ++i)
      add(schema.algorithms[i].name, schema.algorithms[i].pos,
          DeclRef{decl_kind(schema.algorithms[i].kind), s, i});
    set_.visible_[s] = schema.declarations;
  }
}

// ---------------------------------------------------------------------------------------------
// 2. USE FROM / REFERENCE FROM

void Linker::resolve_interfaces() {
  const auto schema_index = [&](const std::string& name) -> std::optional<std::uint32_t> {
    for (std::uint32_t s = 0; s < set_.schemas_.size(); ++s)
      if (set_.schemas_[s].name == name) return s;
    return std::nullopt;
  };
  // Each pass copies what the source schemas can see now; imports of imports need further
  // passes, and no chain is longer than the number of schemas.
  bool changed = true;
  for (std::size_t pass = 0; changed && pass <= set_.schemas_.size(); ++pass) {
    changed = false;
    for (std::uint32_t s = 0; s < set_.schemas_.size(); ++s) {
      for (const Interface& interface : set_.schemas_[s].interfaces) {
        const auto source = schema_index(interface.schema.name);
        if (!source || *source == s) continue;
        const auto& from = set_.visible_[*source];
        auto& into = set_.visible_[s];
        if (interface.items.empty()) {
          for (const auto& [name, ref] : from) changed |= into.emplace(name, ref).second;
          continue;
        }
        for (const InterfaceItem& item : interface.items) {
          const auto it = from.find(item.item.name);
          if (it == from.end()) continue;
          const std::string& local = item.alias.empty() ? item.item.name : item.alias;
          changed |= into.emplace(local, it->second).second;
        }
      }
    }
  }
  for (std::uint32_t s = 0; s < set_.schemas_.size(); ++s) {
    for (const Interface& interface : set_.schemas_[s].interfaces) {
      const auto source = schema_index(interface.schema.name);
      if (!source) {
        report(diag::Code::ExpUnknownSchema, interface.schema.pos,
               cat("SCHEMA ", interface.schema.name,
                   " is not in the source; its declarations cannot be checked"));
        if (interface.items.empty()) imports_missing_schema_[s] = true;
        for (const InterfaceItem& item : interface.items)
          external_names_[s].insert(item.alias.empty() ? item.item.name : item.alias);
        continue;
      }
      for (const InterfaceItem& item : interface.items) {
        if (set_.visible_[*source].count(item.item.name) == 0)
          report(diag::Code::ExpUnknownImport, item.item.pos,
                 cat("SCHEMA ", interface.schema.name, " has no declaration ", item.item.name));
      }
    }
  }
}

// ---------------------------------------------------------------------------------------------
// 3. Inheritance

void Linker::resolve_supertypes() {
  for (std::uint32_t s = 0; s < set_.schemas_.size(); ++s) {
    auto& entities = set_.schemas_[s].entities;
    for (std::uint32_t i = 0; i < entities.size(); ++i) {
      Entity& e = entities[i];
      for (const NamedRef& super : e.supertypes) {
        const auto ref = lookup(s, super.name);
        if (!ref) {
          if (!unknowable(s, super.name))
            report(diag::Code::ExpUnknownSupertype, super.pos,
                   cat("ENTITY ", e.name, ": supertype ", super.name, " is not declared"));
          continue;
        }
        if (ref->kind != DeclKind::Entity) {
          report(diag::Code::ExpUnknownSupertype, super.pos,
                 cat("ENTITY ", e.name, ": supertype ", super.name, " is a ", kind_name(ref->kind),
                     ", not an ENTITY"));
          continue;
        }
        if (contains(e.supertype_refs, *ref)) continue;
        e.supertype_refs.push_back(*ref);
      }
    }
  }
}

std::vector<DeclRef> Linker::inheritance_order() {
  // Entity numbering across schemas, for the visit marks.
  std::vector<std::size_t> offset(set_.schemas_.size() + 1, 0);
  for (std::size_t s = 0; s < set_.schemas_.size(); ++s)
    offset[s + 1] = offset[s] + set_.schemas_[s].entities.size();
  const auto id = [&](DeclRef ref) { return offset[ref.schema] + ref.index; };
  enum : std::uint8_t { kNew, kOnPath, kDone };
  std::vector<std::uint8_t> mark(offset.back(), kNew);

  std::vector<DeclRef> order;
  order.reserve(offset.back());
  struct Frame {
    DeclRef ref;
    std::size_t next_super;
  };
  std::vector<Frame> path;  // explicit stack: a hostile 100 000-level hierarchy is no problem
  for (std::uint32_t s = 0; s < set_.schemas_.size(); ++s) {
    for (std::uint32_t i = 0; i < set_.schemas_[s].entities.size(); ++i) {
      const DeclRef root{DeclKind::Entity, s, i};
      if (mark[id(root)] != kNew) continue;
      mark[id(root)] = kOnPath;
      path.push_back({root, 0});
      while (!path.empty()) {
        Frame& top = path.back();
        Entity& e = entity(top.ref);
        if (top.next_super < e.supertype_refs.size()) {
          const DeclRef super = e.supertype_refs[top.next_super];
          if (mark[id(super)] == kNew) {
            ++top.next_super;
            mark[id(super)] = kOnPath;
            path.push_back({super, 0});
          } else if (mark[id(super)] == kOnPath) {
            // A cycle: drop the link that closes it, so that every later step terminates.
            const auto written =
                std::find_if(e.supertypes.begin(), e.supertypes.end(),
                             [&](const NamedRef& n) { return n.name == set_.name_of(super); });
            report(diag::Code::ExpInheritanceCycle,
                   written != e.supertypes.end() ? written->pos : e.pos,
                   cat("ENTITY ", e.name, " inherits from itself through ", set_.name_of(super)));
            e.supertype_refs.erase(e.supertype_refs.begin() +
                                   static_cast<std::ptrdiff_t>(top.next_super));
          } else {
            ++top.next_super;
          }
          continue;
        }
        mark[id(top.ref)] = kDone;
        order.push_back(top.ref);
        path.pop_back();
      }
    }
  }
  return order;
}

// Flattened lists grow with the depth of the hierarchy; a bound on the depth keeps them (and
// the ancestor lists) proportional to the input. Real schemas stay below 20 levels.
void Linker::limit_inheritance_depth(const std::vector<DeclRef>& order) {
  std::vector<std::size_t> offset(set_.schemas_.size() + 1, 0);
  for (std::size_t s = 0; s < set_.schemas_.size(); ++s)
    offset[s + 1] = offset[s] + set_.schemas_[s].entities.size();
  std::vector<std::uint32_t> depth(offset.back(), 0);
  for (const DeclRef ref : order) {
    Entity& e = entity(ref);
    std::uint32_t own = 0;
    for (const DeclRef super : e.supertype_refs)
      own = std::max(own, depth[offset[super.schema] + super.index] + 1);
    if (own > limits_.max_inheritance_depth) {
      report(diag::Code::ExpInheritanceTooDeep, e.pos,
             cat("ENTITY ", e.name, " is more than ", std::to_string(limits_.max_inheritance_depth),
                 " levels below its root supertype; its SUBTYPE OF links are ignored"));
      e.supertype_refs.clear();
      own = 0;
    }
    depth[offset[ref.schema] + ref.index] = own;
  }
}

void Linker::compute_ancestors(Entity& e) {
  for (const DeclRef super_ref : e.supertype_refs) {
    const Entity& super = entity(super_ref);
    for (const DeclRef ancestor : super.ancestors)
      if (!contains(e.ancestors, ancestor)) e.ancestors.push_back(ancestor);
    if (!contains(e.ancestors, super_ref)) e.ancestors.push_back(super_ref);
  }
}

// ISO 10303-21 order: the attributes of each supertype in SUBTYPE OF order (each already
// flattened, so depth-first left-to-right), an attribute reached twice through a common
// ancestor only once, then the entity's own new explicit attributes. Redeclarations keep the
// position of the attribute they redeclare.
void Linker::flatten(Entity& e) {
  std::vector<FlatAttribute>& list = e.attributes;
  for (const DeclRef super_ref : e.supertype_refs) {
    for (const FlatAttribute& inherited : entity(super_ref).attributes) {
      const auto same = std::find_if(list.begin(), list.end(), [&](const FlatAttribute& a) {
        return a.owner == inherited.owner && a.declared_name == inherited.declared_name;
      });
      if (same == list.end()) {
        list.push_back(inherited);
        continue;
      }
      // Reached again through another branch: a DERIVE redeclaration on any branch makes the
      // value derived in the instance; an explicit one narrows the type.
      same->derived_redeclared = same->derived_redeclared || inherited.derived_redeclared;
      if (!inherited.redeclared_by.empty() && same->redeclared_by.empty()) {
        same->type = inherited.type;
        same->optional = inherited.optional;
        same->name = inherited.name;
        same->redeclared_by = inherited.redeclared_by;
        same->schema = inherited.schema;
      }
    }
  }
  check_local_attribute_names(e);
  for (const ExplicitAttribute& attribute : e.explicit_attributes) {
    if (attribute.redeclares) {
      apply_explicit_redeclaration(e, attribute);
    } else {
      list.push_back(FlatAttribute{attribute.name,
                                   e.name,
                                   attribute.name,
                                   attribute.type,
                                   attribute.optional,
                                   false,
                                   {},
                                   e.schema});
    }
  }
  for (const DerivedAttribute& attribute : e.derived_attributes)
    if (attribute.redeclares) apply_derived_redeclaration(e, attribute);
  for (const InverseAttribute& attribute : e.inverse_attributes)
    if (attribute.redeclares) check_inverse_redeclaration(e, attribute);
}

const Entity* Linker::redeclared_supertype(const Entity& e, const QualifiedAttribute& qualified) {
  const auto ref = lookup(e.schema, qualified.entity);
  if (!ref || ref->kind != DeclKind::Entity || !contains(e.ancestors, *ref)) {
    if (!ref && unknowable(e.schema, qualified.entity)) return nullptr;
    report(diag::Code::ExpUnknownRedeclared, qualified.pos,
           cat("ENTITY ", e.name, ": SELF\\", qualified.entity, ".", qualified.attribute, " names ",
               qualified.entity, ", which is not a supertype of ", e.name));
    return nullptr;
  }
  return &entity(*ref);
}

namespace {

// The position in `list` of the explicit attribute that `supertype` knows as `name`.
std::vector<FlatAttribute>::iterator find_inherited(std::vector<FlatAttribute>& list,
                                                    const Entity& supertype,
                                                    const std::string& name) {
  const auto known = std::find_if(supertype.attributes.begin(), supertype.attributes.end(),
                                  [&](const FlatAttribute& a) { return a.name == name; });
  if (known == supertype.attributes.end()) return list.end();
  return std::find_if(list.begin(), list.end(), [&](const FlatAttribute& a) {
    return a.owner == known->owner && a.declared_name == known->declared_name;
  });
}

}  // namespace

void Linker::apply_explicit_redeclaration(Entity& e, const ExplicitAttribute& attribute) {
  const QualifiedAttribute& qualified = *attribute.redeclares;
  const Entity* super = redeclared_supertype(e, qualified);
  if (super == nullptr) return;
  const auto target = find_inherited(e.attributes, *super, qualified.attribute);
  if (target == e.attributes.end()) {
    report(diag::Code::ExpUnknownRedeclared, qualified.pos,
           cat("ENTITY ", e.name, ": ", super->name, " has no explicit attribute ",
               qualified.attribute, " to redeclare"));
    return;
  }
  target->name = attribute.name;  // differs only with RENAMED
  target->type = attribute.type;
  target->optional = attribute.optional;
  target->redeclared_by = e.name;
  target->schema = e.schema;
}

void Linker::apply_derived_redeclaration(Entity& e, const DerivedAttribute& attribute) {
  const QualifiedAttribute& qualified = *attribute.redeclares;
  const Entity* super = redeclared_supertype(e, qualified);
  if (super == nullptr) return;
  const auto target = find_inherited(e.attributes, *super, qualified.attribute);
  if (target != e.attributes.end()) {
    // The value is computed from now on: an instance writes `*` at this position.
    target->name = attribute.name;
    target->type = attribute.type;
    target->derived_redeclared = true;
    target->redeclared_by = e.name;
    target->schema = e.schema;
    return;
  }
  // Re-deriving an attribute that a supertype already derives does not touch the P21 layout.
  const auto derives = [&](const Entity& candidate) {
    return std::any_of(candidate.derived_attributes.begin(), candidate.derived_attributes.end(),
                       [&](const DerivedAttribute& d) { return d.name == qualified.attribute; });
  };
  bool found = derives(*super);
  for (const DeclRef ancestor : super->ancestors) found = found || derives(entity(ancestor));
  if (!found)
    report(diag::Code::ExpUnknownRedeclared, qualified.pos,
           cat("ENTITY ", e.name, ": ", super->name, " has no attribute ", qualified.attribute,
               " to redeclare as DERIVE"));
}

void Linker::check_inverse_redeclaration(const Entity& e, const InverseAttribute& attribute) {
  const QualifiedAttribute& qualified = *attribute.redeclares;
  const Entity* super = redeclared_supertype(e, qualified);
  if (super == nullptr) return;
  const auto has_inverse = [&](const Entity& candidate) {
    return std::any_of(candidate.inverse_attributes.begin(), candidate.inverse_attributes.end(),
                       [&](const InverseAttribute& i) { return i.name == qualified.attribute; });
  };
  bool found = has_inverse(*super);
  for (const DeclRef ancestor : super->ancestors) found = found || has_inverse(entity(ancestor));
  if (!found)
    report(diag::Code::ExpUnknownRedeclared, qualified.pos,
           cat("ENTITY ", e.name, ": ", super->name, " has no INVERSE attribute ",
               qualified.attribute, " to redeclare"));
}

// The names an entity introduces itself (not redeclarations) share one namespace.
void Linker::check_local_attribute_names(const Entity& e) {
  std::unordered_set<std::string> names;
  const auto add = [&](const std::string& name, SourcePos pos) {
    if (!names.insert(name).second)
      report(diag::Code::ExpDuplicateAttribute, pos,
             cat("ENTITY ", e.name, " declares attribute ", name, " twice"));
  };
  for (const auto& a : e.explicit_attributes)
    if (!a.redeclares) add(a.name, a.pos);
  for (const auto& a : e.derived_attributes)
    if (!a.redeclares) add(a.name, a.pos);
  for (const auto& a : e.inverse_attributes)
    if (!a.redeclares) add(a.name, a.pos);
}

// ---------------------------------------------------------------------------------------------
// 4. References

void Linker::check_references() {
  for (std::uint32_t s = 0; s < set_.schemas_.size(); ++s) {
    const Schema& schema = set_.schemas_[s];
    for (const Constant& constant : schema.constants) check_type(s, constant.type);
    for (const TypeDecl& decl : schema.types) check_type_decl(decl);
    for (const Entity& e : schema.entities) check_entity_references(e);
  }
}

void Linker::check_type(std::uint32_t schema, const TypeSpec& type) {
  const TypeSpec* current = &type;
  // Aggregates nest through `element`; walk them with a loop rather than recursion.
  while (current != nullptr) {
    if (current->kind == TypeKind::Named) {
      const auto ref = lookup(schema, current->name);
      if (!ref) {
        if (!unknowable(schema, current->name))
          report(diag::Code::ExpUnknownType, current->pos,
                 cat("type or entity ", current->name, " is not declared"));
      } else if (ref->kind != DeclKind::Entity && ref->kind != DeclKind::Type) {
        report(diag::Code::ExpWrongKind, current->pos,
               cat(current->name, " is a ", kind_name(ref->kind), ", not a type or entity"));
      }
    }
    current = current->kind == TypeKind::Aggregate ? current->element.get() : nullptr;
  }
}

void Linker::check_type_decl(const TypeDecl& decl) {
  const std::uint32_t s = decl.schema;
  if (decl.underlying.kind == TypeKind::Select) {
    for (const NamedRef& item : decl.select.items) {
      const auto ref = lookup(s, item.name);
      if (!ref) {
        if (!unknowable(s, item.name))
          report(diag::Code::ExpUnknownType, item.pos,
                 cat("TYPE ", decl.name, ": SELECT item ", item.name, " is not declared"));
      } else if (ref->kind != DeclKind::Entity && ref->kind != DeclKind::Type) {
        report(
            diag::Code::ExpWrongKind, item.pos,
            cat("TYPE ", decl.name, ": SELECT item ", item.name, " is a ", kind_name(ref->kind)));
      }
    }
  }
  const std::optional<NamedRef>& base =
      decl.underlying.kind == TypeKind::Select ? decl.select.based_on : decl.enumeration.based_on;
  if (base) {
    const auto ref = lookup(s, base->name);
    if (!ref) {
      if (!unknowable(s, base->name))
        report(diag::Code::ExpUnknownType, base->pos,
               cat("TYPE ", decl.name, ": BASED_ON ", base->name, " is not declared"));
    } else if (ref->kind != DeclKind::Type ||
               set_.type(*ref).underlying.kind != decl.underlying.kind) {
      report(diag::Code::ExpWrongKind, base->pos,
             cat("TYPE ", decl.name, ": BASED_ON ", base->name, " is not a ",
                 decl.underlying.kind == TypeKind::Select ? "SELECT" : "ENUMERATION"));
    }
  }
  if (decl.underlying.kind != TypeKind::Select && decl.underlying.kind != TypeKind::Enumeration)
    check_type(s, decl.underlying);
}

void Linker::check_entity_references(const Entity& e) {
  const std::uint32_t s = e.schema;
  for (const auto& a : e.explicit_attributes) check_type(s, a.type);
  for (const auto& a : e.derived_attributes) check_type(s, a.type);
  if (e.subtype_constraint) check_supertype_expression(s, *e.subtype_constraint, 0);
  for (const InverseAttribute& inverse : e.inverse_attributes) {
    const auto ref = lookup(s, inverse.entity.name);
    if (!ref) {
      if (!unknowable(s, inverse.entity.name))
        report(diag::Code::ExpUnknownType, inverse.entity.pos,
               cat("ENTITY ", e.name, ": INVERSE ", inverse.name, " refers to ",
                   inverse.entity.name, ", which is not declared"));
      continue;
    }
    if (ref->kind != DeclKind::Entity) {
      report(diag::Code::ExpWrongKind, inverse.entity.pos,
             cat("ENTITY ", e.name, ": INVERSE ", inverse.name, " refers to ", inverse.entity.name,
                 ", which is not an ENTITY"));
      continue;
    }
    // The attribute may be explicit (the usual case) or derived in the referencing entity.
    const Entity& referencing = set_.entity(*ref);
    bool found = referencing.attribute(inverse.for_attribute) != nullptr;
    const auto derives = [&](const Entity& candidate) {
      return std::any_of(
          candidate.derived_attributes.begin(), candidate.derived_attributes.end(),
          [&](const DerivedAttribute& d) { return d.name == inverse.for_attribute; });
    };
    found = found || derives(referencing);
    for (const DeclRef ancestor : referencing.ancestors)
      found = found || derives(set_.entity(ancestor));
    if (!found)
      report(diag::Code::ExpUnknownInverse, inverse.pos,
             cat("ENTITY ", e.name, ": INVERSE ", inverse.name, " is FOR ", inverse.for_attribute,
                 ", which ", referencing.name, " does not have"));
  }
}

void Linker::check_supertype_expression(std::uint32_t schema, const SupertypeExpression& expression,
                                        std::uint32_t depth) {
  // The parser bounded the depth of this tree; the guard keeps the invariant local.
  if (depth > 4096) return;
  if (expression.op != SupertypeExpression::Op::Entity) {
    for (const auto& operand : expression.operands)
      check_supertype_expression(schema, operand, depth + 1);
    return;
  }
  const NamedRef& name = expression.entity;
  const auto ref = lookup(schema, name.name);
  if (ref && ref->kind == DeclKind::Entity) return;
  if (!ref && unknowable(schema, name.name)) return;
  report(diag::Code::ExpUnknownSubtype, name.pos,
         cat("SUPERTYPE OF names ", name.name, ", which is not a declared ENTITY"));
}

void Linker::check_type_cycles() {
  // Colour marks over all types: following each chain of defined types once keeps this linear.
  std::vector<std::size_t> offset(set_.schemas_.size() + 1, 0);
  for (std::size_t s = 0; s < set_.schemas_.size(); ++s)
    offset[s + 1] = offset[s] + set_.schemas_[s].types.size();
  enum : std::uint8_t { kNew, kOnPath, kDone };
  std::vector<std::uint8_t> mark(offset.back(), kNew);
  std::vector<std::size_t> path;
  for (std::uint32_t s = 0; s < set_.schemas_.size(); ++s) {
    for (std::uint32_t i = 0; i < set_.schemas_[s].types.size(); ++i) {
      DeclRef ref{DeclKind::Type, s, i};
      while (mark[offset[ref.schema] + ref.index] == kNew) {
        mark[offset[ref.schema] + ref.index] = kOnPath;
        path.push_back(offset[ref.schema] + ref.index);
        const TypeDecl& decl = set_.type(ref);
        if (decl.underlying.kind != TypeKind::Named) break;
        const auto next = lookup(decl.schema, decl.underlying.name);
        if (!next || next->kind != DeclKind::Type) break;
        if (mark[offset[next->schema] + next->index] == kOnPath) {
          const TypeDecl& closing = set_.type(*next);
          report(diag::Code::ExpTypeCycle, closing.pos,
                 cat("TYPE ", closing.name, " is defined in terms of itself"));
          break;
        }
        ref = *next;
      }
      for (const std::size_t visited : path) mark[visited] = kDone;
      path.clear();
    }
  }
}

}  // namespace ncpost::express::detail
