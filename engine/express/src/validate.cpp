// Model validation against a schema: one pass over the instances, with the schema's types,
// SELECT closures and enumeration items resolved once per declaration (see validate.hpp).

#include "ncpost/express/validate.hpp"

#include <algorithm>
#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <unordered_map>
#include <utility>
#include <vector>

#include "lexer.hpp"
#include "ncpost/p21/reader.hpp"

namespace ncpost::express {
namespace {

using p21::Instance;
using p21::Model;
using p21::Value;
using p21::ValueKind;

// Values nest at most as deep as the reader allows (ReadOptions::max_list_depth, 64 by default;
// typed parameters count as a level), and the checks recurse once per level. This bound keeps
// the recursion shallow even for a Model built with a larger reader limit.
constexpr unsigned kMaxValueDepth = 256;

// Deviations that the tolerant check (ValidateOptions::tolerant) reports as one warning per
// entity and attribute: what the interpreter and the feature generators read, they check again
// where they read it, and they report an error there when they cannot do without the value.
bool tolerated(diag::Code code) {
  return code == diag::Code::ExpRequiredOmitted || code == diag::Code::ExpAbstractInstance ||
         code == diag::Code::ExpReferenceType;
}

// One warning standing for every instance with the same deviation of the same entity's
// attribute: the first instance's diagnostic and how many there were.
struct Tolerated {
  std::string key;      // code, entity as written, attribute
  std::string subject;  // "#3 PERSON.id"
  diag::Diagnostic first;
  std::size_t count = 0;
};

void add_tolerated(std::vector<Tolerated>& into,
                   std::unordered_map<std::string, std::size_t>& index, Tolerated found) {
  const auto [at, fresh] = index.try_emplace(found.key, into.size());
  if (fresh)
    into.push_back(std::move(found));
  else
    into[at->second].count += found.count;
}

diag::Diagnostic tolerated_warning(const Tolerated& t) {
  diag::Diagnostic d = t.first;
  d.severity = diag::Severity::Warning;
  std::string message;
  if (t.count > 1) message = "\u00d7" + std::to_string(t.count) + ", first ";
  message += t.subject + ": " + d.message +
             " (tolerated; an error follows where machining needs the value; --strict reports "
             "each instance as an error)";
  d.message = std::move(message);
  return d;
}

bool equals_ignoring_case(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    char x = a[i];
    char y = b[i];
    if (x >= 'A' && x <= 'Z') x = static_cast<char>(x - 'A' + 'a');
    if (y >= 'A' && y <= 'Z') y = static_cast<char>(y - 'A' + 'a');
    if (x != y) return false;
  }
  return true;
}

// What a declared type comes down to once defined types are followed.
enum class Shape : std::uint8_t {
  Any,  // not checked: generic types, names that do not resolve
  Integer,
  Real,
  Number,
  String,
  Binary,
  Boolean,
  Logical,
  Entity,
  Select,
  Enumeration,
  Aggregate,
};

struct Resolved {
  Shape shape = Shape::Any;
  const TypeSpec* spec = nullptr;       // Aggregate: the aggregate type (bounds, element)
  std::uint32_t schema = 0;             // the schema in which spec's element type is resolved
  const Entity* entity = nullptr;       // Entity
  const TypeDecl* decl = nullptr;       // Select, Enumeration
  std::vector<std::string_view> names;  // the defined types passed through, outermost first
};

struct SelectInfo {
  std::vector<const Entity*> entities;  // entity leaves
  std::vector<const TypeDecl*> types;   // defined-type leaves (written as TYPE_NAME(value))
  bool any_entity = false;              // EXTENSIBLE GENERIC_ENTITY SELECT
  std::string members;                  // for messages
};

// One attribute as an instance (or a partial record) holds it.
struct AttributeView {
  std::string_view name;
  const TypeSpec* type = nullptr;
  std::uint32_t schema = 0;  // where `type` is resolved
  bool optional = false;
  bool derived = false;
  std::string_view derived_by;
};

// Where a value is, for messages, and what bounds that name attributes are evaluated against.
struct Where {
  const Instance* instance = nullptr;
  std::string_view entity;           // as written in the file
  std::string_view declared_entity;  // the schema's name of the instance's (record's) entity
  bool partial_record = false;
  std::string_view attribute;
  std::vector<std::uint32_t> path;  // 1-based element numbers, outermost first
  const Entity* owner = nullptr;    // simple instances: the instance's entity
  std::span<const Value> params;    // and its parameters
};

// What the schema set says about its types, learnt as they are asked for: what a declared type
// stands for, the members of a SELECT, the items of an ENUMERATION. A check learns them for the
// types its model uses; a CheckPlan learns them for every type once, and is then read by any
// number of checks at once.
class TypeFacts {
 public:
  explicit TypeFacts(const SchemaSet& set) : set_(set) {
    for (const Schema& schema : set.schemas()) type_count_ += schema.types.size();
  }

