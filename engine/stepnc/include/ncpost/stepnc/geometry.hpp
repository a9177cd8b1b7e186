#pragma once
// Points, directions and coordinate frames read from ISO 10303-42 placements.
//
// Shared by the two interpreters (engine/stepnc for ISO 14649, engine/ap238 for the AP238 AIM):
// the ISO 10303-42 resources are the same in both schemas, so one reader serves both. Not an
// interface for the pipeline, the CLI or the server (namespace detail).

#include <array>
#include <cmath>
#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

#include "ncpost/diag/diagnostic.hpp"
#include "ncpost/p21/model.hpp"
#include "ncpost/p21/reader.hpp"
#include "ncpost/stepnc/attributes.hpp"

namespace ncpost::stepnc::detail {

struct Vec3 {
  double x = 0;
  double y = 0;
  double z = 0;
  friend Vec3 operator+(Vec3 a, Vec3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
  friend Vec3 operator-(Vec3 a, Vec3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
  friend Vec3 operator*(Vec3 a, double s) { return {a.x * s, a.y * s, a.z * s}; }
  [[nodiscard]] double dot(Vec3 b) const { return x * b.x + y * b.y + z * b.z; }
  [[nodiscard]] Vec3 cross(Vec3 b) const {
    return {y * b.z - z * b.y, z * b.x - x * b.z, x * b.y - y * b.x};
  }
  [[nodiscard]] double length() const { return std::sqrt(dot(*this)); }
  [[nodiscard]] bool finite() const {
    return std::isfinite(x) && std::isfinite(y) && std::isfinite(z);
  }
};

// A right-handed frame: origin and unit axes, all expressed in the parent frame.
struct Frame {
  Vec3 origin{};
  Vec3 x{1, 0, 0};
  Vec3 y{0, 1, 0};
  Vec3 z{0, 0, 1};

  [[nodiscard]] Vec3 point(Vec3 local) const {
    return origin + x * local.x + y * local.y + z * local.z;
  }
  [[nodiscard]] Vec3 direction(Vec3 local) const { return x * local.x + y * local.y + z * local.z; }
  // This frame after `inner`: a point of `inner`'s local coordinates, in this frame's parent.
  [[nodiscard]] Frame then(const Frame& inner) const {
    return {point(inner.origin), direction(inner.x), direction(inner.y), direction(inner.z)};
  }
  [[nodiscard]] bool identity() const;
};

// The frame that undoes `f` (f.then(inverse(f)) is the identity): `f`'s parent in `f`'s
// coordinates. `f`'s axes must be orthonormal, as placements give them.
[[nodiscard]] Frame inverse(const Frame& f);

// Reads geometry instances, reporting every problem at the instance that has it.
class GeometryReader {
 public:
  GeometryReader(const p21::Model& model, const AttributeReader& attributes,
                 std::vector<diag::Diagnostic>& diagnostics);

  // CARTESIAN_POINT (two coordinates mean z = 0).
  [[nodiscard]] std::optional<Vec3> point(std::optional<p21::Value> reference);
  // DIRECTION, normalised.
  [[nodiscard]] std::optional<Vec3> direction(std::optional<p21::Value> reference);
  // AXIS2_PLACEMENT_3D; a missing axis is +Z and a missing ref_direction +X (ISO 10303-42).
  [[nodiscard]] std::optional<Frame> placement(std::optional<p21::Value> reference);
  // A number attribute, checked finite.
  [[nodiscard]] std::optional<double> number(const p21::Instance& owner, std::string_view name);

  // is_a by entity name, with the schema look-up of each name done once per interpretation.
  // `entity` must be a string with static storage (a literal): it keys the cache.
  [[nodiscard]] bool is_a(const p21::Instance& instance, std::string_view entity);
  // AttributeReader::get, with each (entity, name) position looked up once per interpretation.
  // `name` must be a literal, as for is_a.
  [[nodiscard]] std::optional<p21::Value> get(const p21::Instance& instance, std::string_view name);

  const p21::Instance* instance(std::optional<p21::Value> reference, std::string_view expected,
                                const p21::Instance* owner = nullptr,
                                std::string_view attribute = {});
  void error(diag::Code code, const p21::Instance& at, std::string message);

  [[nodiscard]] const p21::Model& model() const { return model_; }
  [[nodiscard]] const AttributeReader& attributes() const { return attributes_; }

 private:
  const p21::Model& model_;
  const AttributeReader& attributes_;
  std::vector<diag::Diagnostic>& diagnostics_;
  std::optional<p21::LineIndex> lines_;  // built at the first diagnostic
  std::unordered_map<std::string_view, const express::Entity*> entities_;
  // Per keyword: (name literal, position or -1) pairs, compared by pointer.
  std::vector<std::vector<std::pair<const char*, int>>> positions_;
  std::vector<std::vector<std::pair<const char*, bool>>> kinds_;  // is_a answers, likewise
};

std::string describe(const p21::Model& model, const p21::Instance& instance);

}  // namespace ncpost::stepnc::detail
