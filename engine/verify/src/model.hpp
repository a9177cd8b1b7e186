#pragma once
// What the verifier reads from the ISO 14649 model: frames, tools, operations and features. Its
// own small readers (through the schema, by attribute name), independent of the interpreter's
// and the generator's, so a misreading there is not repeated here.

#include <array>
#include <cmath>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "ncpost/p21/model.hpp"
#include "ncpost/p21/reader.hpp"
#include "ncpost/stepnc/attributes.hpp"
#include "ncpost/stepnc/interpreter.hpp"
#include "region.hpp"

namespace ncpost::verify::detail {

class Cavity;

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
  [[nodiscard]] Vec2 xy() const { return {x, y}; }
};

// Origin and unit axes in the parent frame.
struct Frame {
  Vec3 origin{};
  Vec3 x{1, 0, 0};
  Vec3 y{0, 1, 0};
  Vec3 z{0, 0, 1};
  [[nodiscard]] Vec3 point(Vec3 l) const { return origin + x * l.x + y * l.y + z * l.z; }
  [[nodiscard]] Vec3 direction(Vec3 l) const { return x * l.x + y * l.y + z * l.z; }
  [[nodiscard]] Vec3 local(Vec3 p) const {
    const Vec3 d = p - origin;
    return {d.dot(x), d.dot(y), d.dot(z)};
  }
  [[nodiscard]] Frame then(const Frame& inner) const {
    return {point(inner.origin), direction(inner.x), direction(inner.y), direction(inner.z)};
  }
};

class Reader {
 public:
  Reader(const p21::Model& model, const stepnc::AttributeReader& attributes)
      : m_(model), a_(attributes), lines_(model.text()) {}

  [[nodiscard]] const p21::Model& model() const { return m_; }
  // The job's reading (stepnc::Mode): tolerant, the verifier takes the values a program leaves
  // implicit as the interpreter does (docs/interoperability.md), each computed here on its own.
  [[nodiscard]] bool tolerant() const { return a_.mode() == stepnc::Mode::Tolerant; }
  [[nodiscard]] std::optional<p21::Value> get(const p21::Instance& i, std::string_view name) const {
    return a_.get(i, name);
  }
  // The referenced instance, or null when the attribute is unset or not a reference.
  [[nodiscard]] const p21::Instance* ref(const p21::Instance& i, std::string_view name) const;
  [[nodiscard]] bool is_a(const p21::Instance& i, std::string_view entity) const {
    return a_.is_a(i, entity);
  }
  [[nodiscard]] std::optional<double> number(const p21::Instance& i, std::string_view name) const;
  // A length given as a number, a TOLERANCED_LENGTH_MEASURE (its theoretical size) or a
  // NUMERIC_PARAMETER (its value).
  [[nodiscard]] std::optional<double> length(const p21::Instance& i, std::string_view name) const;
  [[nodiscard]] std::optional<Vec3> point(const p21::Instance* p) const;
  [[nodiscard]] std::optional<Vec3> direction(const p21::Instance* d) const;
  // AXIS2_PLACEMENT_3D with ISO 10303-42's defaults (axis +Z, ref_direction +X projected).
  [[nodiscard]] std::optional<Frame> placement(const p21::Instance* a) const;
  [[nodiscard]] std::string name(const p21::Instance& i) const;
  [[nodiscard]] std::string type(const p21::Instance& i) const {
    return std::string(m_.type_name(i));
  }
  // "#18 CLOSED_POCKET 'POCKET1'"
  [[nodiscard]] std::string describe(const p21::Instance& i) const;
  [[nodiscard]] p21::LineIndex::Position where(const p21::Instance& i) const {
    return lines_.at(i.offset);
  }

 private:
  const p21::Model& m_;
  const stepnc::AttributeReader& a_;
  p21::LineIndex lines_;
};

// De Boor's algorithm in homogeneous coordinates: the point at parameter u of a clamped B-spline
// of `degree` with control points (x, y, z, weight) and knots expanded by multiplicity.
[[nodiscard]] Vec3 de_boor(const std::vector<std::array<double, 4>>& points,
                           const std::vector<double>& knots, int degree, double u);

// A tool as a solid of revolution with its tip (the canonical position) at the origin: flat,
// bull-nose, ball, or a cone with a rounded tip (countersinks, pointed cutters, drills).
struct ToolShape {
  double radius = 0;
  double corner = 0;  // edge radius (a ball: the radius)
  double cone = 0;    // angle between the flank and the axis (radians); 0: no cone
  // Height of the tool's lower surface above its tip at distance rho from its axis.
  [[nodiscard]] double lower(double rho) const;
  // Its outline in (rho, h): along the lower surface from the tip out to the radius, then up
  // the side to `height` above the tip.
  [[nodiscard]] std::vector<Vec2> outline(double spacing, double height) const;
};