  // Follows defined types from `spec` (resolved in schema number `schema`) to what they stand
  // for. `decl` is the TYPE whose underlying type `spec` is, if it is one (needed when `spec` is
  // the SELECT or ENUMERATION itself). Loops, bounded by the number of types: cycles were
  // reported by the parser and must not hang this.
  const Resolved& resolve(const TypeSpec& spec, std::uint32_t schema,
                          const TypeDecl* decl = nullptr) {
    const auto cached = resolved_.find(&spec);
    if (cached != resolved_.end()) return cached->second;
    Resolved r;
    const TypeSpec* current = &spec;
    for (std::size_t steps = 0; steps <= type_count_ + 1; ++steps) {
      switch (current->kind) {
        case TypeKind::Integer:
          r.shape = Shape::Integer;
          break;
        case TypeKind::Real:
          r.shape = Shape::Real;
          break;
        case TypeKind::Number:
          r.shape = Shape::Number;
          break;
        case TypeKind::String:
          r.shape = Shape::String;
          break;
        case TypeKind::Binary:
          r.shape = Shape::Binary;
          break;
        case TypeKind::Boolean:
          r.shape = Shape::Boolean;
          break;
        case TypeKind::Logical:
          r.shape = Shape::Logical;
          break;
        case TypeKind::Aggregate:
          r.shape = current->element ? Shape::Aggregate : Shape::Any;
          r.spec = current;
          r.schema = schema;
          break;
        case TypeKind::Select:
        case TypeKind::Enumeration:
          if (decl != nullptr) {
            r.shape = current->kind == TypeKind::Select ? Shape::Select : Shape::Enumeration;
            r.decl = decl;
          }
          break;
        case TypeKind::Named: {
          std::optional<DeclRef> ref = set_.resolve(schema, current->name);
          if (!ref) {  // the parser reported it; try any schema of the set
            if (const Entity* e = set_.find_entity(current->name))
              ref = set_.resolve(e->schema, e->name);
            else if (const TypeDecl* t = set_.find_type(current->name))
              ref = set_.resolve(t->schema, t->name);
          }
          if (!ref) break;
          if (ref->kind == DeclKind::Entity) {
            r.shape = Shape::Entity;
            r.entity = &set_.entity(*ref);
            break;
          }
          if (ref->kind != DeclKind::Type) break;
          decl = &set_.type(*ref);
          r.names.push_back(decl->name);
          current = &decl->underlying;
          schema = decl->schema;
          continue;  // follow the defined type
        }
        default:  // GENERIC, GENERIC_ENTITY
          break;
      }
      break;
    }
    return resolved_.emplace(&spec, std::move(r)).first->second;
  }

  const SelectInfo& select_info(const TypeDecl& select) {
    const auto cached = selects_.find(&select);
    if (cached != selects_.end()) return cached->second;
    SelectInfo info;
    info.any_entity = select.select.generic_entity;
    for (const DeclRef leaf : set_.select_leaves(select)) {
      if (leaf.kind == DeclKind::Entity)
        info.entities.push_back(&set_.entity(leaf));
      else if (leaf.kind == DeclKind::Type)
        info.types.push_back(&set_.type(leaf));
      else
        continue;
      if (!info.members.empty()) info.members += ", ";
      info.members += set_.name_of(leaf);
    }
    return selects_.emplace(&select, std::move(info)).first->second;
  }

  const std::vector<std::string>& enumeration_items(const TypeDecl& enumeration) {
    const auto cached = enumerations_.find(&enumeration);
    if (cached != enumerations_.end()) return cached->second;
    return enumerations_.emplace(&enumeration, set_.enumeration_items(enumeration)).first->second;
  }

  // Read only: what has been learnt already, or null.
  [[nodiscard]] const Resolved* known(const TypeSpec& spec) const {
    const auto found = resolved_.find(&spec);
    return found != resolved_.end() ? &found->second : nullptr;
  }
  [[nodiscard]] const SelectInfo* known_select(const TypeDecl& select) const {
    const auto found = selects_.find(&select);
    return found != selects_.end() ? &found->second : nullptr;
  }
  [[nodiscard]] const std::vector<std::string>* known_enumeration(const TypeDecl& decl) const {
    const auto found = enumerations_.find(&decl);
    return found != enumerations_.end() ? &found->second : nullptr;
  }

 private:
  const SchemaSet& set_;
  std::size_t type_count_ = 0;
  std::unordered_map<const TypeSpec*, Resolved> resolved_;
  std::unordered_map<const TypeDecl*, SelectInfo> selects_;
  std::unordered_map<const TypeDecl*, std::vector<std::string>> enumerations_;
};

}  // namespace

// Every type of the set learnt in advance, in the ways a check asks for it: each flattened
// attribute's type (in the schema of its declaring entity), each defined type's underlying type
// (with the declaration), the elements of aggregates, every SELECT and ENUMERATION.
class CheckPlan::Impl {
 public:
  explicit Impl(const SchemaSet& set) : set_(set), facts_(set) {
    for (const Schema& schema : set.schemas()) {
      for (const Entity& entity : schema.entities)
        for (const FlatAttribute& attribute : entity.attributes)
          learn(attribute.type, attribute.schema, nullptr);
      for (const TypeDecl& type : schema.types) {
        learn(type.underlying, type.schema, &type);
        if (type.underlying.kind == TypeKind::Select) (void)facts_.select_info(type);
        if (type.underlying.kind == TypeKind::Enumeration) (void)facts_.enumeration_items(type);
      }
    }
  }
  [[nodiscard]] const SchemaSet& set() const noexcept { return set_; }
  [[nodiscard]] const TypeFacts& facts() const noexcept { return facts_; }

