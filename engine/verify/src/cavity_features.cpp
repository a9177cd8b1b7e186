// The verifier's own reading of the profiled features (cavity.hpp): slots of any profile along
// lines and circles, steps and threads. The readings of the standard are the ones docs/verify.md
// states (ISO 10303-214's vee tilt, a step's wall at its vee's vertex, circles about the
// feature's origin); the code is the verifier's.

#include <algorithm>
#include <cctype>
#include <numbers>

#include "cavity.hpp"
#include "model.hpp"

namespace ncpost::verify::detail {
namespace {

constexpr double kDeg = std::numbers::pi / 180;

const p21::Instance* item(const Reader& r, p21::Value v) {
  return v.is_reference() ? r.model().find(v.id()) : nullptr;
}

// The swept profile as a section; false with the reason.
bool slot_section(const Reader& r, const p21::Instance& shape, double depth, Cavity& c,
                  Feature& f) {
  if (r.ref(shape, "placement") != nullptr) {
    f.reason = "its swept shape has a placement";
    return false;
  }
  if (r.is_a(shape, "square_u_profile")) {
    const auto width = r.length(shape, "width");
    for (const char* angle : {"first_angle", "second_angle"})
      if (const auto a = r.number(shape, angle); a && std::abs(*a - 90) > 1e-6) {
        f.reason = "its square-U walls are not vertical";
        return false;
      }
    const double r1 = r.length(shape, "first_radius").value_or(0);
    const double r2 = r.length(shape, "second_radius").value_or(0);
    if (!width || *width <= 0 || std::abs(r1 - r2) > 1e-9) {
      f.reason = "its square-U width or floor radii cannot be modelled";
      return false;
    }
    c.square_u(*width / 2, depth, r1);
    return true;
  }
  if (r.is_a(shape, "rounded_u_profile")) {
    const auto width = r.length(shape, "width");
    if (!width || *width <= 0) {
      f.reason = "its rounded-U profile has no width";
      return false;
    }
    c.rounded_u(*width / 2, depth);
    return true;
  }
  if (r.is_a(shape, "vee_profile")) {
    // ISO 10303-214: tilt_angle is the angle between the first side and the profile's x axis,
    // so a vee symmetric about the vertical has 90 - angle / 2.
    const auto angle = r.number(shape, "profile_angle");
    const auto tilt = r.number(shape, "tilt_angle");
    const double radius = r.length(shape, "profile_radius").value_or(0);
    if (!angle || !tilt || *angle <= 0 || *angle >= 180 || radius < 0) {
      f.reason = "its vee has no angle between 0 and 180 degrees";
      return false;
    }
    if (std::abs(*tilt - (90 - *angle / 2)) > 0.01) {
      f.reason = "its vee is tilted to one side";
      return false;
    }
    c.vee(*angle * kDeg, radius, depth);
    return true;
  }
  if (r.is_a(shape, "partial_circular_profile")) {
    const auto radius = r.length(shape, "radius");
    const auto sweep = r.number(shape, "sweep_angle");
    if (!radius || !sweep || *radius <= 0 || *sweep <= 0 || *sweep > 180 + 1e-9 ||
        !c.partial_circle(*radius, *sweep * kDeg, depth)) {
      f.reason = "its partial circle does not reach from the depth plane to the top";
      return false;
    }
    return true;
  }
  f.reason = "its swept shape " + r.type(shape) + " is not supported";
  return false;
}

}  // namespace

bool read_profiled_slot(const Reader& r, const p21::Instance& feature, Feature& f) {
  const double depth = -f.floor;
  const p21::Instance* travel = r.ref(feature, "course_of_travel");
  const p21::Instance* shape = r.ref(feature, "swept_shape");
  if (travel == nullptr || shape == nullptr || depth <= 0) {
    f.reason = "its course of travel, swept shape or depth cannot be read";
    return false;
  }
  auto cavity = std::make_shared<Cavity>();
  if (!slot_section(r, *shape, depth, *cavity, f)) return false;
  // End types: one item (other than a loop) for both ends, as the generator reads it.
  enum class End { None, Radiused, Open, Woodruff, Loop, Other };
  End ends[2] = {End::None, End::None};
  double woodruff[2] = {0, 0};
  std::size_t count = 0;
  if (const auto list = r.get(feature, "end_conditions"); list && list->is_list()) {
    const auto items = r.model().items(*list);
    count = items.size();
    for (std::size_t k = 0; k < items.size() && k < 2; ++k) {
      const p21::Instance* e = item(r, items[k]);
      if (e == nullptr) continue;
      if (r.is_a(*e, "radiused_slot_end_type")) {
        ends[k] = End::Radiused;
      } else if (r.is_a(*e, "open_slot_end_type")) {
        ends[k] = End::Open;
      } else if (r.is_a(*e, "loop_slot_end_type")) {
        ends[k] = End::Loop;
      } else if (r.is_a(*e, "woodruff_slot_end_type")) {
        ends[k] = End::Woodruff;
        woodruff[k] = r.length(*e, "radius").value_or(0);
      } else {
        ends[k] = End::Other;
      }
    }
    if (items.size() == 1) {
      ends[1] = ends[0];
      woodruff[1] = woodruff[0];
    }
  }
  // A placed course of travel is in f.frame already (model.cpp, place_travel).
  if (r.is_a(*travel, "complete_circular_path")) {
    const auto radius = r.length(*travel, "radius");
    if (!radius || *radius <= 0 || (count > 0 && ends[0] != End::Loop)) {
      f.reason = "its circular course of travel has no radius or ends that are not a loop";
      return false;
    }
    cavity->circle({0, 0}, *radius);
  } else if (r.is_a(*travel, "partial_circular_path")) {
    const auto radius = r.length(*travel, "radius");
    const auto sweep = r.number(*travel, "sweep_angle");
    if (!radius || !sweep || *radius <= 0 || ends[0] != End::Radiused || ends[1] != End::Radiused) {
      f.reason = "its arc of travel has no radius or ends other than radiused";
      return false;
    }
    cavity->arc({0, 0}, *radius, 0, *sweep * kDeg);
  } else if (r.is_a(*travel, "linear_path")) {
    const auto length = r.length(*travel, "distance");
    const auto direction = r.direction(r.ref(*travel, "its_direction"));
    if (!length || !direction || *length <= 0 || std::abs(direction->z) > 1e-9) {
      f.reason = "its course of travel cannot be read";
      return false;
    }
    for (int k = 0; k < 2; ++k) {
      if (ends[k] == End::Radiused || ends[k] == End::Open) continue;
      if (ends[k] == End::Woodruff && woodruff[k] + 1e-9 >= depth) continue;
      f.reason = ends[k] == End::Woodruff ? "its woodruff end is less deep than the slot"
                                          : "its ends are not radiused, open or woodruff ends";
      return false;
    }
    const Vec2 d = direction->xy() * (1 / direction->xy().length());
    cavity->segment({0, 0}, d * *length, ends[0] == End::Open, ends[1] == End::Open,
                    ends[0] == End::Woodruff ? woodruff[0] : 0,
                    ends[1] == End::Woodruff ? woodruff[1] : 0);
  } else {
    f.reason = "its course of travel " + r.type(*travel) + " is not supported";
    return false;
  }
  f.cavity = std::move(cavity);
  return true;
}

bool read_step(const Reader& r, const p21::Instance& feature, Feature& f) {
  const double depth = -f.floor;
  const p21::Instance* open = r.ref(feature, "open_boundary");
  const p21::Instance* wall = r.ref(feature, "wall_boundary");
  const auto length = open ? r.length(*open, "distance") : std::nullopt;
  auto along = open ? r.direction(r.ref(*open, "its_direction")) : std::nullopt;
  if (!length || !along || *length <= 0 || depth <= 0) {
    f.reason = "its open boundary or depth cannot be read";
    return false;
  }
  Vec3 origin{};
  if (const p21::Instance* placed = r.ref(*open, "placement")) {
    const auto frame = r.placement(placed);
    if (!frame || std::abs(frame->z.z - 1) > 1e-9) {
      f.reason = "its open boundary's placement cannot be read";
      return false;
    }
    origin = frame->origin;
    along = frame->direction(*along);
  }
  // The wall stands at the vertex of its wall_boundary's vee, whose placement locates it.
  const auto foot = wall ? r.placement(r.ref(*wall, "placement")) : std::nullopt;
  if (!foot) {
    f.reason = "its wall is not located (no wall_boundary with a placement)";
    return false;
  }
  const double angle = r.number(*wall, "profile_angle").value_or(90);
  const double tilt = r.number(*wall, "tilt_angle").value_or(0);
  const double radius = r.length(*wall, "profile_radius").value_or(0);
  if (std::abs(tilt) > 1e-6 || angle < 90 - 1e-9 || angle >= 180 || radius < 0) {
    f.reason = "its wall is tilted or overhangs its floor";
    return false;
  }
  const Vec2 d = along->xy() * (1 / along->xy().length());
  const Vec2 left{-d.y, d.x};
  const double offset = (foot->origin - origin).xy().dot(left);
  if (std::abs(offset) < 1e-6) {
    f.reason = "its wall stands on its open boundary";
    return false;
  }
  const Vec2 into_wall = left * (offset > 0 ? 1 : -1);
  auto cavity = std::make_shared<Cavity>();
  cavity->step(angle * kDeg, radius, depth);
  cavity->line(origin.xy() + into_wall * std::abs(offset), d, into_wall, *length, std::abs(offset));
  f.cavity = std::move(cavity);
  return true;
}

bool read_thread(const Reader& r, const p21::Instance& feature, Feature& f) {
  // The thread's cylinder of its major diameter down its length, then its hole.
  const auto list = r.get(feature, "applied_shape");
  const p21::Instance* hole = nullptr;
  if (list && list->is_list() && list->count() == 1) hole = item(r, r.model().items(*list)[0]);
  const auto major = r.number(feature, "major_diameter");
  if (hole == nullptr || !r.is_a(*hole, "round_hole") || !major || *major <= 0) {
    f.reason = "it is not applied to one ROUND_HOLE or has no major diameter";
    return false;
  }
  const auto own = r.placement(r.ref(feature, "feature_placement"));
  const auto hole_frame = r.placement(r.ref(*hole, "feature_placement"));
  const p21::Instance* plane = r.ref(*hole, "depth");
  const auto hole_depth = plane ? r.placement(r.ref(*plane, "position")) : std::nullopt;
  const auto diameter = r.length(*hole, "diameter");
  if (!own || !hole_frame || !hole_depth || !diameter ||
      (own->origin - hole_frame->origin).length() > 1e-6 ||
      (own->z - hole_frame->z).length() > 1e-9) {
    f.reason = "its hole is not on its axis or cannot be read";
    return false;
  }
  const double length = -f.floor;
  const double depth = -hole_depth->origin.z;
  bool through = false;
  if (const p21::Instance* bottom = r.ref(*hole, "bottom_condition")) {
    through = r.is_a(*bottom, "through_bottom_condition");
    if (!through && !r.is_a(*bottom, "flat_hole_bottom"))
      f.notes.push_back("its hole's " + r.type(*bottom) + " is checked as a flat bottom");
  }
  if (length <= 0 || depth < length - 1e-9 || *diameter >= *major) {
    f.reason = "its length, its hole's depth or its diameters are inconsistent";
    return false;
  }
  auto cavity = std::make_shared<Cavity>();
  cavity->thread(*major / 2, length, *diameter / 2, depth, through);
  cavity->point({0, 0});
  f.cavity = std::move(cavity);
  f.floor = -depth;
  f.through = through;
  f.coverage = false;
  f.notes.push_back(
      "its thread is checked as a cylinder of its major diameter, and the floor "
      "of its hole is not measured for coverage");
  return true;
}

}  // namespace ncpost::verify::detail
