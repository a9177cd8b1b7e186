#include "binding.hpp"

#include <cctype>

namespace ncpost::p28::detail {

using express::TypeKind;
using Kind = TypePlan::Kind;

// Defined types can refer to defined types; a cycle would be a schema error, so the chain is
// followed to a fixed depth only.
constexpr int kMaxTypeDepth = 32;

std::string lower(std::string_view s) {
  std::string out(s);
  for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

std::string upper(std::string_view s) {
  std::string out(s);
  for (char& c : out) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return out;
}

std::string positional_name(std::size_t index) {
  return "attr_" + std::to_string(index + 1);
}

Binding::Binding(const express::SchemaSet* schemas) : schemas_(schemas) {}

const TypePlan* Binding::plan_named(std::string_view name, int depth) {
  const std::string key = lower(name);
  if (auto it = by_name_.find(key); it != by_name_.end()) return it->second;
  if (schemas_ == nullptr || depth > kMaxTypeDepth) return &unknown_;
  TypePlan& p = types_.emplace_back();
  p.name = key;
  by_name_.emplace(key, &p);  // before recursing, so a self-reference ends here
  if (const express::TypeDecl* decl = schemas_->find_type(key)) {
    switch (decl->underlying.kind) {
      case TypeKind::Select:
        p.kind = Kind::Select;
        break;
      case TypeKind::Enumeration:
        p.kind = Kind::Enumeration;
        break;
      default:
        p.kind = Kind::Defined;
        p.underlying = plan(decl->underlying, depth + 1);
        break;
    }
  } else if (schemas_->find_entity(key) != nullptr) {
    p.kind = Kind::Entity;
  } else {
    p.kind = Kind::Unknown;
  }
  return &p;
}

const TypePlan* Binding::plan(const express::TypeSpec& spec, int depth) {
  if (auto it = by_spec_.find(&spec); it != by_spec_.end()) return it->second;
  const TypePlan* result = &unknown_;
  switch (spec.kind) {
    case TypeKind::Integer: {
      TypePlan& p = types_.emplace_back();
      p.kind = Kind::Integer;
      result = &p;
      break;
    }
    case TypeKind::Real:
    case TypeKind::Number: {
      TypePlan& p = types_.emplace_back();
      p.kind = Kind::Real;
      result = &p;
      break;
    }
    case TypeKind::String: {
      TypePlan& p = types_.emplace_back();
      p.kind = Kind::String;
      result = &p;
      break;
    }
    case TypeKind::Binary: {
      TypePlan& p = types_.emplace_back();
      p.kind = Kind::Binary;
      result = &p;
      break;
    }
    case TypeKind::Boolean: {
      TypePlan& p = types_.emplace_back();
      p.kind = Kind::Boolean;
      result = &p;
      break;
    }
    case TypeKind::Logical: {
      TypePlan& p = types_.emplace_back();
      p.kind = Kind::Logical;
      result = &p;
      break;
    }
    case TypeKind::Named:
      result = plan_named(spec.name, depth);
      break;
    case TypeKind::Aggregate: {
      TypePlan& p = types_.emplace_back();
      p.kind = Kind::Aggregate;
      p.aggregate = spec.aggregate;
      p.element =
          spec.element && depth < kMaxTypeDepth ? plan(*spec.element, depth + 1) : &unknown_;
      result = &p;
      break;
    }
    default:
      break;
  }
  by_spec_.emplace(&spec, result);
  return result;
}

const TypePlan* Binding::named_type(std::string_view name) {
  return plan_named(name, 0);
}

const EntityPlan& Binding::entity(std::string_view name, std::size_t min_attributes) {
  std::string key = lower(name);
  auto it = entities_.find(key);
  if (it == entities_.end()) {
    EntityPlan plan;
    plan.name = key;
    if (const express::Entity* e = schemas_ ? schemas_->find_entity(key) : nullptr) {
      plan.known = true;
      for (const auto& a : e->attributes) {
        AttributePlan ap;
        ap.name = a.name;
        ap.inherited = a.owner != e->name;
        ap.derived = a.derived_redeclared;
        ap.type = this->plan(a.type, 0);
        plan.index_of.emplace(ap.name, plan.attributes.size());
        plan.attributes.push_back(std::move(ap));
      }
    }
    it = entities_.emplace(std::move(key), std::move(plan)).first;
  }
  EntityPlan& plan = it->second;
  // Unknown entities (and instances with more parameters than the schema says) get positional
  // names for the extra positions, so nothing is ever dropped.
  while (plan.attributes.size() < min_attributes) {
    AttributePlan ap;
    ap.name = positional_name(plan.attributes.size());
    ap.type = &unknown_;
    plan.index_of.emplace(ap.name, plan.attributes.size());
    plan.attributes.push_back(std::move(ap));
  }
  return plan;
}

}  // namespace ncpost::p28::detail