 private:
  // Aggregates of aggregates nest as deep as the schema writes them; the loop, not recursion,
  // keeps a hostile schema from overflowing the stack.
  void learn(const TypeSpec& spec, std::uint32_t schema, const TypeDecl* decl) {
    const TypeSpec* current = &spec;
    for (std::size_t depth = 0; current != nullptr && depth <= kMaxValueDepth; ++depth) {
      const Resolved& r = facts_.resolve(*current, schema, decl);
      if (r.shape != Shape::Aggregate || !r.spec->element) return;
      current = r.spec->element.get();
      schema = r.schema;
      decl = nullptr;
    }
  }

  const SchemaSet& set_;
  TypeFacts facts_;
};

namespace {

class Validator {
 public:
  Validator(const Model& model, const SchemaSet& set, const ValidateOptions& options)
      : model_(model),
        set_(set),
        options_(options),
        entities_(model.keyword_count()),
        shared_(options.plan != nullptr && &options.plan->set() == &set
                    ? &options.plan->impl().facts()
                    : nullptr),
        own_(set) {}

  // What checking some of the instances found, to be merged with what the other pieces of a
  // parallel check found (merge()).
  struct Found {
    std::vector<diag::Diagnostic> diagnostics;
    // The EXP-060s, given once per entity name: which diagnostic, for which keyword.
    std::vector<std::pair<std::size_t, p21::KeywordId>> unknown_entities;
    // Tolerant check: the tolerated deviations, in the order first found.
    std::vector<Tolerated> tolerated;
    bool stopped = false;  // more than max_diagnostics
  };

  Found check(std::span<const Instance> instances) {
    constexpr std::size_t kCancelPollInstances = 4096;
    std::size_t until_poll = kCancelPollInstances;
    for (const Instance& instance : instances) {
      if (muted()) break;
      if (--until_poll == 0) {
        until_poll = kCancelPollInstances;
        if (options_.cancel != nullptr && options_.cancel->load(std::memory_order_relaxed)) break;
      }
      if (instance.keyword == Model::kExternalKeyword) continue;
      if (model_.is_complex(instance))
        check_complex(instance);
      else
        check_simple(instance);
    }
    return {std::move(diagnostics_), std::move(unknown_entities_), std::move(tolerated_), stopped_};
  }

 private:
  struct EntityInfo {
    bool looked_up = false;
    bool reported = false;  // EXP-060 given for this keyword
    const Entity* entity = nullptr;
  };

  // ---- reporting ----------------------------------------------------------------------------

  // Tolerant, the check goes on past the limit to count the tolerated deviations of the whole
  // file, so that a check in pieces counts what a check in order counts.
  [[nodiscard]] bool muted() const { return stopped_ && !options_.tolerant; }

  // One Where per instance, its path's storage kept: a fresh vector per instance was a
  // malloc/free pair for most of them.
  Where& fresh_where() {
    std::vector<std::uint32_t> path = std::move(where_.path);
    path.clear();
    where_ = Where{};
    where_.path = std::move(path);
    return where_;
  }

  void add(diag::Code code, const Instance& at, std::string message) {
    if (stopped_) return;
    if (diagnostics_.size() >= options_.max_diagnostics) {
      stopped_ = true;
      return;
    }
    if (!lines_) lines_.emplace(model_.text());
    const auto pos = lines_->at(at.offset);
    diagnostics_.push_back(diag::make(code, pos.line, pos.column, std::move(message)));
  }

  static std::string instance_name(const Instance& instance, std::string_view entity,
                                   bool partial_record) {
    std::string out = "#" + std::to_string(instance.id) + " ";
    if (partial_record) out += "partial record ";
    out += entity;
    return out;
  }

  // A tolerated deviation: counted under its entity and attribute (`attribute` empty for the
  // entity itself); only the first instance's message is kept.
  void tolerate(diag::Code code, const Instance& at, std::string_view entity,
                std::string_view attribute, std::string detail) {
    Tolerated t;
    t.key =
        std::string(diag::info(code).id) + " " + std::string(entity) + "." + std::string(attribute);
    t.count = 1;
    const auto fresh = tolerated_index_.find(t.key) == tolerated_index_.end();
    if (fresh) {
      t.subject = "#" + std::to_string(at.id) + " " + std::string(entity);
      if (!attribute.empty()) t.subject += "." + std::string(attribute);
      if (!lines_) lines_.emplace(model_.text());
      const auto pos = lines_->at(at.offset);
      t.first = diag::make(code, pos.line, pos.column, std::move(detail));
    }
    add_tolerated(tolerated_, tolerated_index_, std::move(t));
  }

