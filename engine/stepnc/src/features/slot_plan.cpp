// The passes of a form tool along a slot's course of travel (slot.hpp): the planner, level by
// level:
// - along a straight slot, one pass on the course of travel (back and forth between levels),
//   or, for stepped passes, the centre line and then rings about it, each ring the course of
//   travel offset by its pass's offset (half circles about radiused ends, a crossing beyond an
//   open end, where the slot has left the part);
// - up and down the arcs of woodruff ends, played as straight feeds whose chords stay inside
//   the arc (the ball moves away from the end, never into it);
// - along an arc between radiused ends, or round a closed circle (a loop end).
// A level above the bottom runs each finishing pass no deeper than the level: the tool is
// lifted from a place where it touches the slot, which keeps it inside the slot, whose walls
// never overhang.

#include <algorithm>
#include <cmath>
#include <functional>
#include <numbers>
#include <tuple>

#include "motion.hpp"
#include "slot.hpp"

namespace ncpost::stepnc::features {
namespace {

constexpr double kEps = 1e-9;

// A point of a pass: u along the course of travel (from the end the pass starts at), v to its
// left, z the tool tip's height.
struct Station {
  double u = 0;
  double v = 0;
  double z = 0;
};

// One move of a ring, in the same coordinates: straight, or an arc about (cu, cv).
struct RingMove {
  Station to;
  bool arc = false;
  double cu = 0;
  double cv = 0;
};

class Passes {
 public:
  Passes(const FormSlotSpec& spec, Draft& draft)
      : draft_(draft), options_(draft.options()), spec_(spec), depth_(spec.depth) {}

  bool run();

 private:
  // A straight slot, from end `a` towards the other.
  [[nodiscard]] Vec3 at(int a, Station p) const;
  [[nodiscard]] double extension(const SlotEnd& e) const {
    return e.kind == SlotEnd::Kind::Open ? spec_.tool_radius + options_.clearance : 0.0;
  }
  // The woodruff end's arc for a pass whose tip is at `level` (at or above the bottom), from
  // where it leaves the level to where the tool is out of the slot; u measured outwards from
  // the end of the course of travel.
  [[nodiscard]] std::vector<Station> woodruff(const SlotEnd& e, double level) const;
  [[nodiscard]] std::vector<Station> centre_line(int a, double z) const;
  [[nodiscard]] std::vector<RingMove> ring(int a, double offset, double z) const;
  [[nodiscard]] std::vector<SlotPass> level_passes(double level) const;
  void descend(int a, Station start, double from_z, bool in_material, bool first);
  bool line();
  // How the tool goes from one height to another along a circular path, from `from_z` to
  // `to_z`, as the entry says (a ramp or a helix along the circle).
  using Slope = std::function<void(const Entry&, double from_z, double to_z)>;
  [[nodiscard]] Vec3 on_circle(double theta, double z) const;
  // Along a circular path, level by level: down at `theta` (along the axis, or by `slope` as
  // the approach asks), then `run` at the level; after the last level up by `slope` for a
  // retract other than along the axis, and to the top.
  bool around(double& theta, const Slope& slope, const std::function<void(double)>& run);
  bool arc();
  bool circle();
  void leave_end(int a, Station here);
  void plunge_note();

