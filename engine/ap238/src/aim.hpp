#pragma once
// Reading the AIM: the generic resources (properties, representations, relationships, units)
// through which AP238 spells the ARM's objects. Shared by the interpreter and the inspector.

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "links.hpp"
#include "ncpost/diag/diagnostic.hpp"
#include "ncpost/p21/model.hpp"
#include "ncpost/stepnc/attributes.hpp"
#include "ncpost/stepnc/geometry.hpp"

namespace ncpost::ap238::detail {

using p21::Instance;
using stepnc::detail::Frame;
using stepnc::detail::Vec3;

// The dimensions a unit measures, as exponents of the base units ncpost converts to: mm, s,
// rad and revolutions. `other` counts what none of those covers (mass, temperature, solid
// angle, a context-dependent unit other than 'revolution', a fractional exponent).
struct Dimensions {
  int length = 0;
  int time = 0;
  int angle = 0;
  int revolution = 0;
  int other = 0;
  friend bool operator==(const Dimensions&, const Dimensions&) = default;
};
inline constexpr Dimensions kLength{1, 0, 0, 0, 0};
inline constexpr Dimensions kTime{0, 1, 0, 0, 0};
inline constexpr Dimensions kAngle{0, 0, 1, 0, 0};
inline constexpr Dimensions kLengthPerTime{1, -1, 0, 0, 0};
inline constexpr Dimensions kRevolutionsPerTime{0, -1, 0, 1, 0};
inline constexpr Dimensions kNone{};

// One unit: `factor` base units (mm^l s^t rad^a rev^r) each.
struct Unit {
  double factor = 1;
  Dimensions dimensions;
};

// A value converted to base units.
struct Quantity {
  double value = 0;
  Dimensions dimensions;
};

// The units of a representation context's items: lengths in mm and plane angles in radians per
// unit. A context without assigned units (ISO 10303-43 allows it) reads as mm and radians.
struct ContextUnits {
  double mm_per_length = 1;
  double radians_per_angle = 1;
};

// The representations that give a property its value: almost always one, kept inline (a
// program has a property per toolpath and kind); more go to a vector.
class Representations {
 public:
  void push_back(const Instance* r) {
    if (first_ == nullptr)
      first_ = r;
    else
      rest_.push_back(r);
  }
  [[nodiscard]] bool empty() const { return first_ == nullptr; }
  [[nodiscard]] const Instance* front() const { return first_; }
  template <class F>
  void for_each(F&& f) const {
    if (first_ != nullptr) f(*first_);
    for (const Instance* r : rest_) f(*r);
  }

 private:
  const Instance* first_ = nullptr;
  std::vector<const Instance*> rest_;
};

// A property of an AIM object: its name and the representations that give its value.
struct Property {
  const Instance* instance = nullptr;  // action_property or resource_property
  std::string name;
  Representations representations;
};

// A conversion-based unit defined through this many others is refused (a cycle, or hostile).
inline constexpr int kMaxUnitDepth = 8;
// The largest power of a derived unit's element read as such: real units use 1 to 4; a larger
// one (1E300 in a hostile file) is counted like a fractional power, as nothing ncpost converts.
inline constexpr double kMaxUnitExponent = 16;

class Aim {
 public:
  Aim(const p21::Model& model, const stepnc::AttributeReader& attributes,
      std::vector<diag::Diagnostic>& diagnostics);

  [[nodiscard]] const p21::Model& model() const { return model_; }
  [[nodiscard]] stepnc::detail::GeometryReader& geometry() { return geometry_; }
  [[nodiscard]] const Links& links() const { return links_; }
  [[nodiscard]] std::string describe(const Instance& i) const;
  void report(diag::Code code, const Instance& at, std::string message) {
    geometry_.error(code, at, std::move(message));
  }
  // A diagnostic about the whole file (no instance to point at).
  void report_unplaced(diag::Code code, std::string message) {
    diagnostics_.push_back(diag::make(code, 0, 0, std::move(message)));
  }
  [[nodiscard]] const std::vector<diag::Diagnostic>& diagnostics() const { return diagnostics_; }