  void report(diag::Code code, const Where& w, const std::string& detail) {
    if (options_.tolerant && tolerated(code)) {
      std::string what = detail;
      if (!w.path.empty()) {
        what = "element";
        for (std::size_t i = 0; i < w.path.size(); ++i)
          what += (i == 0 ? " " : ".") + std::to_string(w.path[i]);
        what += ": " + detail;
      }
      tolerate(code, *w.instance, w.entity, w.attribute, std::move(what));
      return;
    }
    if (stopped_) return;
    std::string message = instance_name(*w.instance, w.entity, w.partial_record);
    message += " attribute '";
    message += w.attribute;
    message += "'";
    for (std::size_t i = 0; i < w.path.size(); ++i)
      message += (i == 0 ? " element " : ".") + std::to_string(w.path[i]);
    message += ": ";
    message += detail;
    add(code, *w.instance, std::move(message));
  }

  std::string describe(Value v) const {
    const auto quoted = [&](std::string_view text) {
      std::string out(text.substr(0, text.size() > 40 ? 37 : text.size()));
      if (text.size() > 40) out += "...";
      return out;
    };
    switch (v.kind()) {
      case ValueKind::Omitted:
        return "'$'";
      case ValueKind::Derived:
        return "'*'";
      case ValueKind::Integer:
        return "the integer " + quoted(model_.slice(v));
      case ValueKind::Real:
        return "the real " + quoted(model_.slice(v));
      case ValueKind::String:
        return "the string '" + quoted(model_.slice(v)) + "'";
      case ValueKind::Enumeration:
        return "the enumeration value ." + quoted(model_.slice(v)) + ".";
      case ValueKind::Binary:
        return "a binary";
      case ValueKind::Reference: {
        std::string out = "#" + std::to_string(v.id());
        if (const Instance* target = model_.find(v.id()); target && !model_.is_complex(*target))
          out += " (" + std::string(model_.type_name(*target)) + ")";
        return out;
      }
      case ValueKind::List:
        return "a list of " + std::to_string(v.count()) + " element" + (v.count() == 1 ? "" : "s");
      case ValueKind::Typed:
        return "the typed value " + std::string(model_.keyword(v.keyword_id())) + "(...)";
      default:
        return "an ed.3 constant, value instance or resource";
    }
  }

  static std::string shape_text(const Resolved& r) {
    switch (r.shape) {
      case Shape::Integer:
        return "INTEGER";
      case Shape::Real:
        return "REAL";
      case Shape::Number:
        return "NUMBER";
      case Shape::String:
        return "STRING";
      case Shape::Binary:
        return "BINARY";
      case Shape::Boolean:
        return "BOOLEAN";
      case Shape::Logical:
        return "LOGICAL";
      case Shape::Entity:
        return "a reference to " + r.entity->name;
      case Shape::Select:
        return "SELECT";
      case Shape::Enumeration:
        return "ENUMERATION";
      case Shape::Aggregate:
        return to_express(*r.spec);
      case Shape::Any:
        break;
    }
    return "any value";
  }

  // "length_measure (REAL)", "INTEGER", "a reference to cartesian_point".
  static std::string expected_text(const TypeSpec& declared, const Resolved& r) {
    const std::string written = to_express(declared);
    const std::string base = shape_text(r);
    if (r.shape == Shape::Entity) return base;
    if (equals_ignoring_case(written, base)) return base;
    return written + " (" + base + ")";
  }

  void wrong_kind(const Where& w, const TypeSpec& declared, const Resolved& r, Value v) {
    std::string detail = "expected " + expected_text(declared, r) + ", found " + describe(v);
    if (r.shape == Shape::Select && v.kind() != ValueKind::Reference &&
        v.kind() != ValueKind::Typed)
      detail += " (a SELECT value that is not an entity is written as TYPE_NAME(value))";
    report(diag::Code::ExpValueKind, w, detail);
  }

  // ---- schema look-ups, cached --------------------------------------------------------------

  // Keyword ids are below model_.keyword_count(), the size of entities_, which never changes:
  // references into it stay valid for the whole pass.
  EntityInfo& entity_info(p21::KeywordId keyword) {
    if (keyword >= entities_.size()) return no_entity_;
    EntityInfo& info = entities_[keyword];
    if (!info.looked_up) {
      info.looked_up = true;
      info.entity = set_.find_entity(model_.keyword(keyword));
      if (info.entity == nullptr) {
        for (const NameAlias& alias : options_.entity_aliases)
          if (alias.written == detail::to_lower(model_.keyword(keyword)))
            info.entity = set_.find_entity(alias.read_as);
      }
    }
    return info;
  }

  // The schema's facts: from the plan when it has them, else learnt during this check.
  const Resolved& resolve(const TypeSpec& spec, std::uint32_t schema,
                          const TypeDecl* decl = nullptr) {
    if (shared_ != nullptr)
      if (const Resolved* known = shared_->known(spec)) return *known;
    return own_.resolve(spec, schema, decl);
  }
  const SelectInfo& select_info(const TypeDecl& select) {
    if (shared_ != nullptr)
      if (const SelectInfo* known = shared_->known_select(select)) return *known;
    return own_.select_info(select);
  }
  const std::vector<std::string>& enumeration_items(const TypeDecl& enumeration) {
    if (shared_ != nullptr)
      if (const auto* known = shared_->known_enumeration(enumeration)) return *known;
    return own_.enumeration_items(enumeration);
  }