struct Tool {
  bool known = false;  // a diameter was found
  double radius = 0;
  bool ball = false;
  // Its whole shape, for the features whose walls are not vertical (cavity.hpp); the checks of
  // the others take it as a flat or ball end of `radius`.
  ToolShape shape;
  bool hole_making = false;    // drill, reamer, tap, boring tool, ...: plunging is what it does
  bool centre_cutting = true;  // false for face, side, T-slot, woodruff, dovetail, thread mills
  std::string body;            // entity of the tool body, e.g. "TAPERED_ENDMILL"
};
Tool read_tool(const Reader& r, const p21::Instance* tool, const stepnc::InterpretOptions& options);

struct Operation {
  const p21::Instance* instance = nullptr;
  bool hole_making = false;
  // Centre drilling and countersinking stop short of the hole's depth by design.
  bool spot = false;
  double side_allowance = 0;
  double bottom_allowance = 0;
  bool has_bottom_allowance = false;
  // The approach strategy, when it limits how steeply the tool may enter material.
  enum class Approach { None, ToolAxis, Ramp, Helix, Zigzag } approach = Approach::None;
  std::optional<double> approach_angle;  // degrees
  const p21::Instance* approach_instance = nullptr;
};
Operation read_operation(const Reader& r, const p21::Instance* operation);

// A feature in its own frame: z up along the feature axis, the top at z = 0, the floor at
// `floor`; `region` its outline in the xy plane.
struct Feature {
  const p21::Instance* instance = nullptr;
  std::string type;
  bool checked = false;
  std::string reason;  // why not, when not
  enum class Kind { Face, Pocket, Hole, Slot, Outside, Profiled } kind = Kind::Pocket;
  Frame frame;    // machine ← feature
  Region region;  // what the walls bound (an open slot end lies far beyond the slot)
  // The floor, when it is not `region` (a slot with an open end: the floor stops at the end).
  std::optional<Region> floor_region;
  [[nodiscard]] const Region& floor_outline() const {
    return floor_region ? *floor_region : region;
  }
  bool walls = true;  // a face has none: the tool may overhang its outline
  // An outside profile: the material is inside `region` and the tool outside; the floor is a
  // band round the region, as wide as the smallest tool radius (the stock beyond is unknown).
  bool outside = false;
  double floor = 0;
  bool through = false;
  double hole_radius = 0;
  // A CONICAL_HOLE_BOTTOM's point lies this far below the depth plane (R / tan(tip angle / 2)):
  // the depth plane ends the cylinder, and a pointed tool may go into the cone.
  double cone_depth = 0;
  std::vector<std::string> notes;  // what of the shape is simplified (bottom radius, taper, ...)
  // Profiled: slots of any profile, steps, threads (cavity.hpp), instead of `region`.
  std::shared_ptr<const Cavity> cavity;
  bool coverage = true;  // false: the feature has no floor of its own to cover (a thread)
  [[nodiscard]] bool has_outline() const { return cavity != nullptr || !region.empty(); }
};
// Readers of the profiled features (cavity_features.cpp): false, with f.reason, when the
// feature cannot be modelled.
bool read_profiled_slot(const Reader& r, const p21::Instance& feature, Feature& f);
bool read_step(const Reader& r, const p21::Instance& feature, Feature& f);
bool read_thread(const Reader& r, const p21::Instance& feature, Feature& f);

// `workpiece_frame` is machine ← the feature's workpiece.
Feature read_feature(const Reader& r, const p21::Instance& feature, const Frame& workpiece_frame);

// The footprint of a feature in machine coordinates (bounding box) and its top: used to build
// the stock when the workpiece has no bounding geometry.
struct Extent {
  Vec2 min{1e300, 1e300};
  Vec2 max{-1e300, -1e300};
  double top = -1e300;
  [[nodiscard]] bool valid() const { return min.x <= max.x && min.y <= max.y; }
  void add(Vec3 p) {
    min = {std::min(min.x, p.x), std::min(min.y, p.y)};
    max = {std::max(max.x, p.x), std::max(max.y, p.y)};
  }
};
Extent feature_extent(const Feature& f);
// BLOCK bounding geometry of a workpiece, in machine coordinates; nullopt when it has none.
std::optional<Extent> workpiece_block(const Reader& r, const p21::Instance& workpiece,
                                      const Frame& workpiece_frame);
// The same BLOCK's eight corners in machine coordinates (corner k is x if k & 1, y if k & 2,
// z if k & 4 along the block's own axes).
std::optional<std::array<Vec3, 8>> workpiece_block_corners(const Reader& r,
                                                           const p21::Instance& workpiece,
                                                           const Frame& workpiece_frame);

// Where a SETUP puts its workpieces: machine <- setup (its_origin), and machine <- each
// workpiece of its_workpiece_setup (the setup's origin, then the workpiece set-up's).
struct SetupFrames {
  Frame setup;
  Frame default_workpiece;  // the first workpiece's, else the setup's
  std::vector<std::pair<std::uint64_t, Frame>> workpieces;  // workpiece id (0: unset) -> frame
};
SetupFrames setup_frames(const Reader& r, const p21::Instance& setup);

}  // namespace ncpost::verify::detail