  // ---- attributes (names must be literals: GeometryReader caches by pointer) ----
  [[nodiscard]] bool is_a(const Instance& i, std::string_view entity) {
    return geometry_.is_a(i, entity);
  }
  [[nodiscard]] std::optional<p21::Value> get(const Instance& i, std::string_view attribute) {
    return geometry_.get(i, attribute);
  }
  // A string attribute, "" when it is unset or not a string.
  [[nodiscard]] std::string text(const Instance& i, std::string_view attribute);
  // True when the string attribute is `wanted` (without decoding a plain string).
  [[nodiscard]] bool text_is(const Instance& i, std::string_view attribute,
                             std::string_view wanted);
  [[nodiscard]] const Instance* ref(const Instance& i, std::string_view attribute);

  // Every instance of `entity` or of a subtype, in file order (keyword by keyword: the entity
  // of a keyword is looked up once, not per instance).
  [[nodiscard]] std::vector<const Instance*> instances_of(std::string_view entity) const;

  // ---- links ----
  // The instances of `entity` whose `attribute` refers to `target`, in file order.
  [[nodiscard]] std::vector<const Instance*> referring(const Instance& target,
                                                       std::string_view entity,
                                                       std::string_view attribute);
  // The related_method of every relationship of kind `relationship` whose relating_method is
  // `method`. Sequential kinds come in sequence_position order (ties in file order, with one
  // AP238-012 warning at `method`), the others in file order.
  [[nodiscard]] std::vector<const Instance*> related(const Instance& method,
                                                     std::string_view relationship);
  // The properties (action_property, resource_property) that describe `owner`; the second
  // form refills `out`, keeping its storage (the interpreter reads every toolpath's).
  [[nodiscard]] std::vector<Property> properties(const Instance& owner);
  void properties(const Instance& owner, std::vector<Property>& out);
  // The related_method of the first relationship of kind `relationship` from `method` (in
  // file order), and how many there are; no allocation.
  [[nodiscard]] const Instance* first_related(const Instance& method, std::string_view relationship,
                                              std::size_t& count);
  // The representation items of a representation.
  [[nodiscard]] std::vector<const Instance*> items(const Instance& representation);
  // Its first item that is `entity` and, when `name` is not empty, is named so; null if none.
  [[nodiscard]] const Instance* first_item(const Instance& representation, std::string_view entity,
                                           std::string_view name = {});
  // The first item of the property's representations that is `entity` and, when `name` is not
  // empty, is named so.
  [[nodiscard]] const Instance* item(const Property& p, std::string_view entity,
                                     std::string_view name = {});

  // ---- values ----
  // A descriptive_representation_item's text, or nullopt.
  [[nodiscard]] std::optional<std::string> description_of(const Instance* item);
  // The text of the property's first descriptive item ("" without one), remembered per
  // representation: writers share one representation among thousands of toolpaths.
  [[nodiscard]] const std::string& described(const Property& p);
  // A measure (measure_representation_item, measure_with_unit) in base units; nullopt when its
  // value is not a number or its unit cannot be read (the caller reports AP238-008).
  [[nodiscard]] std::optional<Quantity> measure(const Instance& item);
  [[nodiscard]] std::optional<Unit> unit(p21::Value reference, int depth = 0);
  [[nodiscard]] ContextUnits context_units(const Instance& representation);

 private:
  const p21::Model& model_;
  const stepnc::AttributeReader& attributes_;
  std::vector<diag::Diagnostic>& diagnostics_;
  stepnc::detail::GeometryReader geometry_;
  Links links_;
  std::unordered_map<std::uint64_t, std::optional<Unit>> units_;
  std::unordered_map<std::uint64_t, ContextUnits> contexts_;
  std::unordered_map<std::uint64_t, std::string> descriptions_;  // by representation id
  std::vector<std::uint64_t> sequence_warned_;
};

}  // namespace ncpost::ap238::detail
