#include "model.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "cavity.hpp"
#include "contour.hpp"

namespace ncpost::verify::detail {

const p21::Instance* Reader::ref(const p21::Instance& i, std::string_view name) const {
  const auto v = get(i, name);
  if (!v || !v->is_reference()) return nullptr;
  return m_.find(v->id());
}

std::optional<double> Reader::number(const p21::Instance& i, std::string_view name) const {
  auto v = get(i, name);
  if (!v) return std::nullopt;
  if (v->kind() == p21::ValueKind::Typed) v = m_.typed_child(*v);
  if (!v->is_number()) return std::nullopt;
  const double d = m_.as_real(*v);
  if (!std::isfinite(d)) return std::nullopt;
  return d;
}

std::optional<double> Reader::length(const p21::Instance& i, std::string_view name) const {
  if (auto n = number(i, name)) return n;
  const p21::Instance* target = ref(i, name);
  if (target == nullptr) return std::nullopt;
  if (is_a(*target, "toleranced_length_measure")) return number(*target, "theoretical_size");
  if (is_a(*target, "numeric_parameter")) return number(*target, "its_parameter_value");
  return std::nullopt;
}

std::optional<Vec3> Reader::point(const p21::Instance* p) const {
  if (p == nullptr || !is_a(*p, "cartesian_point")) return std::nullopt;
  const auto c = get(*p, "coordinates");
  if (!c || !c->is_list() || c->count() < 2 || c->count() > 3) return std::nullopt;
  const auto items = m_.items(*c);
  double xyz[3] = {0, 0, 0};
  for (std::size_t k = 0; k < items.size(); ++k) {
    const p21::Value v =
        items[k].kind() == p21::ValueKind::Typed ? m_.typed_child(items[k]) : items[k];
    if (!v.is_number()) return std::nullopt;
    xyz[k] = m_.as_real(v);
    if (!std::isfinite(xyz[k])) return std::nullopt;
  }
  return Vec3{xyz[0], xyz[1], xyz[2]};
}

std::optional<Vec3> Reader::direction(const p21::Instance* d) const {
  if (d == nullptr || !is_a(*d, "direction")) return std::nullopt;
  const auto c = get(*d, "direction_ratios");
  if (!c || !c->is_list() || c->count() < 2 || c->count() > 3) return std::nullopt;
  const auto items = m_.items(*c);
  Vec3 v{m_.as_real(items[0]), m_.as_real(items[1]), items.size() > 2 ? m_.as_real(items[2]) : 0};
  const double l = v.length();
  if (!std::isfinite(l) || l < 1e-12) return std::nullopt;
  return v * (1 / l);
}

std::optional<Frame> Reader::placement(const p21::Instance* a) const {
  if (a == nullptr || !is_a(*a, "axis2_placement_3d")) return std::nullopt;
  const auto origin = point(ref(*a, "location"));
  if (!origin) return std::nullopt;
  Vec3 z{0, 0, 1};
  Vec3 x{1, 0, 0};
  if (const p21::Instance* axis = ref(*a, "axis")) {
    const auto d = direction(axis);
    if (!d) return std::nullopt;
    z = *d;
  }
  if (const p21::Instance* rd = ref(*a, "ref_direction")) {
    const auto d = direction(rd);
    if (!d) return std::nullopt;
    x = *d;
  } else if (std::abs(z.dot(x)) > 1 - 1e-9) {
    x = {0, 0, 1};
  }
  const Vec3 projected = x - z * x.dot(z);
  if (projected.length() < 1e-9) return std::nullopt;
  Frame f;
  f.origin = *origin;
  f.z = z;
  f.x = projected * (1 / projected.length());
  f.y = f.z.cross(f.x);
  return f;
}

std::string Reader::name(const p21::Instance& i) const {
  const auto v = get(i, "its_id");
  return v && v->kind() == p21::ValueKind::String ? m_.as_string(*v) : std::string();
}

std::string Reader::describe(const p21::Instance& i) const {
  const std::string n = name(i);
  return "#" + std::to_string(i.id) + " " + type(i) + (n.empty() ? "" : " '" + n + "'");
}

Tool read_tool(const Reader& r, const p21::Instance* tool,
               const stepnc::InterpretOptions& options) {
  Tool t;
  if (tool == nullptr) return t;
  const p21::Instance* body = r.ref(*tool, "its_tool_body");
  if (body != nullptr) {
    t.body = r.type(*body);
    t.ball = r.is_a(*body, "ball_endmill");
    t.hole_making = r.is_a(*body, "drill") || r.is_a(*body, "center_drill") ||
                    r.is_a(*body, "reamer") || r.is_a(*body, "tap") ||
                    r.is_a(*body, "boring_tool") || r.is_a(*body, "countersink") ||
                    r.is_a(*body, "counterbore");
    t.centre_cutting = !(r.is_a(*body, "facemill") || r.is_a(*body, "side_mill") ||
                         r.is_a(*body, "t_slot_mill") || r.is_a(*body, "woodruff_keyseat_mill") ||
                         r.is_a(*body, "dovetail_mill") || r.is_a(*body, "thread_mill"));
    if (const p21::Instance* dim = r.ref(*body, "dimension")) {
      if (const auto d = r.number(*dim, "diameter"); d && *d > 0) {
        t.radius = *d / 2;
        t.known = true;
      }
      // A bull-nose whose edge radius is the whole radius is a ball.
      const auto e = r.number(*dim, "edge_radius");
      if (e && t.known && *e >= t.radius - 1e-9) t.ball = true;
      if (e && *e > 0) t.shape.corner = *e;
      // A point: tool_tip_half_angle as NIST reads it (below 90 degrees the angle between the
      // cutting edge and the plane normal to the axis, from 90 on the whole point angle).
      if (const auto a = r.number(*dim, "tool_tip_half_angle"); a && *a > 0 && *a < 180 && !t.ball)
        t.shape.cone = (*a < 90 ? 90 - *a : *a / 2) * std::numbers::pi / 180;
    }
    t.shape.radius = t.radius;
    if (t.ball) t.shape.corner = t.radius;
    t.shape.corner = std::min(t.shape.corner, t.radius);
  }
  if (!t.known && options.tools) {
    if (const auto* entry = options.tools->find(r.name(*tool)); entry && entry->diameter > 0) {
      t.radius = entry->diameter / 2;
      t.known = true;
    }
  }
  return t;
}

Operation read_operation(const Reader& r, const p21::Instance* operation) {
  Operation o;
  o.instance = operation;
  if (operation == nullptr) return o;
  o.hole_making = r.is_a(*operation, "drilling_type_operation");
  o.spot = r.is_a(*operation, "center_drilling") || r.is_a(*operation, "counter_sinking");
  if (const auto s = r.number(*operation, "allowance_side")) o.side_allowance = *s;
  if (const auto b = r.number(*operation, "allowance_bottom")) {
    o.bottom_allowance = *b;
    o.has_bottom_allowance = true;
  }
  if (const p21::Instance* a = r.ref(*operation, "approach")) {
    o.approach_instance = a;
    if (r.is_a(*a, "plunge_toolaxis")) {
      o.approach = Operation::Approach::ToolAxis;
    } else if (r.is_a(*a, "plunge_ramp")) {
      o.approach = Operation::Approach::Ramp;
    } else if (r.is_a(*a, "plunge_helix")) {
      o.approach = Operation::Approach::Helix;
    } else if (r.is_a(*a, "plunge_zigzag")) {
      o.approach = Operation::Approach::Zigzag;
    }
    if (o.approach != Operation::Approach::None && o.approach != Operation::Approach::ToolAxis)
      o.approach_angle = r.number(*a, "angle");
  }
  return o;
}

namespace {

// A closed profile in the feature's xy plane (profiles may have their own placement).
bool closed_profile(const Reader& r, const p21::Instance& profile, Feature& f,
                    double corner_radius) {
  Frame local;
  if (const p21::Instance* p = r.ref(profile, "placement")) {
    const auto frame = r.placement(p);
    if (!frame) {
      f.reason = "its profile placement cannot be read";
      return false;
    }
    local = *frame;
  }
  const Vec2 origin = local.origin.xy();
  const Vec2 x_axis = local.x.xy();
  if (r.is_a(profile, "rectangular_closed_profile")) {
    const auto width = r.length(profile, "profile_width");
    const auto length = r.length(profile, "profile_length");
    if (!width || !length) {
      f.reason = "its rectangle has no width or length";
      return false;
    }
    f.region = Region::rectangle(origin, x_axis, *length, *width, corner_radius);
    return true;
  }
  if (r.is_a(profile, "circular_closed_profile")) {
    const auto d = r.length(profile, "diameter");
    if (!d) {
      f.reason = "its circle has no diameter";
      return false;
    }
    f.region = Region::circle(origin, *d / 2);
    return true;
  }
  std::vector<Piece2> chain;
  if (r.is_a(profile, "ngon_closed_profile")) {
    const auto d = r.length(profile, "diameter");
    const auto n = r.number(profile, "number_of_sides");
    const auto circumscribed = r.get(profile, "circumscribed_or_across_flats");
    if (!d || !n || *n < 3 || *n > 100000) {
      f.reason = "its n-gon has no diameter or fewer than 3 (or more than 100000) sides";
      return false;
    }
    const int sides = static_cast<int>(*n);
    const bool across_flats = circumscribed && r.model().as_logical(*circumscribed) &&
                              *r.model().as_logical(*circumscribed) == p21::Logical::False;
    const double vertex = across_flats ? *d / 2 / std::cos(std::numbers::pi / sides) : *d / 2;
    const double base = std::atan2(x_axis.y, x_axis.x);
    const auto at = [&](int k) {
      const double a = base + kTwoPi * (k % sides) / sides;
      return origin + Vec2{std::cos(a), std::sin(a)} * vertex;
    };
    for (int k = 0; k < sides; ++k) chain.push_back({false, at(k), at(k + 1), {}, 0, 0});
  } else if (r.is_a(profile, "general_closed_profile")) {
    const p21::Instance* curve = r.ref(profile, "closed_profile_shape");
    if (curve == nullptr) {
      f.reason = "its general closed profile has no curve";
      return false;
    }
    auto read = read_curve(r, *curve, local, f.reason);
    if (!read) return false;
    chain = std::move(*read);
    if ((chain.back().b - chain.front().a).length() > 1e-3) {
      // Tolerant, a polyline that does not repeat its first point is closed by a line back to
      // it (INTEROP-005); strict, the profile is not closed.
      if (!r.tolerant() || !r.is_a(*curve, "polyline")) {
        f.reason = "its general closed profile is not closed";
        return false;
      }
      chain.push_back({false, chain.back().b, chain.front().a, {}, 0, 0});
    }
    chain.back().b = chain.front().a;
  }
  if (!chain.empty()) {
    make_counter_clockwise(chain);
    f.region = region_of(with_fillets(chain, corner_radius, true));
    return true;
  }
  f.reason = "its profile " + r.type(profile) + " is not supported";
  return false;
}

// An OPEN_POCKET: its open_boundary (a GENERAL_PROFILE) is the walls; the pocket is open along
// the straight line between the walls' ends (wall_boundary is for information only, ISO
// 14649-10). Beyond that line is air; the line's continuation past the walls' ends is the part's
// face, which the tool must not cut either.
bool open_pocket_walls(const Reader& r, const p21::Instance& feature, Feature& f,
                       double corner_radius) {
  const p21::Instance* boundary = r.ref(feature, "open_boundary");
  if (boundary == nullptr || !r.is_a(*boundary, "general_profile")) {
    f.reason = "its open_boundary is not a GENERAL_PROFILE";
    return false;
  }
  Frame local;
  if (const p21::Instance* p = r.ref(*boundary, "placement")) {
    const auto frame = r.placement(p);
    if (!frame) {
      f.reason = "its profile placement cannot be read";
      return false;
    }
    local = *frame;
  }
  const p21::Instance* curve = r.ref(*boundary, "its_profile");
  if (curve == nullptr) {
    f.reason = "its open profile has no curve";
    return false;
  }
  auto walls = read_curve(r, *curve, local, f.reason);
  if (!walls) return false;
  if ((walls->back().b - walls->front().a).length() < 1e-3) {
    f.reason = "its open profile is closed";
    return false;
  }
  make_counter_clockwise(*walls);
  const auto rounded = with_fillets(*walls, corner_radius, false);
  constexpr double kFar = 1000;
  f.region = open_walls_region(rounded, kFar);
  f.floor_region = region_of(rounded);
  return true;
}

// Tolerant, a through hole without a depth plane goes down to the lowest corner of its
// workpiece's bounding BLOCK (the workpiece's, else its raw piece's): the floor relative to the
// feature's top (INTEROP-003), checked here from the block's corners.
std::optional<double> through_floor(const Reader& r, const p21::Instance& feature) {
  const p21::Instance* bottom = r.ref(feature, "bottom_condition");
  if (!r.tolerant() || bottom == nullptr || !r.is_a(*bottom, "through_bottom_condition"))
    return std::nullopt;
  const p21::Instance* workpiece = r.ref(feature, "its_workpiece");
  const p21::Instance* block = workpiece ? r.ref(*workpiece, "its_bounding_geometry") : nullptr;
  if (block == nullptr && workpiece != nullptr) {
    if (const p21::Instance* raw = r.ref(*workpiece, "its_rawpiece"))
      block = r.ref(*raw, "its_bounding_geometry");
  }
  if (block == nullptr || !r.is_a(*block, "block")) return std::nullopt;
  const auto corner = r.placement(r.ref(*block, "position"));
  const auto top = r.placement(r.ref(feature, "feature_placement"));
  const auto x = r.number(*block, "x");
  const auto y = r.number(*block, "y");
  const auto z = r.number(*block, "z");
  if (!corner || !top || !x || !y || !z) return std::nullopt;
  double lowest = corner->origin.z;
  for (const double i : {0.0, *x})
    for (const double j : {0.0, *y})
      for (const double k : {0.0, *z}) lowest = std::min(lowest, corner->point({i, j, k}).z);
  if (!(lowest < top->origin.z)) return std::nullopt;
  return lowest - top->origin.z;
}

double depth_of(const Reader& r, const p21::Instance& feature, bool& ok) {
  ok = false;
  const p21::Instance* plane = r.ref(feature, "depth");
  if (plane == nullptr) {
    const auto through = through_floor(r, feature);
    ok = through.has_value();
    return through.value_or(0);
  }
  const auto frame = r.placement(r.ref(*plane, "position"));
  if (!frame) return 0;
  ok = true;
  return frame->origin.z;
}

// A straight SLOT: its centre line from the placement along the course of travel, its width from
// the swept U profile; each end radiused (a half circle about the end of the centre line), flat
// (a wall across the end) or open (no wall: the tool may leave the slot there).
bool straight_slot(const Reader& r, const p21::Instance& feature, Feature& f) {
  const p21::Instance* travel = r.ref(feature, "course_of_travel");
  if (travel == nullptr || !r.is_a(*travel, "linear_path")) {
    f.reason = "its course_of_travel is not a LINEAR_PATH";
    return false;
  }
  const auto length = r.length(*travel, "distance");
  const auto direction = r.direction(r.ref(*travel, "its_direction"));
  const p21::Instance* shape = r.ref(feature, "swept_shape");
  const bool u_shape =
      shape && (r.is_a(*shape, "square_u_profile") || r.is_a(*shape, "rounded_u_profile"));
  const auto width = u_shape ? r.length(*shape, "width") : std::nullopt;
  if (!length || !direction || !width || std::abs(direction->z) > 1e-9) {
    f.reason = u_shape ? "its course_of_travel or width cannot be read"
                       : "its swept shape is not a SQUARE_U_PROFILE or ROUNDED_U_PROFILE";
    return false;
  }
  enum class End { Radiused, Flat, Open };
  End ends[2] = {End::Flat, End::Flat};
  double corner[2][2] = {{0, 0}, {0, 0}};  // per end: corner_radius1 (-n side), corner_radius2
  if (const auto list = r.get(feature, "end_conditions"); list && list->is_list()) {
    const auto items = r.model().items(*list);
    for (std::size_t k = 0; k < items.size() && k < 2; ++k) {
      const p21::Instance* e = items[k].is_reference() ? r.model().find(items[k].id()) : nullptr;
      if (e == nullptr) continue;
      if (r.is_a(*e, "radiused_slot_end_type")) {
        ends[k] = End::Radiused;
      } else if (r.is_a(*e, "open_slot_end_type")) {
        ends[k] = End::Open;
      } else if (r.is_a(*e, "flat_slot_end_type")) {
        ends[k] = End::Flat;
        corner[k][0] = r.length(*e, "corner_radius1").value_or(0);
        corner[k][1] = r.length(*e, "corner_radius2").value_or(0);
      } else {
        f.reason = "its end type " + r.type(*e) + " is not supported";
        return false;
      }
    }
    // One end type for a slot with two ends: both ends are of that type.
    if (items.size() == 1) {
      ends[1] = ends[0];
      corner[1][0] = corner[0][0];
      corner[1][1] = corner[0][1];
    }
  }
  if (r.is_a(*shape, "rounded_u_profile"))
    f.notes.push_back("its rounded-U floor is checked as flat at the depth");
  const Vec2 d = Vec2{direction->x, direction->y} * (1 / Vec2{direction->x, direction->y}.length());
  const Vec2 n{-d.y, d.x};
  const double h = *width / 2;
  for (auto& c : corner)
    for (double& v : c) v = std::clamp(v, 0.0, h);
  // An open end's walls run on far past it.
  constexpr double kOpen = 1000;
  const auto outline = [&](bool floor) {
    Region region;
    Vec2 last{};
    bool started = false;
    const auto line_to = [&](Vec2 q) {
      if (started && (q - last).length() > 1e-12) region.add_line(last, q);
      region.add_polygon_point(q);
      last = q;
      started = true;
    };
    const auto arc = [&](Vec2 centre, double radius, double from, double sweep) {
      if (radius <= 0) return;
      region.add_arc(centre, radius, from, sweep);
      for (int k = 1; k <= 32; ++k) {
        const double t = from + sweep * k / 32;
        region.add_polygon_point(centre + Vec2{std::cos(t), std::sin(t)} * radius);
      }
      last = centre + Vec2{std::cos(from + sweep), std::sin(from + sweep)} * radius;
    };
    // A 90-degree convex corner at v between the directions in and out, rounded with c.
    const auto round_corner = [&](Vec2 v, Vec2 in, Vec2 out, double c) {
      line_to(v - in * c);
      const Vec2 centre = v - in * c + out * c;
      arc(centre, c, std::atan2(-out.y, -out.x), kTwoPi / 4);
    };
    const Vec2 p0{0, 0};
    const Vec2 p1 = d * *length;
    const bool open0 = ends[0] == End::Open;
    const bool open1 = ends[1] == End::Open;
    const double s0 = open0 && !floor ? -kOpen : 0;
    const double s1 = open1 && !floor ? *length + kOpen : *length;
    const Vec2 a0 = d * s0 - n * h;
    const Vec2 a1 = d * s1 - n * h;
    const Vec2 b1 = d * s1 + n * h;
    const Vec2 b0 = d * s0 + n * h;
    const double base = std::atan2(d.y, d.x);
    const bool flat0 = ends[0] == End::Flat;
    const bool flat1 = ends[1] == End::Flat;
    line_to(a0 + d * (flat0 ? corner[0][0] : 0));
    if (ends[1] == End::Radiused) {
      line_to(a1);
      arc(p1, h, base - kTwoPi / 4, kTwoPi / 2);
    } else {
      round_corner(a1, d, n, flat1 ? corner[1][0] : 0);
      round_corner(b1, n, d * -1, flat1 ? corner[1][1] : 0);
    }
    if (ends[0] == End::Radiused) {
      line_to(b0);
      arc(p0, h, base + kTwoPi / 4, kTwoPi / 2);
    } else {
      round_corner(b0, d * -1, n * -1, flat0 ? corner[0][1] : 0);
      round_corner(a0, n * -1, d, flat0 ? corner[0][0] : 0);
    }
    line_to(a0 + d * (flat0 ? corner[0][0] : 0));
    return region;
  };
  f.region = outline(false);
  if (ends[0] == End::Open || ends[1] == End::Open) f.floor_region = outline(true);
  return true;
}

// A course of travel with a placement of its own (ISO 14649-10 travel_path.placement): the slot
// is read in that placement, which must lie in the feature's xy plane (turned about its z, moved
// along it).
bool place_travel(const Reader& r, const p21::Instance& feature, Feature& f) {
  const p21::Instance* travel = r.ref(feature, "course_of_travel");
  const p21::Instance* placed = travel ? r.ref(*travel, "placement") : nullptr;
  if (placed == nullptr) return true;
  const auto frame = r.placement(placed);
  if (!frame) {
    f.reason = "its course of travel's placement cannot be read";
    return false;
  }
  if (std::abs(frame->z.z - 1) > 1e-9 || std::abs(frame->origin.z) > 1e-9) {
    f.reason = "its course of travel is placed out of the slot's plane";
    return false;
  }
  f.frame = f.frame.then(*frame);
  return true;
}

// A straight slot with vertical walls meeting a flat floor in sharp corners and radiused, flat
// or open ends: the outline model above. Every other slot is a profiled one (cavity.hpp).
bool plain_slot(const Reader& r, const p21::Instance& feature) {
  const p21::Instance* travel = r.ref(feature, "course_of_travel");
  const p21::Instance* shape = r.ref(feature, "swept_shape");
  if (travel == nullptr || shape == nullptr || !r.is_a(*travel, "linear_path") ||
      !r.is_a(*shape, "square_u_profile"))
    return false;
  for (const char* radius : {"first_radius", "second_radius"})
    if (r.length(*shape, radius).value_or(0) > 0) return false;
  const auto list = r.get(feature, "end_conditions");
  if (!list || !list->is_list()) return true;
  for (p21::Value v : r.model().items(*list)) {
    const p21::Instance* e = v.is_reference() ? r.model().find(v.id()) : nullptr;
    if (e != nullptr && (r.is_a(*e, "woodruff_slot_end_type") || r.is_a(*e, "loop_slot_end_type")))
      return false;
  }
  return true;
}

// A ROUND_HOLE with a taper, as a cavity about its axis (f has its radius, floor, through and
// cone depth read already).
Feature& tapered_hole(const Reader& r, const p21::Instance& taper, Feature& f) {
  double bottom_radius = 0;
  if (r.is_a(taper, "diameter_taper")) {
    bottom_radius = r.length(taper, "final_diameter").value_or(0) / 2;
  } else if (const auto angle = r.number(taper, "angle");
             angle && r.is_a(taper, "angle_taper") && std::abs(*angle) < 90) {
    bottom_radius = f.hole_radius + f.floor * std::tan(*angle * std::numbers::pi / 180);
  }
  if (!(bottom_radius > 0) || !(f.floor < 0)) {
    f.reason = "its change_in_diameter cannot be read";
    return f;
  }
  // The cone of a conical bottom has the taper's final radius.
  const double cone = f.hole_radius > 0 ? f.cone_depth * bottom_radius / f.hole_radius : 0;
  auto cavity = std::make_shared<Cavity>();
  cavity->taper(f.hole_radius, bottom_radius, -f.floor, f.through ? 0 : cone, f.through);
  cavity->point({0, 0});
  f.kind = Feature::Kind::Profiled;
  f.cavity = std::move(cavity);
  f.coverage = false;
  f.notes.push_back("its " + r.type(taper) +
                    " is checked as the cone of its wall; its floor is not measured for "
                    "coverage");
  f.checked = true;
  return f;
}

// A ROUND_HOLE with a SPHERICAL_HOLE_BOTTOM, as a cavity about its axis: the wall, then the
// sphere whose lowest point is on the depth plane (f has its radius and floor read already).
Feature& spherical_hole(const Reader& r, const p21::Instance& bottom, Feature& f) {
  const double sphere = r.length(bottom, "radius").value_or(0);
  const double depth = -f.floor;
  if (!(sphere >= f.hole_radius) || !(depth > 0) ||
      sphere - std::sqrt(sphere * sphere - f.hole_radius * f.hole_radius) > depth) {
    f.reason =
        "its SPHERICAL_HOLE_BOTTOM's radius is narrower than the hole or its sphere "
        "reaches above the hole's top";
    return f;
  }
  auto cavity = std::make_shared<Cavity>();
  cavity->spherical_hole(f.hole_radius, sphere, depth);
  cavity->point({0, 0});
  f.kind = Feature::Kind::Profiled;
  f.cavity = std::move(cavity);
  if (sphere > f.hole_radius + 1e-9) {
    // The coverage raster disagrees with the tool in the edge where such a sphere meets the
    // wall at an angle (a ball leaves it; the raster's reach goes further): not measured yet.
    f.coverage = false;
    f.notes.push_back("its " + r.type(bottom) +
                      " meets the wall at an angle; its surface is not measured for coverage");
  }
  f.checked = true;
  return f;
}

}  // namespace

Feature read_feature(const Reader& r, const p21::Instance& feature, const Frame& workpiece_frame) {
  Feature f;
  f.instance = &feature;
  f.type = r.type(feature);
  f.frame = workpiece_frame;
  const auto placement = r.placement(r.ref(feature, "feature_placement"));
  if (placement) f.frame = workpiece_frame.then(*placement);
  const bool face = r.is_a(feature, "planar_face");
  const bool closed_pocket = r.is_a(feature, "closed_pocket");
  const bool open_pocket = r.is_a(feature, "open_pocket");
  const bool outside = r.is_a(feature, "general_outside_profile");
  const bool hole = r.is_a(feature, "round_hole");
  const bool slot = r.is_a(feature, "slot");
  const bool step = r.is_a(feature, "step");
  const bool thread = r.is_a(feature, "thread");
  if (!face && !closed_pocket && !open_pocket && !outside && !hole && !slot && !step && !thread) {
    f.reason = "feature kind " + f.type + " is not checked";
    return f;
  }
  if (!placement) {
    f.reason = "its feature_placement cannot be read";
    return f;
  }
  if (std::abs(f.frame.z.z - 1) > 1e-9) {
    f.reason = "its axis is not the machine's +Z (a tilted feature is not checked)";
    return f;
  }
  bool depth_ok = false;
  f.floor = depth_of(r, feature, depth_ok);
  if (!depth_ok) {
    f.reason = "its depth plane cannot be read";
    return f;
  }
  if (face) {
    f.kind = Feature::Kind::Face;
    f.walls = false;
    if (const p21::Instance* boundary = r.ref(feature, "face_boundary")) {
      if (!closed_profile(r, *boundary, f, 0)) return f;
    } else {
      // The face spans course_of_travel (distance along its direction) by removal_boundary
      // (profile length, along the profile's x axis, else the feature's x axis; the feature's y
      // when that is the travel direction).
      const p21::Instance* travel = r.ref(feature, "course_of_travel");
      const p21::Instance* profile = r.ref(feature, "removal_boundary");
      const auto distance = travel ? r.length(*travel, "distance") : std::nullopt;
      const auto direction = travel ? r.direction(r.ref(*travel, "its_direction")) : std::nullopt;
      const auto width = profile ? r.length(*profile, "profile_length") : std::nullopt;
      if (!distance || !direction || !width) {
        f.reason = "its course_of_travel or removal_boundary cannot be read";
        return f;
      }
      Vec2 across{1, 0};
      if (const auto pp = profile ? r.placement(r.ref(*profile, "placement")) : std::nullopt)
        across = pp->x.xy();
      const Vec2 along = direction->xy();
      if (std::abs(along.cross(across)) < 1e-9) across = {-along.y, along.x};
      const double l = across.length();
      f.region = Region::parallelogram({0, 0}, along * *distance, across * (*width / l));
    }
  } else if (slot && !place_travel(r, feature, f)) {
    return f;
  } else if (slot && plain_slot(r, feature)) {
    f.kind = Feature::Kind::Slot;
    if (!straight_slot(r, feature, f)) return f;
  } else if (outside) {
    f.kind = Feature::Kind::Outside;
    f.outside = true;
    const p21::Instance* boundary = r.ref(feature, "feature_boundary");
    if (boundary == nullptr || !r.is_a(*boundary, "closed_profile") ||
        !closed_profile(r, *boundary, f, 0)) {
      if (f.reason.empty()) f.reason = "its feature_boundary is not a closed profile";
      return f;
    }
  } else if (slot || step || thread) {
    f.kind = Feature::Kind::Profiled;
    if (slot   ? !read_profiled_slot(r, feature, f)
        : step ? !read_step(r, feature, f)
               : !read_thread(r, feature, f))
      return f;
    f.checked = true;
    return f;
  } else if (closed_pocket || open_pocket) {
    f.kind = Feature::Kind::Pocket;
    const auto corner = r.length(feature, "orthogonal_radius");
    if (open_pocket) {
      if (!open_pocket_walls(r, feature, f, corner.value_or(0))) return f;
    } else if (const p21::Instance* boundary = r.ref(feature, "feature_boundary");
               boundary == nullptr || !closed_profile(r, *boundary, f, corner.value_or(0))) {
      if (f.reason.empty()) f.reason = "its feature_boundary cannot be read";
      return f;
    }
    if (const p21::Instance* bottom = r.ref(feature, "bottom_condition")) {
      if (r.is_a(*bottom, "through_pocket_bottom_condition")) {
        f.through = true;
      } else if (!r.is_a(*bottom, "planar_pocket_bottom_condition")) {
        f.notes.push_back("its " + r.type(*bottom) + " is checked as a planar floor at the depth");
      }
    }
    if (const auto bottom_radius = r.length(feature, "planar_radius");
        bottom_radius && *bottom_radius > 0)
      f.notes.push_back("its planar_radius (floor-to-wall fillet) is not modelled");
  } else {
    f.kind = Feature::Kind::Hole;
    const auto d = r.length(feature, "diameter");
    if (!d || *d <= 0) {
      f.reason = "its diameter cannot be read";
      return f;
    }
    f.hole_radius = *d / 2;
    f.region = Region::circle({0, 0}, f.hole_radius);
    if (const p21::Instance* bottom = r.ref(feature, "bottom_condition")) {
      f.through = r.is_a(*bottom, "through_bottom_condition");
      if (r.is_a(*bottom, "conical_hole_bottom")) {
        if (const auto angle = r.number(*bottom, "tip_angle"); angle && *angle > 0 && *angle < 180)
          f.cone_depth = f.hole_radius / std::tan(*angle / 2 * std::numbers::pi / 180);
      } else if (r.is_a(*bottom, "spherical_hole_bottom") &&
                 r.ref(feature, "change_in_diameter") == nullptr) {
        return spherical_hole(r, *bottom, f);
      } else if (r.is_a(*bottom, "spherical_hole_bottom") ||
                 r.is_a(*bottom, "flat_with_radius_hole_bottom")) {
        f.notes.push_back("its " + r.type(*bottom) + " is checked as a flat bottom at the depth");
      }
    }
    // A taper (ISO 14649-10 change_in_diameter: DIAMETER_TAPER's final diameter at the depth
    // plane, or ANGLE_TAPER's angle between wall and axis, positive narrowing downwards): the
    // hole is a cavity about its axis, its wall the cone between the two radii (cavity.hpp).
    if (const p21::Instance* taper = r.ref(feature, "change_in_diameter"))
      return tapered_hole(r, *taper, f);
  }
  if (f.region.empty()) {
    f.reason = "its outline is empty";
    return f;
  }
  f.checked = true;
  return f;
}

Extent feature_extent(const Feature& f) {
  Extent e;
  const Vec2 lo = f.cavity ? f.cavity->min() : f.floor_outline().min();
  const Vec2 hi = f.cavity ? f.cavity->max() : f.floor_outline().max();
  for (const Vec2 c : {lo, Vec2{hi.x, lo.y}, hi, Vec2{lo.x, hi.y}})
    e.add(f.frame.point({c.x, c.y, 0}));
  e.top = f.frame.origin.z;
  return e;
}

std::optional<std::array<Vec3, 8>> workpiece_block_corners(const Reader& r,
                                                           const p21::Instance& workpiece,
                                                           const Frame& workpiece_frame) {
  const p21::Instance* block = r.ref(workpiece, "its_bounding_geometry");
  if (block == nullptr || !r.is_a(*block, "block")) return std::nullopt;
  const auto frame = r.placement(r.ref(*block, "position"));
  const auto x = r.number(*block, "x");
  const auto y = r.number(*block, "y");
  const auto z = r.number(*block, "z");
  if (!frame || !x || !y || !z) return std::nullopt;
  const Frame machine = workpiece_frame.then(*frame);
  std::array<Vec3, 8> corners;
  for (std::size_t k = 0; k < corners.size(); ++k)
    corners[k] = machine.point({(k & 1) ? *x : 0, (k & 2) ? *y : 0, (k & 4) ? *z : 0});
  return corners;
}

std::optional<Extent> workpiece_block(const Reader& r, const p21::Instance& workpiece,
                                      const Frame& workpiece_frame) {
  const auto corners = workpiece_block_corners(r, workpiece, workpiece_frame);
  if (!corners) return std::nullopt;
  Extent e;
  for (const Vec3& corner : *corners) {
    e.add(corner);
    e.top = std::max(e.top, corner.z);
  }
  return e;
}

SetupFrames setup_frames(const Reader& r, const p21::Instance& setup) {
  SetupFrames out;
  if (const auto f = r.placement(r.ref(setup, "its_origin"))) out.setup = *f;
  out.default_workpiece = out.setup;
  if (const auto list = r.get(setup, "its_workpiece_setup"); list && list->is_list()) {
    for (p21::Value v : r.model().items(*list)) {
      const p21::Instance* wps = v.is_reference() ? r.model().find(v.id()) : nullptr;
      if (wps == nullptr) continue;
      const Frame f = out.setup.then(r.placement(r.ref(*wps, "its_origin")).value_or(Frame{}));
      const auto wp = r.get(*wps, "its_workpiece");
      if (out.workpieces.empty()) out.default_workpiece = f;
      out.workpieces.emplace_back(wp && wp->is_reference() ? wp->id() : 0, f);
    }
  }
  return out;
}

Vec3 de_boor(const std::vector<std::array<double, 4>>& points, const std::vector<double>& knots,
             int degree, double u) {
  const int p = degree;
  const int n = static_cast<int>(points.size()) - 1;
  int k = p;
  while (k < n && knots[static_cast<std::size_t>(k + 1)] <= u) ++k;
  std::vector<std::array<double, 4>> d(static_cast<std::size_t>(p + 1));
  for (int j = 0; j <= p; ++j) {
    const auto& q = points[static_cast<std::size_t>(j + k - p)];
    d[static_cast<std::size_t>(j)] = {q[0] * q[3], q[1] * q[3], q[2] * q[3], q[3]};
  }
  for (int r = 1; r <= p; ++r) {
    for (int j = p; j >= r; --j) {
      const double lo = knots[static_cast<std::size_t>(j + k - p)];
      const double hi = knots[static_cast<std::size_t>(j + 1 + k - r)];
      const double alpha = hi > lo ? (u - lo) / (hi - lo) : 0;
      for (std::size_t m = 0; m < 4; ++m)
        d[static_cast<std::size_t>(j)][m] = (1 - alpha) * d[static_cast<std::size_t>(j - 1)][m] +
                                            alpha * d[static_cast<std::size_t>(j)][m];
    }
  }
  const auto& h = d[static_cast<std::size_t>(p)];
  return {h[0] / h[3], h[1] / h[3], h[2] / h[3]};
}

}  // namespace ncpost::verify::detail
