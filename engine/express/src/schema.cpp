// Queries on the schema model: lookups by name, subtype tests, defined-type and SELECT closure.

#include "ncpost/express/schema.hpp"

#include <algorithm>

#include "lexer.hpp"

namespace ncpost::express {

using detail::to_lower;

// ---------------------------------------------------------------------------------------------
// Entity and Schema

const FlatAttribute* Entity::attribute(std::string_view wanted_name) const {
  const auto index = attribute_index(wanted_name);
  return index ? &attributes[*index] : nullptr;
}

std::optional<std::size_t> Entity::attribute_index(std::string_view wanted_name) const {
  // Called per attribute read by the interpreter: compare without allocating. Stored names are
  // lower case already.
  const auto same = [&](const std::string& stored) {
    if (stored.size() != wanted_name.size()) return false;
    for (std::size_t i = 0; i < stored.size(); ++i) {
      char c = wanted_name[i];
      if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
      if (c != stored[i]) return false;
    }
    return true;
  };
  for (std::size_t i = 0; i < attributes.size(); ++i)
    if (same(attributes[i].name)) return i;
  return std::nullopt;
}

namespace {

// A name in lower case, for a look-up: on the stack unless it is longer than any name the
// real schemas use.
class LowerName {
 public:
  explicit LowerName(std::string_view name) {
    if (name.size() > sizeof short_) {
      long_ = to_lower(name);
      view_ = long_;
      return;
    }
    for (std::size_t i = 0; i < name.size(); ++i) {
      const char c = name[i];
      short_[i] = (c >= 'A' && c <= 'Z') ? static_cast<char>(c - 'A' + 'a') : c;
    }
    view_ = std::string_view(short_, name.size());
  }
  LowerName(const LowerName&) = delete;
  LowerName& operator=(const LowerName&) = delete;
  [[nodiscard]] std::string_view view() const noexcept { return view_; }