  // Whether the instance `id` is an instance of an entity for which `fits` holds: for a complex
  // instance, of one of its partial records. nullopt when that cannot be told (a dangling
  // reference, which the reader reports, an ed.3 reference, or entities the schema lacks).
  template <typename Fits>
  std::optional<bool> instance_fits(std::uint64_t id, const Fits& fits) {
    const Instance* target = model_.find(id);
    if (target == nullptr || target->keyword == Model::kExternalKeyword) return std::nullopt;
    if (!model_.is_complex(*target)) {
      const Entity* e = entity_info(target->keyword).entity;
      if (e == nullptr) return std::nullopt;
      return fits(*e);
    }
    bool all_known = true;
    for (const Value record : model_.params(*target)) {
      if (record.kind() != ValueKind::Typed) continue;
      const Entity* e = entity_info(record.keyword_id()).entity;
      if (e == nullptr) {
        all_known = false;
        continue;
      }
      if (fits(*e)) return true;
    }
    if (!all_known) return std::nullopt;
    return false;
  }

  bool select_accepts(const TypeDecl& select, const SelectInfo& info, const Entity& e) {
    if (info.any_entity) return true;
    const auto key = std::make_pair(&select, &e);
    const auto cached = select_fits_.find(key);
    if (cached != select_fits_.end()) return cached->second;
    const bool fits = std::any_of(info.entities.begin(), info.entities.end(),
                                  [&](const Entity* leaf) { return set_.is_subtype_of(e, *leaf); });
    select_fits_.emplace(key, fits);
    return fits;
  }

  // ---- bounds -------------------------------------------------------------------------------

