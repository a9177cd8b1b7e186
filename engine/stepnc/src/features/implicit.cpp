// Values left implicit, filled in with a note (implicit.hpp).

#include "implicit.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "reader.hpp"

namespace ncpost::stepnc::features {
namespace {

constexpr double kParallel = 1e-12;

bool tolerant(Reader& reader) {
  return reader.geometry().attributes().mode() == Mode::Tolerant;
}

// The workpiece's bounding BLOCK: its own, else its raw piece's (one level: a raw piece is the
// stock the workpiece is cut from, so its block contains the workpiece).
const Instance* bounding_block(Reader& reader, const Instance& workpiece) {
  const Instance* w = &workpiece;
  for (int level = 0; level < 2 && w != nullptr; ++level) {
    const auto v = reader.get(*w, "its_bounding_geometry");
    const Instance* g = v && v->is_reference() ? reader.model().find(v->id()) : nullptr;
    if (g != nullptr && reader.is(g, "block")) return g;
    const auto raw = reader.get(*w, "its_rawpiece");
    w = raw && raw->is_reference() ? reader.model().find(raw->id()) : nullptr;
  }
  return nullptr;
}

}  // namespace

std::optional<double> exit_distance(const detail::Frame& box, detail::Vec3 size, detail::Vec3 from,
                                    detail::Vec3 direction) {
  const detail::Frame to_box = detail::inverse(box);
  const detail::Vec3 p = to_box.point(from);
  const detail::Vec3 d = to_box.direction(direction);
  double enter = -std::numeric_limits<double>::infinity();
  double leave = std::numeric_limits<double>::infinity();
  const double ps[] = {p.x, p.y, p.z};
  const double ds[] = {d.x, d.y, d.z};
  const double ls[] = {size.x, size.y, size.z};
  for (int i = 0; i < 3; ++i) {
    if (std::abs(ds[i]) < kParallel) {
      if (ps[i] < 0 || ps[i] > ls[i]) return std::nullopt;  // beside the box, parallel to it
      continue;
    }
    const double a = (0 - ps[i]) / ds[i];
    const double b = (ls[i] - ps[i]) / ds[i];
    enter = std::max(enter, std::min(a, b));
    leave = std::min(leave, std::max(a, b));
  }
  if (!(leave > 0) || enter > leave || !std::isfinite(leave)) return std::nullopt;
  return leave;
}

bool implicit_through_depth(Reader& reader, std::optional<double>& out) {
  const Instance& f = reader.feature();
  out.reset();
  if (!tolerant(reader)) return false;
  const auto depth = reader.get(f, "depth");
  const Instance* bottom = reader.ref(f, "bottom_condition", "");
  if (!depth || !depth->is_omitted() || !reader.is(bottom, "through_bottom_condition"))
    return false;
  const Instance* workpiece = reader.ref(f, "its_workpiece", "workpiece");
  const Instance* block = workpiece ? bounding_block(reader, *workpiece) : nullptr;
  const auto fail = [&](const std::string& why) {
    reader.report().add_finding(diag::Code::InteropNoWorkpieceSize, reader.subject(f),
                                reader.name(f) + " has no depth and goes through its workpiece " +
                                    reader.name(workpiece) + ", but " + why +
                                    ", so the depth of the hole is unknown");
    return true;
  };
  if (block == nullptr) return fail("the workpiece has no bounding BLOCK");
  const auto box = reader.placement(*block, "position");
  const auto x = reader.number(*block, "x");
  const auto y = reader.number(*block, "y");
  const auto z = reader.number(*block, "z");
  const auto top = reader.placement(f, "feature_placement");
  if (!box || !x || !y || !z || !top) return fail(reader.name(block) + " has no size or position");
  // The hole goes down its own -z from its placement, both in the workpiece's coordinates.
  const auto leave = exit_distance(*box, {*x, *y, *z}, top->origin, top->z * -1.0);
  if (!leave || !reader.size_ok(*block, *leave, "depth through the workpiece"))
    return fail("its axis does not pass through " + reader.name(block));
  reader.report().add_finding(
      diag::Code::InteropThroughDepth, reader.subject(f),
      reader.name(f) + ": depth taken as " + fmt(*leave) +
          " mm (its depth is unset and its bottom THROUGH_BOTTOM_CONDITION: it goes through " +
          reader.name(workpiece) + ", whose bounding " + reader.name(block) + " ends " +
          fmt(*leave) + " mm below the hole's top)");
  out = leave;
  return true;
}

void note_implicit_cutting_depth(Reader& reader, double bottom_z) {
  if (!tolerant(reader)) return;
  const Instance& op = reader.operation();
  reader.report().add_finding(diag::Code::InteropCuttingDepth, reader.subject(op),
                              reader.name(op) + ": cutting_depth taken as " + fmt(-bottom_z) +
                                  " mm (unset: the depth of " + reader.name(reader.feature()) +
                                  " and its bottom)");
}

bool close_implicitly(Reader& reader, const Instance& profile, const Instance& curve, double gap) {
  if (!tolerant(reader) || !reader.is(&curve, "polyline")) return false;
  reader.report().add_finding(diag::Code::InteropProfileClosed, reader.subject(curve),
                              reader.name(curve) + " of " + reader.name(profile) +
                                  ": closed with a straight line of " + fmt(gap) +
                                  " mm back to its first point (a closed profile's polyline "
                                  "that does not repeat its first point)");
  return true;
}

}  // namespace ncpost::stepnc::features
