// SLOT: the reader of what every slot has (course of travel, profile, ends) and of the straight
// U slots cleared as regions (slot.hpp).

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

#include "milling_read.hpp"
#include "profile_read.hpp"
#include "region.hpp"
#include "slot.hpp"

namespace ncpost::stepnc::features {
namespace {

constexpr double kEps = 1e-9;

bool read_linear_path(Reader& reader, const Instance& travel, SlotPath& path) {
  const auto length = reader.toleranced(travel, "distance");
  const auto along = reader.direction(travel, "its_direction");
  if (!length || !along || !(length->size > 0) || std::abs(along->z) > kEps)
    return reader.report().bad(
        reader.subject(travel),
        reader.name(travel) + " needs a positive distance in the slot's plane");
  if (!reader.size_ok(travel, length->size, "distance")) return false;
  path.kind = SlotPath::Kind::Line;
  path.length = length->size;
  path.dir = *along * (1.0 / along->length());
  return true;
}

// The circle is centred on the placement; a partial one starts on its x axis and sweeps
// counter-clockwise (clockwise for a negative sweep_angle).
bool read_circular_path(Reader& reader, const Instance& travel, SlotPath& path) {
  const auto radius = reader.toleranced(travel, "radius");
  if (!radius || !(radius->size > 0))
    return reader.report().bad(reader.subject(travel),
                               reader.name(travel) + " needs a positive radius");
  if (!reader.size_ok(travel, radius->size, "radius")) return false;
  path.radius = radius->size;
  if (reader.is(&travel, "complete_circular_path")) {
    path.kind = SlotPath::Kind::Circle;
    path.sweep = 2 * std::numbers::pi;
  } else {
    const auto sweep = reader.number(travel, "sweep_angle");
    if (!sweep || !(std::abs(*sweep) > 1e-6) || !(std::abs(*sweep) < 360 - 1e-6))
      return reader.report().bad(reader.subject(travel),
                                 reader.name(travel) +
                                     " needs a sweep_angle strictly between -360 and 360 degrees "
                                     "and not 0 (a whole circle is a COMPLETE_CIRCULAR_PATH)");
    path.kind = SlotPath::Kind::Arc;
    path.sweep = radians(*sweep);
  }
  path.length = path.radius * std::abs(path.sweep);
  return true;
}

// A course of travel with a placement of its own is read in that placement (in the feature's
// xy plane: turned about and moved along it, never tilted out of it).
bool read_path(Reader& reader, const Instance& travel, SlotPath& path, detail::Frame& frame) {
  const auto f = [&] { return reader.name(reader.feature()); };
  if (!read_profile_placement(reader, travel, "slot's", frame)) return false;
  if (reader.is(&travel, "linear_path")) return read_linear_path(reader, travel, path);
  if (reader.is(&travel, "circular_path")) return read_circular_path(reader, travel, path);
  return reader.report().not_implemented(f() + " along " + reader.name(travel) +
                                         " (linear and circular paths are)");
}

bool read_square_u(Reader& reader, const Instance& swept, SlotSection& s) {
  Report& report = reader.report();
  const auto w = reader.toleranced(swept, "width");
  const auto r1 = reader.toleranced(swept, "first_radius");
  const auto r2 = reader.toleranced(swept, "second_radius");
  const auto a1 = reader.number(swept, "first_angle");
  const auto a2 = reader.number(swept, "second_angle");
  if (!w || !(w->size > 0))
    return report.bad(reader.subject(swept), reader.name(swept) + " needs a positive width");
  if (!reader.size_ok(swept, w->size, "width")) return false;
  if ((a1 && std::abs(*a1 - 90) > 1e-6) || (a2 && std::abs(*a2 - 90) > 1e-6))
    return report.not_implemented(reader.name(swept) + " with walls that are not vertical");
  if (r1 && r2 && std::abs(r1->size - r2->size) > kEps)
    return report.not_implemented(reader.name(swept) + " with two different floor radii");
  s.kind = SlotSection::Kind::SquareU;
  s.half = w->size / 2;
  if (r1 && r1->size > 0) s.fillet = r1;
  return true;
}

bool read_rounded_u(Reader& reader, const Instance& swept, SlotSection& s) {
  const auto w = reader.toleranced(swept, "width");
  if (!w || !(w->size > 0))
    return reader.report().bad(reader.subject(swept),
                               reader.name(swept) + " needs a positive width");
  if (!reader.size_ok(swept, w->size, "width")) return false;
  s.kind = SlotSection::Kind::RoundedU;
  s.half = w->size / 2;
  s.radius = Toleranced{w->size / 2, w->upper / 2, w->lower / 2};
  return true;
}

// ISO 10303-214 (whose vee_profile ISO 14649-10 uses): profile_angle is the angle between the
// two sides, tilt_angle the angle between the first side and the profile's x axis (across the
// slot). The vee is symmetric about the tool axis when the first side rises at 90° - angle/2,
// which is the only vee a cone turning about that axis makes.
bool read_vee(Reader& reader, const Instance& swept, SlotSection& s) {
  Report& report = reader.report();
  const auto angle = reader.number(swept, "profile_angle");
  const auto tilt = reader.number(swept, "tilt_angle");
  const auto radius = reader.toleranced(swept, "profile_radius");
  const Subject named = reader.subject(swept);
  if (!angle || !(*angle > 0) || !(*angle < 180))
    return report.bad(named, named.name() + " profile_angle must be between 0 and 180 degrees");
  if (!tilt) return report.bad(named, named.name() + " has no tilt_angle");
  const double symmetric = 90 - *angle / 2;
  if (std::abs(*tilt - symmetric) > kAngleMatch)
    return report.not_implemented(
        reader.name(reader.feature()) + " with " + named.name() +
        ", a vee tilted to one side (tilt_angle " + fmt(*tilt) +
        "; read as ISO 10303-214 does, the angle between its first side and its x " +
        "axis, a symmetric vee of " + fmt(*angle) + " degrees has " + fmt(symmetric) + ")");
  if (radius && radius->size < 0)
    return report.bad(named, named.name() + " profile_radius is negative");
  if (radius && !reader.size_ok(swept, radius->size, "profile_radius")) return false;
  s.kind = SlotSection::Kind::Vee;
  s.angle = radians(*angle);
  s.radius = radius.value_or(Toleranced{});
  return true;
}

bool read_partial_circle(Reader& reader, const Instance& swept, SlotSection& s) {
  Report& report = reader.report();
  const auto radius = reader.toleranced(swept, "radius");
  const auto sweep = reader.number(swept, "sweep_angle");
  if (!radius || !(radius->size > 0))
    return report.bad(reader.subject(swept), reader.name(swept) + " needs a positive radius");
  if (!reader.size_ok(swept, radius->size, "radius")) return false;
  if (!sweep || !(*sweep > 0) || *sweep > 180 + 1e-9)
    return report.not_implemented(reader.name(reader.feature()) + " with " + reader.name(swept) +
                                  " whose sweep_angle is not in (0, 180] degrees (a wider arc "
                                  "undercuts its own top)");
  s.kind = SlotSection::Kind::PartialCircular;
  s.radius = *radius;
  s.sweep = radians(*sweep);
  return true;
}

bool read_section(Reader& reader, const Instance& swept, SlotSection& s) {
  const auto f = [&] { return reader.name(reader.feature()); };
  if (reader.set(swept, "placement"))
    return reader.report().not_implemented(f() + " with a placed swept_shape " +
                                           reader.name(swept));
  if (reader.is(&swept, "square_u_profile")) return read_square_u(reader, swept, s);
  if (reader.is(&swept, "rounded_u_profile")) return read_rounded_u(reader, swept, s);
  if (reader.is(&swept, "vee_profile")) return read_vee(reader, swept, s);
  if (reader.is(&swept, "partial_circular_profile")) return read_partial_circle(reader, swept, s);
  if (reader.is(&swept, "general_profile")) return read_general_section(reader, swept, s);
  return reader.report().not_implemented(f() + " with " + reader.name(swept) +
                                         " (square-U, rounded-U, vee and partial-circular slots "
                                         "are)");
}

bool read_end(Reader& reader, const Instance& e, SlotEnd& out) {
  Report& report = reader.report();
  out.subject = reader.subject(e);
  if (reader.is(&e, "radiused_slot_end_type")) {
    out.kind = SlotEnd::Kind::Radiused;
  } else if (reader.is(&e, "open_slot_end_type")) {
    out.kind = SlotEnd::Kind::Open;
  } else if (reader.is(&e, "loop_slot_end_type")) {
    out.kind = SlotEnd::Kind::Loop;
  } else if (reader.is(&e, "flat_slot_end_type")) {
    out.kind = SlotEnd::Kind::Flat;
    const auto c1 = reader.toleranced(e, "corner_radius1");
    const auto c2 = reader.toleranced(e, "corner_radius2");
    out.right = c1 ? c1->size : 0;
    out.left = c2 ? c2->size : 0;
    if (out.right < 0 || out.left < 0)
      return report.bad(out.subject, out.subject.name() + " has a negative corner radius");
    if (!reader.size_ok(e, std::max(out.right, out.left), "corner radius")) return false;
  } else if (reader.is(&e, "woodruff_slot_end_type")) {
    out.kind = SlotEnd::Kind::Woodruff;
    const auto r = reader.toleranced(e, "radius");
    if (!r || !(r->size > 0))
      return report.bad(out.subject, out.subject.name() + " needs a positive radius");
    if (!reader.size_ok(e, r->size, "radius")) return false;
    out.woodruff = *r;
  } else {
    return report.not_implemented(reader.name(reader.feature()) + " with end type " +
                                  out.subject.name());
  }
  return true;
}

bool read_ends(Reader& reader, SlotEnd (&end)[2], std::size_t& count) {
  const Instance& f = reader.feature();
  const auto list = reader.get(f, "end_conditions");
  count = 0;
  if (!list || !list->is_list()) return true;
  const auto items = reader.model().items(*list);
  if (items.size() > 2)
    return reader.report().bad(reader.subject(f),
                               reader.name(f) + " has more than two end_conditions");
  count = items.size();
  for (std::size_t k = 0; k < items.size(); ++k) {
    const Instance* e = reader.geometry().instance(items[k], "slot_end_type", &f, "end_conditions");
    if (e == nullptr || !read_end(reader, *e, end[k])) return false;
  }
  // One end type for a slot with two ends: both ends are of that type (ISO 14649-10 allows one
  // item only for a loop; a single other item is read leniently, as before).
  if (items.size() == 1) end[1] = end[0];
  return true;
}

// Ends against the path (ISO 14649-10: a loop end closes a slot whose path closes, alone).
bool check_ends(Reader& reader, const SlotBasics& basics) {
  const Subject f = reader.subject(reader.feature());
  const SlotEnd(&end)[2] = basics.end;
  const bool loop = basics.end_count > 0 &&
                    (end[0].kind == SlotEnd::Kind::Loop || end[1].kind == SlotEnd::Kind::Loop);
  if (basics.path.kind == SlotPath::Kind::Circle) {
    if (basics.end_count > 0 && !(basics.end_count == 1 && loop))
      return reader.report().bad(f, f.name() + " runs along the closed " + basics.travel.name() +
                                        ": its only end condition can be a LOOP_SLOT_END_TYPE");
    return true;
  }
  if (loop)
    return reader.report().bad(f, f.name() +
                                      " has a LOOP_SLOT_END_TYPE, but its course of travel " +
                                      basics.travel.name() + " does not close");
  if (basics.end_count == 0)
    return reader.report().bad(
        f, f.name() + " has no end_conditions: the shape of its ends is unknown");
  return true;
}

}  // namespace

bool SlotBasics::region() const {
  const bool woodruff =
      path.kind != SlotPath::Kind::Circle &&
      (end[0].kind == SlotEnd::Kind::Woodruff || end[1].kind == SlotEnd::Kind::Woodruff);
  const bool u_profile =
      section.kind == SlotSection::Kind::SquareU || section.kind == SlotSection::Kind::RoundedU;
  return path.kind == SlotPath::Kind::Line && u_profile && !woodruff;
}

bool read_slot_basics(Reader& reader, SlotBasics& basics) {
  Report& report = reader.report();
  const Instance& f = reader.feature();
  const Instance& op = reader.operation();
  if (!reader.is(&op, "bottom_and_side_milling") && !reader.is(&op, "side_milling"))
    return report.not_implemented(reader.name(op) + " on " + reader.name(f) +
                                  " (slots take bottom-and-side or side milling)");
  const Instance* travel = reader.ref(f, "course_of_travel", "travel_path");
  const Instance* swept = reader.ref(f, "swept_shape", "open_profile");
  if (travel == nullptr || swept == nullptr)
    return report.bad(reader.subject(f),
                      reader.name(f) + " needs a course_of_travel and a swept_shape");
  basics.travel = reader.subject(*travel);
  basics.swept = reader.subject(*swept);
  return read_path(reader, *travel, basics.path, basics.travel_frame) &&
         read_section(reader, *swept, basics.section) &&
         read_ends(reader, basics.end, basics.end_count) && check_ends(reader, basics);
}

// Extent along the course of travel (s from its start) and the corners at each end: a radiused
// end is a half circle about the end of the course of travel, a flat end a wall at it
// (corner_radius1 on the right of the travel direction, corner_radius2 on the left), an open
// end lets the tool run out of the slot.
bool read_slot_region(Reader& reader, const SlotBasics& basics, RegionSpec& spec) {
  const auto tool = reader.read_tool();
  if (!tool) return false;
  const Operation operation = reader.read_operation();
  const SlotEnd(&end)[2] = basics.end;
  const double half = basics.section.half;
  const double runout = tool->radius + reader.options().clearance;
  const auto reach = [&](const SlotEnd& e) {
    return e.kind == SlotEnd::Kind::Radiused ? half : e.kind == SlotEnd::Kind::Open ? runout : 0.0;
  };
  const auto corner = [&](const SlotEnd& e, bool left) {
    if (e.kind == SlotEnd::Kind::Radiused) return half;
    if (e.kind == SlotEnd::Kind::Open) return tool->radius + operation.allowance_side;
    return std::min(left ? e.left : e.right, half);
  };
  const double s0 = -reach(end[0]);
  const double s1 = basics.path.length + reach(end[1]);
  Region region;
  // Corners counter-clockwise from (+a, +b): the second end (+x) left, the first end (-x) left,
  // the first end right, the second end right.
  const std::array<double, 4> corners{corner(end[1], true), corner(end[0], true),
                                      corner(end[0], false), corner(end[1], false)};
  double in_material = half;
  bool any_in_material = false;
  for (int k = 0; k < 4; ++k) {
    const SlotEnd& e = end[k == 0 || k == 3 ? 1 : 0];
    if (e.kind == SlotEnd::Kind::Open) continue;
    any_in_material = true;
    in_material = std::min(in_material, corners[static_cast<std::size_t>(k)]);
  }
  region.shape = Shape::rectangle((s1 - s0) / 2, half, in_material);
  if (std::any_of(corners.begin(), corners.end(),
                  [&](double c) { return std::abs(c - corners[0]) > kEps; }))
    region.shape.corners = corners;
  else
    region.shape.corner = corners[0];
  region.corners_in_material = any_in_material;
  // The slot's frame: centred half way along its extent, x along the course of travel.
  const Vec3 dir = basics.path.dir;
  region.shape.frame.origin = dir * ((s0 + s1) / 2);
  region.shape.frame.x = dir;
  region.shape.frame.y = Vec3{0, 0, 1}.cross(dir);
  if (basics.section.kind == SlotSection::Kind::RoundedU) {
    // A full-round floor: only a ball of the slot's width, along the centre line.
    region.fillet = basics.section.radius;
    region.centre_only = true;
  } else {
    region.fillet = basics.section.fillet;
  }
  if (reader.is(operation.strategy, "center_milling")) region.centre_only = true;
  region.walls_only = reader.is(&reader.operation(), "side_milling");
  const auto depth = reader.read_depth();
  if (!depth) return false;
  return read_region(reader, region, *depth, *tool, operation, spec);
}

}  // namespace ncpost::stepnc::features