  // An integer bound, or one that names an INTEGER attribute of the instance itself
  // (`SELF\mesh.index_count`, `SELF.n`, `n`). Other expressions are not evaluated: nullopt.
  std::optional<std::int64_t> bound_value(const std::optional<Bound>& bound, const Where& w) const {
    if (!bound || bound->indeterminate()) return std::nullopt;
    if (bound->value) return bound->value;
    if (w.owner == nullptr) return std::nullopt;
    std::string_view text = bound->text;
    if (text.starts_with("SELF\\")) {
      const auto dot = text.find('.');
      if (dot == std::string_view::npos) return std::nullopt;
      text.remove_prefix(dot + 1);
    } else if (text.starts_with("SELF.")) {
      text.remove_prefix(5);
    }
    if (text.empty() || !std::all_of(text.begin(), text.end(), [](char c) {
          return (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_';
        }))
      return std::nullopt;
    const auto index = w.owner->attribute_index(text);
    if (!index || *index >= w.params.size()) return std::nullopt;
    const Value v = w.params[*index];
    if (v.kind() != ValueKind::Integer) return std::nullopt;
    return model_.as_integer(v);
  }

  // ---- values -------------------------------------------------------------------------------

  void check_attribute(Where& w, const AttributeView& a, Value v) {
    w.attribute = a.name;
    if (a.derived) {
      if (v.kind() != ValueKind::Derived)
        report(diag::Code::ExpDerivedHasValue, w,
               "found " + describe(v) + ", but " + std::string(a.derived_by) +
                   " re-declares the attribute as DERIVE: ISO 10303-21 writes '*' there");
      return;
    }
    if (v.kind() == ValueKind::Omitted) {
      if (!a.optional)
        report(diag::Code::ExpRequiredOmitted, w, "'$' but the attribute is not OPTIONAL");
      return;
    }
    if (v.kind() == ValueKind::Derived) {
      report(diag::Code::ExpUnexpectedDerived, w,
             "'*' but the attribute is not derived in " + std::string(w.declared_entity));
      return;
    }
    check_value(w, *a.type, a.schema, nullptr, v, 0);
  }

  void check_value(Where& w, const TypeSpec& declared, std::uint32_t schema, const TypeDecl* decl,
                   Value v, unsigned depth) {
    check_resolved(w, declared, resolve(declared, schema, decl), v, depth);
  }

  void check_resolved(Where& w, const TypeSpec& declared, const Resolved& r, Value v,
                      unsigned depth) {
    if (depth > kMaxValueDepth || r.shape == Shape::Any) return;
    switch (v.kind()) {
      case ValueKind::ConstantName:
      case ValueKind::ValueName:
      case ValueKind::Resource:
        return;  // ed.3: the value is elsewhere; not checked
      case ValueKind::Derived:
        report(diag::Code::ExpUnexpectedDerived, w, "'*' inside a value");
        return;
      case ValueKind::Integer:
        if (r.shape != Shape::Integer && r.shape != Shape::Real && r.shape != Shape::Number)
          wrong_kind(w, declared, r, v);
        return;
      case ValueKind::Real:
        if (r.shape != Shape::Real && r.shape != Shape::Number) wrong_kind(w, declared, r, v);
        return;
      case ValueKind::String:
        if (r.shape != Shape::String) wrong_kind(w, declared, r, v);
        return;
      case ValueKind::Binary:
        if (r.shape != Shape::Binary) wrong_kind(w, declared, r, v);
        return;
      case ValueKind::Enumeration:
        check_enumeration(w, declared, r, v);
        return;
      case ValueKind::Reference:
        check_reference(w, declared, r, v);
        return;
      case ValueKind::List:
        if (r.shape != Shape::Aggregate) {
          wrong_kind(w, declared, r, v);
          return;
        }
        check_aggregate(w, r, v, depth);
        return;
      case ValueKind::Typed:
        check_typed(w, declared, r, v, depth);
        return;
      case ValueKind::Omitted:
        wrong_kind(w, declared, r, v);  // `$` inside a typed value
        return;
    }
  }

  void check_enumeration(Where& w, const TypeSpec& declared, const Resolved& r, Value v) {
    const std::string_view item = model_.enumeration(v);
    const auto is = [&](std::string_view name) { return equals_ignoring_case(item, name); };
    switch (r.shape) {
      case Shape::Boolean:
        if (!is("T") && !is("F"))
          report(diag::Code::ExpEnumerationValue, w,
                 describe(v) + " is not a BOOLEAN (.T. or .F.)");
        return;
      case Shape::Logical:
        if (!is("T") && !is("F") && !is("U"))
          report(diag::Code::ExpEnumerationValue, w,
                 describe(v) + " is not a LOGICAL (.T., .F. or .U.)");
        return;
      case Shape::Enumeration: {
        const auto& items = enumeration_items(*r.decl);
        if (std::none_of(items.begin(), items.end(), is)) {
          std::string list;
          for (const auto& i : items) {
            if (!list.empty()) list += ", ";
            list += i;
          }
          report(diag::Code::ExpEnumerationValue, w,
                 describe(v) + " is not an item of " + r.decl->name + " (" + list + ")");
        }
        return;
      }
      default:
        wrong_kind(w, declared, r, v);
    }
  }

  void check_reference(Where& w, const TypeSpec& declared, const Resolved& r, Value v) {
    if (r.shape == Shape::Entity) {
      const Entity& wanted = *r.entity;
      const auto fits =
          instance_fits(v.id(), [&](const Entity& e) { return set_.is_subtype_of(e, wanted); });
      if (fits && !*fits)
        report(diag::Code::ExpReferenceType, w,
               describe(v) + " is not a " + wanted.name + " (nor a subtype of it)");
      return;
    }
    if (r.shape == Shape::Select) {
      const TypeDecl& select = *r.decl;
      const SelectInfo& info = select_info(select);
      const auto fits =
          instance_fits(v.id(), [&](const Entity& e) { return select_accepts(select, info, e); });
      if (fits && !*fits)
        report(
            diag::Code::ExpReferenceType, w,
            describe(v) + " is not a member of SELECT " + select.name + " (" + info.members + ")");
      return;
    }
    wrong_kind(w, declared, r, v);
  }

  void check_aggregate(Where& w, const Resolved& r, Value v, unsigned depth) {
    const TypeSpec& spec = *r.spec;
    const auto items = model_.items(v);
    const auto count = static_cast<std::int64_t>(items.size());
    const auto lower = bound_value(spec.lower, w);
    const auto upper = bound_value(spec.upper, w);
    // Messages are built only when reported: this runs for nearly every instance.
    const auto written = [&] {
      std::string text = to_express(spec);
      // A bound computed from the instance: say what it came to.
      const bool computed = (spec.lower && !spec.lower->value && !spec.lower->indeterminate()) ||
                            (spec.upper && !spec.upper->value && !spec.upper->indeterminate());
      if (computed)
        text += " (here [" + (lower ? std::to_string(*lower) : std::string("?")) + ":" +
                (upper ? std::to_string(*upper) : std::string("?")) + "])";
      return text;
    };
    const auto elements = [](std::int64_t n) {
      return std::to_string(n) + (n == 1 ? " element" : " elements");
    };
    if (spec.aggregate == AggregateKind::Array) {
      if (lower && upper && count != *upper - *lower + 1)
        report(diag::Code::ExpAggregateSize, w,
               written() + " holds exactly " + elements(*upper - *lower + 1) + ", found " +
                   std::to_string(count));
    } else if (lower && count < *lower) {
      report(
          diag::Code::ExpAggregateSize, w,
          written() + " needs at least " + elements(*lower) + ", found " + std::to_string(count));
    } else if (upper && count > *upper) {
      report(
          diag::Code::ExpAggregateSize, w,
          written() + " allows at most " + elements(*upper) + ", found " + std::to_string(count));
    }
    const TypeSpec& element = *spec.element;
    std::uint32_t number = 0;
    for (const Value item : items) {
      if (muted()) return;
      w.path.push_back(++number);
      if (item.kind() == ValueKind::Omitted) {
        if (!spec.optional_elements)
          report(diag::Code::ExpRequiredOmitted, w,
                 "'$' but the elements of " + std::string(aggregate_keyword(spec.aggregate)) +
                     " are not OPTIONAL");
      } else {
        check_value(w, element, r.schema, nullptr, item, depth + 1);
      }
      w.path.pop_back();
    }
  }

  void check_typed(Where& w, const TypeSpec& declared, const Resolved& r, Value v, unsigned depth) {
    const std::string_view name = model_.keyword(v.keyword_id());
    const Value inner = model_.typed_child(v);
    if (r.shape == Shape::Select) {
      const SelectInfo& info = select_info(*r.decl);
      const auto member =
          std::find_if(info.types.begin(), info.types.end(),
                       [&](const TypeDecl* t) { return equals_ignoring_case(t->name, name); });
      if (member == info.types.end()) {
        report(diag::Code::ExpSelectType, w,
               "the typed value " + std::string(name) + "(...) is not a member of SELECT " +
                   r.decl->name + " (" + info.members + ")");
        return;
      }
      const TypeDecl& type = **member;
      check_value(w, type.underlying, type.schema, &type, inner, depth + 1);
      return;
    }
    // A typed value that names the declared defined type itself (or one it is defined by):
    // redundant, but it says what the value is.
    const bool names_declared =
        std::any_of(r.names.begin(), r.names.end(),
                    [&](std::string_view n) { return equals_ignoring_case(n, name); });
    if (names_declared) {
      check_resolved(w, declared, r, inner, depth + 1);
      return;
    }
    wrong_kind(w, declared, r, v);
  }

  // ---- instances ----------------------------------------------------------------------------

  void unknown_entity(const Instance& instance, p21::KeywordId keyword, bool partial_record) {
    EntityInfo& info = entity_info(keyword);
    if (info.reported) return;
    info.reported = true;
    if (!stopped_) unknown_entities_.emplace_back(diagnostics_.size(), keyword);
    const std::string_view name = model_.keyword(keyword);
    std::string message = instance_name(instance, name, partial_record) + ": entity " +
                          std::string(name) + " is not in the schema";
    const std::size_t count = model_.instance_indices_of(keyword).size();
    if (count > 1) message += " (" + std::to_string(count) + " instances, the first here)";
    message += "; its values are not checked";
    add(diag::Code::ExpUnknownEntity, instance, std::move(message));
  }

  static std::string attribute_list(const std::vector<std::string_view>& names) {
    std::string out;
    for (const auto n : names) {
      if (!out.empty()) out += ", ";
      out += n;
    }
    return out;
  }

  void check_simple(const Instance& instance) {
    const EntityInfo& info = entity_info(instance.keyword);
    if (info.entity == nullptr) {
      unknown_entity(instance, instance.keyword, false);
      return;
    }
    const Entity& e = *info.entity;
    const auto params = model_.params(instance);
    const std::string_view written = model_.type_name(instance);
    if (e.is_abstract) {
      const std::string why =
          e.name + " is ABSTRACT; only its subtypes (or a complex instance) can be instantiated";
      if (options_.tolerant)
        tolerate(diag::Code::ExpAbstractInstance, instance, written, {}, why);
      else
        add(diag::Code::ExpAbstractInstance, instance,
            instance_name(instance, written, false) + ": " + why);
    }
    if (params.size() != e.attributes.size()) {
      std::vector<std::string_view> names;
      for (const auto& a : e.attributes) names.push_back(a.name);
      add(diag::Code::ExpParameterCount, instance,
          instance_name(instance, written, false) + " has " + std::to_string(params.size()) +
              " parameter" + (params.size() == 1 ? "" : "s") + "; the schema gives " + e.name +
              " " + std::to_string(e.attributes.size()) + " (" + attribute_list(names) + ")");
      return;
    }
    Where& w = fresh_where();
    w.instance = &instance;
    w.entity = written;
    w.declared_entity = e.name;
    w.owner = &e;
    w.params = params;
    for (std::size_t i = 0; i < params.size() && !muted(); ++i) {
      const FlatAttribute& a = e.attributes[i];
      AttributeView view{a.name,         &a.type, a.schema, a.optional, a.derived_redeclared,
                         a.redeclared_by};
      check_attribute(w, view, params[i]);
    }
  }

  // Each partial record holds the explicit attributes that its own entity declares (not the
  // redeclarations), in declaration order. A redeclaration by another record's entity, which
  // is a subtype of this one, still applies to the value: a DERIVE one makes it `*`, an explicit
  // one narrows its type (the deepest redeclaring entity wins).
  void check_complex(const Instance& instance) {
    std::vector<std::pair<Value, const Entity*>> records;
    for (const Value record : model_.params(instance)) {
      if (record.kind() != ValueKind::Typed) continue;  // the reader allows only records here
      const Entity* e = entity_info(record.keyword_id()).entity;
      if (e == nullptr) {
        unknown_entity(instance, record.keyword_id(), true);
        continue;
      }
      records.emplace_back(record, e);
    }
    for (const auto& [record, entity] : records) {
      if (muted()) return;
      const Entity& e = *entity;
      const Value list = model_.typed_child(record);
      if (!list.is_list()) continue;
      const auto values = model_.items(list);
      const std::string_view written = model_.keyword(record.keyword_id());
      std::vector<const ExplicitAttribute*> own;
      for (const auto& a : e.explicit_attributes)
        if (!a.redeclares) own.push_back(&a);
      if (values.size() != own.size()) {
        std::vector<std::string_view> names;
        for (const auto* a : own) names.push_back(a->name);
        add(diag::Code::ExpParameterCount, instance,
            instance_name(instance, written, true) + " has " + std::to_string(values.size()) +
                " parameter" + (values.size() == 1 ? "" : "s") + "; " + e.name + " declares " +
                std::to_string(own.size()) + " (" + attribute_list(names) + ")");
        continue;
      }
      Where& w = fresh_where();
      w.instance = &instance;
      w.entity = written;
      w.declared_entity = e.name;
      w.partial_record = true;
      for (std::size_t k = 0; k < own.size() && !muted(); ++k) {
        const auto same = [&](const FlatAttribute& f) {
          return f.owner == e.name && f.declared_name == own[k]->name;
        };
        const auto base = std::find_if(e.attributes.begin(), e.attributes.end(), same);
        if (base == e.attributes.end()) continue;
        AttributeView view{
            base->name,         &base->type, base->schema, base->optional, base->derived_redeclared,
            base->redeclared_by};
        std::size_t depth_of_choice = e.ancestors.size();
        for (const auto& [other_record, other] : records) {
          if (other == entity || !set_.is_subtype_of(*other, e)) continue;
          const auto f = std::find_if(other->attributes.begin(), other->attributes.end(), same);
          if (f == other->attributes.end() || f->redeclared_by.empty()) continue;
          if (f->derived_redeclared) {
            view.derived = true;
            view.derived_by = f->redeclared_by;
          } else if (other->ancestors.size() > depth_of_choice) {
            depth_of_choice = other->ancestors.size();
            view.type = &f->type;
            view.optional = f->optional;
            view.schema = f->schema;
          }
        }
        check_attribute(w, view, values[k]);
      }
    }
  }

  struct PairHash {
    std::size_t operator()(const std::pair<const TypeDecl*, const Entity*>& p) const noexcept {
      return std::hash<const void*>()(p.first) * 31 + std::hash<const void*>()(p.second);
    }
  };

  const Model& model_;
  const SchemaSet& set_;
  const ValidateOptions& options_;
  std::vector<EntityInfo> entities_;  // by keyword id
  EntityInfo no_entity_{true, true, nullptr};
  const TypeFacts* shared_;  // the plan's (options_.plan), read only; may be null
  TypeFacts own_;            // what the plan lacks
  std::unordered_map<std::pair<const TypeDecl*, const Entity*>, bool, PairHash> select_fits_;
  std::optional<p21::LineIndex> lines_;  // built at the first diagnostic
  Where where_;
  std::vector<diag::Diagnostic> diagnostics_;
  std::vector<std::pair<std::size_t, p21::KeywordId>> unknown_entities_;
  std::vector<Tolerated> tolerated_;
  std::unordered_map<std::string, std::size_t> tolerated_index_;  // key → tolerated_
  bool stopped_ = false;
};

// The pieces' findings in instance order, as one check over all of them would give them: an
// entity name unknown in several pieces is reported in the first only, and the limit applies
// to the whole. (A piece that stopped at the limit has more than enough for what is kept of it:
// it lacks at most one diagnostic per EXP-060 it repeats from earlier pieces, and each of those
// was kept from an earlier piece.)
std::vector<diag::Diagnostic> merge(std::vector<Validator::Found> pieces, std::size_t keywords,
                                    const ValidateOptions& options) {
  std::vector<diag::Diagnostic> out;
  std::vector<bool> unknown_reported(keywords, false);
  bool stopped = false;
  std::vector<Tolerated> tolerated;
  std::unordered_map<std::string, std::size_t> tolerated_index;
  for (auto& piece : pieces) {
    for (auto& t : piece.tolerated) add_tolerated(tolerated, tolerated_index, std::move(t));
    stopped = stopped || piece.stopped;
    auto unknown = piece.unknown_entities.begin();
    for (std::size_t i = 0; i < piece.diagnostics.size(); ++i) {
      if (unknown != piece.unknown_entities.end() && unknown->first == i) {
        const p21::KeywordId keyword = (unknown++)->second;
        if (unknown_reported[keyword]) continue;
        unknown_reported[keyword] = true;
      }
      if (out.size() == options.max_diagnostics) {
        stopped = true;
        break;
      }
      out.push_back(std::move(piece.diagnostics[i]));
    }
  }
  for (const auto& t : tolerated) out.push_back(tolerated_warning(t));
  if (stopped)
    out.push_back(diag::make(diag::Code::ExpTooManyProblems, 0, 0,
                             "validation stopped after " + std::to_string(options.max_diagnostics) +
                                 " diagnostics; the rest of the file was not checked"));
  return out;
}

}  // namespace

CheckPlan::CheckPlan(const SchemaSet& set) : impl_(std::make_unique<const Impl>(set)) {}
CheckPlan::~CheckPlan() = default;

const SchemaSet& CheckPlan::set() const noexcept {
  return impl_->set();
}

std::vector<diag::Diagnostic> validate(const p21::Model& model, const SchemaSet& schema,
                                       const ValidateOptions& options) {
  const auto instances = model.instances();
  const std::size_t pieces = std::max<std::size_t>(
      1, std::min(parallel::max_pieces(options.helpers),
                  instances.size() / std::max<std::size_t>(options.min_piece_instances, 1)));
  std::vector<Validator::Found> found(pieces);
  const auto check_piece = [&](std::size_t i) {
    const std::size_t first = instances.size() * i / pieces;
    const std::size_t end = instances.size() * (i + 1) / pieces;
    found[i] = Validator(model, schema, options).check(instances.subspan(first, end - first));
  };
  parallel::run_pieces(pieces, check_piece, options.helpers);
  return merge(std::move(found), model.keyword_count(), options);
}

}  // namespace ncpost::express