 private:
  char short_[96];
  std::string long_;
  std::string_view view_;
};

}  // namespace

const Entity* Schema::find_entity(std::string_view entity_name) const {
  const auto it = declarations.find(LowerName(entity_name).view());
  if (it == declarations.end() || it->second.kind != DeclKind::Entity) return nullptr;
  return &entities[it->second.index];
}

const TypeDecl* Schema::find_type(std::string_view type_name) const {
  const auto it = declarations.find(LowerName(type_name).view());
  if (it == declarations.end() || it->second.kind != DeclKind::Type) return nullptr;
  return &types[it->second.index];
}

// ---------------------------------------------------------------------------------------------
// SchemaSet

const Schema* SchemaSet::find_schema(std::string_view name) const {
  const std::string wanted = to_lower(name);
  for (const Schema& schema : schemas_)
    if (schema.name == wanted) return &schema;
  return nullptr;
}

const Entity* SchemaSet::find_entity(std::string_view name) const {
  for (const Schema& schema : schemas_)
    if (const Entity* e = schema.find_entity(name)) return e;
  return nullptr;
}

const TypeDecl* SchemaSet::find_type(std::string_view name) const {
  for (const Schema& schema : schemas_)
    if (const TypeDecl* t = schema.find_type(name)) return t;
  return nullptr;
}

std::optional<DeclRef> SchemaSet::resolve(std::uint32_t schema, std::string_view name) const {
  if (schema >= visible_.size()) return std::nullopt;
  const auto it = visible_[schema].find(LowerName(name).view());
  if (it == visible_[schema].end()) return std::nullopt;
  return it->second;
}

const Entity& SchemaSet::entity(DeclRef ref) const {
  return schemas_[ref.schema].entities[ref.index];
}

const TypeDecl& SchemaSet::type(DeclRef ref) const {
  return schemas_[ref.schema].types[ref.index];
}

std::string_view SchemaSet::name_of(DeclRef ref) const {
  const Schema& schema = schemas_[ref.schema];
  switch (ref.kind) {
    case DeclKind::Entity:
      return schema.entities[ref.index].name;
    case DeclKind::Type:
      return schema.types[ref.index].name;
    case DeclKind::Constant:
      return schema.constants[ref.index].name;
    default:
      return schema.algorithms[ref.index].name;
  }
}

bool SchemaSet::is_subtype_of(const Entity& e, const Entity& ancestor) const {
  if (&e == &ancestor) return true;
  return std::any_of(e.ancestors.begin(), e.ancestors.end(),
                     [&](DeclRef ref) { return &entity(ref) == &ancestor; });
}

bool SchemaSet::is_subtype_of(std::string_view e, std::string_view ancestor) const {
  const Entity* sub = find_entity(e);
  const Entity* super = find_entity(ancestor);
  return sub != nullptr && super != nullptr && is_subtype_of(*sub, *super);
}

const TypeSpec& SchemaSet::underlying_type(const TypeDecl& decl) const {
  return underlying_type(decl.schema, decl.underlying);
}

const TypeSpec& SchemaSet::underlying_type(std::uint32_t schema, const TypeSpec& type) const {
  const TypeSpec* current = &type;
  std::size_t type_count = 0;
  for (const Schema& s : schemas_) type_count += s.types.size();
  // Cycles were reported by the linker; the step bound makes this terminate on them anyway.
  for (std::size_t steps = 0; steps <= type_count && current->kind == TypeKind::Named; ++steps) {
    const auto ref = resolve(schema, current->name);
    if (!ref || ref->kind != DeclKind::Type) break;
    const TypeDecl& next = this->type(*ref);
    current = &next.underlying;
    schema = next.schema;
  }
  return *current;
}

namespace {

// Defined types whose BASED_ON names `base` (as resolved in their own schema).
std::vector<DeclRef> extensions_of(const SchemaSet& set, DeclRef base) {
  std::vector<DeclRef> found;
  const auto& schemas = set.schemas();
  for (std::uint32_t s = 0; s < schemas.size(); ++s) {
    for (std::uint32_t i = 0; i < schemas[s].types.size(); ++i) {
      const TypeDecl& t = schemas[s].types[i];
      const auto& based_on =
          t.underlying.kind == TypeKind::Select ? t.select.based_on : t.enumeration.based_on;
      if (!based_on) continue;
      const auto ref = set.resolve(s, based_on->name);
      if (ref && *ref == base) found.push_back(DeclRef{DeclKind::Type, s, i});
    }
  }
  return found;
}

std::optional<DeclRef> ref_of(const SchemaSet& set, const TypeDecl& decl) {
  return set.resolve(decl.schema, decl.name);
}

// The SELECT or ENUMERATION family of `start`: itself, what it is based on, and what is based on
// it, transitively. Worklist with a visited list, so extension cycles terminate.
std::vector<DeclRef> extension_family(const SchemaSet& set, DeclRef start) {
  std::vector<DeclRef> family{start};
  for (std::size_t next = 0; next < family.size(); ++next) {
    const TypeDecl& t = set.type(family[next]);
    std::vector<DeclRef> related = extensions_of(set, family[next]);
    const auto& based_on =
        t.underlying.kind == TypeKind::Select ? t.select.based_on : t.enumeration.based_on;
    if (based_on) {
      const auto base = set.resolve(t.schema, based_on->name);
      if (base && base->kind == DeclKind::Type) related.push_back(*base);
    }
    for (const DeclRef r : related)
      if (std::find(family.begin(), family.end(), r) == family.end()) family.push_back(r);
  }
  return family;
}

}  // namespace

std::vector<DeclRef> SchemaSet::select_leaves(const TypeDecl& select) const {
  std::vector<DeclRef> leaves;
  if (select.underlying.kind != TypeKind::Select) return leaves;
  const auto start = ref_of(*this, select);
  if (!start) return leaves;
  // Worklist over SELECT types; `seen` holds every SELECT already expanded.
  std::vector<DeclRef> pending{*start};
  std::vector<DeclRef> seen;
  while (!pending.empty()) {
    const DeclRef current = pending.back();
    pending.pop_back();
    if (std::find(seen.begin(), seen.end(), current) != seen.end()) continue;
    for (const DeclRef member : extension_family(*this, current)) {
      if (std::find(seen.begin(), seen.end(), member) != seen.end()) continue;
      seen.push_back(member);
      const TypeDecl& decl = type(member);
      for (const NamedRef& item : decl.select.items) {
        const auto ref = resolve(decl.schema, item.name);
        if (!ref) continue;
        if (ref->kind == DeclKind::Type && type(*ref).underlying.kind == TypeKind::Select) {
          pending.push_back(*ref);
        } else if (std::find(leaves.begin(), leaves.end(), *ref) == leaves.end()) {
          leaves.push_back(*ref);
        }
      }
    }
  }
  return leaves;
}

std::vector<std::string> SchemaSet::enumeration_items(const TypeDecl& enumeration) const {
  std::vector<std::string> items;
  if (enumeration.underlying.kind != TypeKind::Enumeration) return items;
  const auto start = ref_of(*this, enumeration);
  if (!start) return items;
  std::vector<DeclRef> family = extension_family(*this, *start);
  // Declaration order: the base first, then the extensions.
  std::stable_sort(family.begin(), family.end(), [](DeclRef a, DeclRef b) {
    return a.schema != b.schema ? a.schema < b.schema : a.index < b.index;
  });
  for (const DeclRef member : family)
    for (const std::string& item : type(member).enumeration.items)
      if (std::find(items.begin(), items.end(), item) == items.end()) items.push_back(item);
  return items;
}

}  // namespace ncpost::express