  Draft& draft_;
  const FeatureOptions& options_;
  const FormSlotSpec& spec_;
  double depth_;
  bool noted_ = false;
  double clear_ = 0;
  double retract_ = 0;
};

Vec3 Passes::at(int a, Station p) const {
  const Vec3 dir = spec_.path.dir;
  const Vec3 left = Vec3{0, 0, 1}.cross(dir);
  const double s = a == 0 ? p.u : spec_.path.length - p.u;
  const double t = a == 0 ? p.v : -p.v;
  return dir * s + left * t + Vec3{0, 0, p.z};
}

std::vector<Station> Passes::woodruff(const SlotEnd& e, double level) const {
  const double r = spec_.ball_radius;
  // The ball touches the end's arc (radius R about an axis R above the bottom, across the
  // slot) when its centre is R - r - allowance from that axis; the allowance is what the
  // finishing pass leaves at the bottom.
  const double allowance = depth_ - spec_.passes.front().depth;
  const double axis = -depth_ + e.woodruff.size;
  const double rho = std::max(0.0, e.woodruff.size - r - allowance);
  const auto tip = [&](double phi) { return axis - rho * std::cos(phi) - r; };
  const auto out = [&](double phi) { return rho * std::sin(phi); };
  std::vector<Station> points;
  if (rho < 1e-6) {
    // The ball is the end: straight up out of it.
    points.push_back({0, 0, level});
    if (level < 0) points.push_back({0, 0, 0});
    return points;
  }
  const double from = std::acos(std::clamp((axis - r - level) / rho, -1.0, 1.0));
  const double to =
      std::min(std::numbers::pi / 2, std::acos(std::clamp((axis - r) / rho, -1.0, 1.0)));
  const double tol = options_.profile_tolerance;
  const double step = rho > tol ? 2 * std::acos(1 - tol / rho) : std::numbers::pi / 2;
  const auto n = static_cast<std::size_t>(std::max(1.0, std::ceil((to - from) / step - 1e-9)));
  points.push_back({out(from), 0, std::max(level, tip(from))});
  for (std::size_t k = 1; k <= n && to > from + kEps; ++k) {
    const double phi = from + (to - from) * static_cast<double>(k) / static_cast<double>(n);
    points.push_back({out(phi), 0, tip(phi)});
  }
  // A quarter turn that leaves the tip below the top: straight up from there.
  if (points.back().z < 0) points.push_back({points.back().u, 0, 0});
  return points;
}

std::vector<Station> Passes::centre_line(int a, double z) const {
  const double length = spec_.path.length;
  const SlotEnd& ea = spec_.end[a];
  const SlotEnd& eb = spec_.end[1 - a];
  std::vector<Station> line;
  if (ea.kind == SlotEnd::Kind::Woodruff) {
    const auto arc = woodruff(ea, z);
    for (auto it = arc.rbegin(); it != arc.rend(); ++it) line.push_back({-it->u, 0, it->z});
  } else {
    line.push_back({-extension(ea), 0, z});
  }
  if (eb.kind == SlotEnd::Kind::Woodruff) {
    for (const Station& p : woodruff(eb, z)) line.push_back({length + p.u, 0, p.z});
  } else {
    line.push_back({length + extension(eb), 0, z});
  }
  return line;
}

std::vector<RingMove> Passes::ring(int a, double e, double z) const {
  const double length = spec_.path.length;
  const SlotEnd& ea = spec_.end[a];
  const SlotEnd& eb = spec_.end[1 - a];
  const bool round_a = ea.kind == SlotEnd::Kind::Radiused;
  const bool round_b = eb.kind == SlotEnd::Kind::Radiused;
  const double ua = -extension(ea);
  const double ub = length + extension(eb);
  // Counter-clockwise from the far end's middle.
  std::vector<RingMove> moves;
  if (round_b)
    moves.push_back({{length, e, z}, true, length, 0});
  else
    moves.push_back({{ub, e, z}});
  moves.push_back({{round_a ? 0 : ua, e, z}});
  if (round_a)
    moves.push_back({{0, -e, z}, true, 0, 0});
  else
    moves.push_back({{ua, -e, z}});
  moves.push_back({{round_b ? length : ub, -e, z}});
  if (round_b)
    moves.push_back({{length + e, 0, z}, true, length, 0});
  else
    moves.push_back({{ub, 0, z}});
  return moves;
}

std::vector<SlotPass> Passes::level_passes(double level) const {
  // Passes deeper than the level run at the level: spread evenly over the width they span
  // there, at most the stepover apart; the others as they are.
  std::vector<SlotPass> out;
  double widest = -1;
  for (const SlotPass& p : spec_.passes)
    if (-p.depth < level - kEps) widest = std::max(widest, p.offset);
  if (widest >= 0) {
    const double step = spec_.stepover > 0 ? spec_.stepover : spec_.tool_radius;
    const auto n = static_cast<std::size_t>(std::ceil(widest / step - 1e-9));
    for (std::size_t k = 0; k <= n; ++k)
      out.push_back(
          {n == 0 ? 0 : widest * static_cast<double>(k) / static_cast<double>(n), -level});
  }
  for (const SlotPass& p : spec_.passes)
    if (-p.depth >= level - kEps && p.offset > widest) out.push_back(p);
  return out;
}

void Passes::plunge_note() {
  if (noted_ || spec_.entry.strategy) return;
  noted_ = true;
  draft_.report().note(spec_.feature,
                       spec_.tool.name() + " machines " + spec_.feature.name() +
                           " along its course of travel; it enters along its axis, as "
                           "there is no room for a helix");
}

// From above the pass's first station (at from_z) down to it: in the air beyond an open or
// woodruff end, or into the material at a radiused end as the approach strategy says.
void Passes::descend(int a, Station start, double from_z, bool in_material, bool first) {
  if (first) {
    const Vec3 above = at(a, {start.u, start.v, std::max(retract_, clear_)});
    draft_.rapid(above);
    if (retract_ > clear_) draft_.rapid(at(a, {start.u, start.v, clear_}));
  }
  if (!in_material) {
    // Already there when the last level ended at this end's exit (a woodruff end).
    const Vec3 to = at(a, start);
    if (first || (draft_.here() - to).length() > kEps) draft_.feed(to);
    return;
  }
  if (spec_.entry.kind == Entry::Kind::Plunge) plunge_note();
  const Vec3 p0 = at(a, {start.u, start.v, from_z});
  const Vec3 inward = at(a, {1, 0, 0}) - at(a, {0, 0, 0});
  double length = spec_.path.length;
  if (spec_.entry.width > 0) length = std::min(length, spec_.entry.width);
  enter(draft_, spec_.entry, p0, inward, inward, length, spec_.ccw, from_z, start.z);
}

void Passes::leave_end(int a, Station here) {
  const double top = std::max(retract_, clear_);
  // At a radiused end the tool is in the material: the retract strategy (straight up when
  // unset); elsewhere it is out of the slot already.
  const bool in_material = here.z < 0 && spec_.end[a].kind == SlotEnd::Kind::Radiused &&
                           spec_.exit.kind != Entry::Kind::Plunge;
  if (in_material) {
    const Vec3 inward = at(a, {1, 0, 0}) - at(a, {0, 0, 0});
    double length = spec_.path.length;
    if (spec_.exit.width > 0) length = std::min(length, spec_.exit.width);
    leave(draft_, spec_.exit, at(a, here), inward, inward, length, spec_.ccw, here.z, clear_);
  }
  const Vec3 end = draft_.here();
  if (end.z < top - kEps) draft_.rapid({end.x, end.y, top});
}

bool Passes::line() {
  const bool single = spec_.passes.size() == 1;
  // Start at an end where the tool comes in from the air when there is one.
  const auto air = [&](int k) { return spec_.end[k].kind != SlotEnd::Kind::Radiused; };
  int a = air(1) && !air(0) ? 1 : 0;
  double from_z = clear_;
  bool first = true;
  for (std::size_t index = 0; index < spec_.levels.size(); ++index) {
    const double level = spec_.levels[index];
    if (single) {
      const std::vector<Station> stations =
          centre_line(a, -spec_.passes.front().depth > level ? -spec_.passes.front().depth : level);
      descend(a, stations.front(), from_z, !air(a), first);
      for (std::size_t k = 1; k < stations.size(); ++k) draft_.feed(at(a, stations[k]));
      from_z = stations.back().z;
      first = false;
      if (draft_.too_many()) return draft_.limit_reached();
      if (index + 1 < spec_.levels.size()) {
        // The next level goes back from where this one ended.
        a = 1 - a;
        if (air(a)) from_z = clear_;
      } else {
        leave_end(1 - a, {0, 0, stations.back().z});
      }
      continue;
    }
    // Stepped: the centre line from end a, then rings about it, from the centre outwards;
    // between levels up and back over end a.
    const std::vector<SlotPass> passes = level_passes(level);
    const std::vector<Station> centre = centre_line(a, -passes.front().depth);
    if (!first) {
      const Vec3 here = draft_.here();
      draft_.rapid({here.x, here.y, clear_});
      draft_.rapid(at(a, {centre.front().u, 0, clear_}));
      if (!air(a)) draft_.feed(at(a, {centre.front().u, 0, from_z}));
    }
    descend(a, centre.front(), air(a) ? clear_ : from_z, !air(a), first);
    for (std::size_t k = 1; k < centre.size(); ++k) draft_.feed(at(a, centre[k]));
    for (std::size_t j = 1; j < passes.size(); ++j) {
      const std::vector<RingMove> moves = ring(a, passes[j].offset, -passes[j].depth);
      draft_.feed(at(a, moves.back().to));  // the ring's start, from the previous ring's
      const auto play = [&](Station to, const RingMove& m, int turns) {
        if (m.arc)
          draft_.arc(at(a, to), at(a, {m.cu, m.cv, to.z}), turns);
        else
          draft_.feed(at(a, to));
      };
      if (spec_.ccw) {
        for (const RingMove& m : moves) play(m.to, m, 1);
      } else {
        for (std::size_t i = moves.size(); i-- > 0;)
          play(i == 0 ? moves.back().to : moves[i - 1].to, moves[i], -1);
      }
      if (draft_.too_many()) return draft_.limit_reached();
    }
    from_z = -passes.front().depth;
    first = false;
  }
  if (!single) {
    // A retract strategy other than along the axis (PLUNGE_TOOLAXIS reads as Plunge).
    if (spec_.exit.strategy && spec_.exit.kind != Entry::Kind::Plunge)
      draft_.report().note(spec_.exit.strategy,
                           spec_.exit.strategy.name() + ": the last pass of " +
                               spec_.feature.name() +
                               " ends at the top of its wall; the tool leaves along its axis");
    const Vec3 end = draft_.here();
    draft_.rapid({end.x, end.y, std::max(retract_, clear_)});
  }
  return true;
}

Vec3 Passes::on_circle(double theta, double z) const {
  const double radius = spec_.path.radius;
  return {radius * std::cos(theta), radius * std::sin(theta), z};
}

bool Passes::around(double& theta, const Slope& slope, const std::function<void(double)>& run) {
  double from_z = clear_;
  bool first = true;
  for (const double level : spec_.levels) {
    const double z = std::max(level, -spec_.passes.front().depth);
    if (first) {
      draft_.rapid(on_circle(theta, std::max(retract_, clear_)));
      if (retract_ > clear_) draft_.rapid(on_circle(theta, clear_));
    }
    if (spec_.entry.kind == Entry::Kind::Plunge) {
      plunge_note();
      draft_.feed(on_circle(theta, z));
    } else {
      slope(spec_.entry, from_z, z);
    }
    run(z);
    from_z = z;
    first = false;
    if (draft_.too_many()) return draft_.limit_reached();
  }
  if (spec_.exit.kind != Entry::Kind::Plunge) slope(spec_.exit, from_z, clear_);
  const Vec3 end = draft_.here();
  if (end.z < std::max(retract_, clear_) - kEps)
    draft_.rapid({end.x, end.y, std::max(retract_, clear_)});
  return true;
}

// Along an arc of the circle between radiused ends, back and forth between levels.
bool Passes::arc() {
  const double radius = spec_.path.radius;
  const double sweep = spec_.path.sweep;
  const auto turn = [&](double from, double to) { return to > from ? 1 : -1; };
  double theta = 0;
  // Ramps and retracts go back and forth along the arc from the end the tool is at.
  const auto ramp = [&](const Entry& e, double from_z, double to_z) {
    double length = spec_.path.length;
    if (e.width > 0) length = std::min(length, e.width);
    const double span =
        length / radius * (theta == 0 ? (sweep > 0 ? 1 : -1) : (sweep > 0 ? -1 : 1));
    const double change = length * std::tan(e.angle);
    double z = from_z;
    double here = theta;
    bool out = true;
    const bool down = to_z < from_z;
    while (down ? z > to_z + kEps : z < to_z - kEps) {
      const double share = std::min(1.0, std::abs(to_z - z) / change);
      z = down ? std::max(to_z, z - change) : std::min(to_z, z + change);
      const double next = out ? here + span * share : here - span * share;
      draft_.arc(on_circle(next, z), {0, 0, z}, turn(here, next));
      here = next;
      out = !out;
      if (draft_.too_many()) return;
    }
    if (down && std::abs(here - theta) > kEps)
      draft_.arc(on_circle(theta, to_z), {0, 0, to_z}, turn(here, theta));
  };
  return around(theta, ramp, [&](double z) {
    const double other = theta == 0 ? sweep : 0;
    draft_.arc(on_circle(other, z), {0, 0, z}, turn(theta, other));
    theta = other;
  });
}

// Round the closed circle at each level; the ramps go down (and up) along it.
bool Passes::circle() {
  const double radius = spec_.path.radius;
  const int dir = spec_.ccw ? 1 : -1;
  double theta = 0;
  // A helical run along the circle from `from_z` to `to_z` at the strategy's angle: whole turns
  // first (one arc), then what is left of a turn.
  const auto helical = [&](const Entry& e, double from_z, double to_z) {
    const double angle = std::abs(to_z - from_z) / (radius * std::tan(e.angle));
    const double whole = std::floor(angle / (2 * std::numbers::pi) + 1e-12);
    double z = from_z;
    if (whole >= 1) {
      z = from_z + (to_z - from_z) * whole * 2 * std::numbers::pi / angle;
      draft_.arc(on_circle(theta, z), {0, 0, z}, dir * static_cast<int>(whole));
    }
    const double rest = angle - whole * 2 * std::numbers::pi;
    if (rest > 1e-9) {
      theta += dir * rest;
      draft_.arc(on_circle(theta, to_z), {0, 0, to_z}, dir);
    }
  };
  return around(theta, helical, [&](double z) {
    draft_.arc(on_circle(theta, z), {0, 0, z}, dir);  // the whole circle
  });
}

bool Passes::run() {
  clear_ = options_.clearance;
  retract_ = spec_.retract_plane.value_or(clear_);
  double deepest = 0;
  for (const SlotPass& p : spec_.passes) deepest = std::max(deepest, p.depth);
  // Ramps: their legs must fit the path, and the number of legs must stay bounded.
  for (const Entry* e : {&spec_.entry, &spec_.exit}) {
    if (e->kind != Entry::Kind::Ramp) continue;
    double length = spec_.path.kind == SlotPath::Kind::Circle
                        ? 2 * std::numbers::pi * spec_.path.radius
                        : spec_.path.length;
    if (e->width > 0) length = std::min(length, e->width);
    if ((clear_ + deepest) / (length * std::tan(e->angle)) >
        static_cast<double>(options_.max_moves))
      return draft_.limit_reached();
  }
  const double moves_per_level =
      static_cast<double>(spec_.passes.size()) * 8 + 2 * (deepest / options_.profile_tolerance);
  if (moves_per_level * static_cast<double>(spec_.levels.size()) >
      static_cast<double>(options_.max_moves))
    return draft_.limit_reached();
  switch (spec_.path.kind) {
    case SlotPath::Kind::Line:
      return line();
    case SlotPath::Kind::Arc:
      return arc();
    case SlotPath::Kind::Circle:
      return circle();
  }
  return false;
}

}  // namespace

bool plan_form_slot(const FormSlotSpec& spec, Draft& draft) {
  Passes passes(spec, draft);
  return passes.run();
}

}  // namespace ncpost::stepnc::features
