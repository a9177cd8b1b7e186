#include "motions.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>
#include <sstream>

#include "corpus.hpp"
#include "forward_kinematics.hpp"
#include "ncpost/canon/cycle.hpp"
#include "ncpost/express/registry.hpp"
#include "ncpost/pipeline/load.hpp"
#include "ncpost/render/render.hpp"
#include "ncpost/stepnc/interpreter.hpp"

namespace ncpost::interop {

std::string describe(const Motion& m) {
  std::ostringstream s;
  s << m.kind << "(";
  for (std::size_t i = 0; i < m.values.size(); ++i) s << (i ? ", " : "") << m.values[i];
  s << ") F" << m.feed;
  if (m.axis.size() == 3)
    s << " axis (" << m.axis[0] << ", " << m.axis[1] << ", " << m.axis[2] << ")";
  return s.str();
}

Motions::Motions(MotionOptions options) : options_(options) {}

canon::Point Motions::map(canon::Point p) const {
  if (!options_.setup) return p;
  const auto& m = options_.setup->matrix;
  const auto& t = options_.setup->translation;
  return {m[0] * p.x + m[1] * p.y + m[2] * p.z + t[0], m[3] * p.x + m[4] * p.y + m[5] * p.z + t[1],
          m[6] * p.x + m[7] * p.y + m[8] * p.z + t[2]};
}

void Motions::push(Motion m) {
  if (options_.kinematics) m.axis = axis_;
  motions.push_back(std::move(m));
}

void Motions::follow_orientation(const canon::Pose& pose) {
  if (!options_.kinematics) return;
  if (!options_.posted) {
    if (!pose.tool_axis) return;
    const auto& v = *pose.tool_axis;
    const double size = std::hypot(v.i, v.j, v.k);
    if (size > 0) axis_ = {v.i / size, v.j / size, v.k / size};
    return;
  }
  if (pose.rotary) rotary_ = *pose.rotary;
  const auto tool = test::forward(*options_.kinematics, {0, 0, 0}, rotary_, 0);
  axis_ = {tool.axis[0], tool.axis[1], tool.axis[2]};
}

canon::Point Motions::program_point(const canon::Point& p) const {
  if (!options_.kinematics || !options_.posted || options_.kinematics->tool_centre_point) return p;
  const auto tool = test::forward(*options_.kinematics, {p.x, p.y, p.z}, rotary_, tool_length_,
                                  options_.pivot_scale);
  return {tool.tip[0], tool.tip[1], tool.tip[2]};
}

void Motions::add_arc(const canon::ArcFeed& original) {
  canon::ArcFeed arc = original;
  follow_orientation(arc.end);
  if (options_.kinematics && options_.posted && !options_.kinematics->tool_centre_point) {
    // A posted arc in machine positions: its end, centre and normal back in the program's.
    const canon::Point end = program_point({arc.end.x, arc.end.y, arc.end.z});
    const canon::Point centre = program_point(arc.centre);
    const canon::Point tip = program_point(
        {arc.centre.x + arc.normal.i, arc.centre.y + arc.normal.j, arc.centre.z + arc.normal.k});
    arc.end.x = end.x;
    arc.end.y = end.y;
    arc.end.z = end.z;
    arc.centre = centre;
    arc.normal = {tip.x - centre.x, tip.y - centre.y, tip.z - centre.z};
  }
  if (options_.setup) {
    // A rotation keeps the turn count's sense relative to the (rotated) normal.
    const auto e = map({arc.end.x, arc.end.y, arc.end.z});
    const auto c = map(arc.centre);
    const auto& m = options_.setup->matrix;
    const auto& n = arc.normal;
    arc.end.x = e.x;
    arc.end.y = e.y;
    arc.end.z = e.z;
    arc.centre = c;
    arc.normal = {m[0] * n.i + m[1] * n.j + m[2] * n.k, m[3] * n.i + m[4] * n.j + m[5] * n.k,
                  m[6] * n.i + m[7] * n.j + m[8] * n.k};
  }
  const auto p = canon::plane_arc(arc);
  ASSERT_TRUE(p) << "tilted arc";
  const canon::Point end{arc.end.x, arc.end.y, arc.end.z};
  if (options_.split_multi_turn_degrees > 0 && p->plane == canon::Plane::Xy &&
      std::abs(p->rotation) > 1) {
    // Equal pieces by angle, Z linear in the angle: the helix itself, cut.
    const double cx = p->first_axis;
    const double cy = p->second_axis;
    const double r = std::hypot(position_.x - cx, position_.y - cy);
    const double a0 = std::atan2(position_.y - cy, position_.x - cx);
    const double a1 = std::atan2(end.y - cy, end.x - cx);
    double d = p->rotation > 0 ? a1 - a0 : a0 - a1;
    constexpr double kTwoPi = 2 * std::numbers::pi;
    while (d <= 1e-9) d += kTwoPi;
    while (d > kTwoPi + 1e-9) d -= kTwoPi;
    const double sweep = (d + kTwoPi * (std::abs(p->rotation) - 1)) * (p->rotation > 0 ? 1 : -1);
    const double limit = options_.split_multi_turn_degrees * std::numbers::pi / 180;
    const auto pieces = static_cast<int>(std::ceil(std::abs(sweep) / limit - 1e-9));
    const double z0 = position_.z;
    for (int k = 1; k <= pieces; ++k) {
      const double t = double(k) / double(pieces);
      const double angle = a0 + sweep * t;
      const canon::Point q = k == pieces
                                 ? end
                                 : canon::Point{cx + r * std::cos(angle), cy + r * std::sin(angle),
                                                z0 + (end.z - z0) * t};
      push({"ARC_FEED", {q.x, q.y, cx, cy, double(p->rotation > 0 ? 1 : -1), q.z}, feed_});
    }
  } else {
    push({"ARC_FEED",
          {p->first_end, p->second_end, p->first_axis, p->second_axis, double(p->rotation),
           p->axis_end_point},
          feed_});
  }
  position_ = end;
}

void Motions::call(const canon::Call& call) {
  if (const auto* f = std::get_if<canon::SetFeedRate>(&call)) feed_ = f->rate;
  if (const auto* l = std::get_if<canon::UseToolLengthOffset>(&call)) tool_length_ = l->length;
  if (const auto* t = std::get_if<canon::StraightTraverse>(&call)) {
    follow_orientation(t->to);
    position_ = map(program_point({t->to.x, t->to.y, t->to.z}));
    push({"STRAIGHT_TRAVERSE", {position_.x, position_.y, position_.z}, feed_});
  }
  if (const auto* t = std::get_if<canon::StraightFeed>(&call)) {
    follow_orientation(t->to);
    position_ = map(program_point({t->to.x, t->to.y, t->to.z}));
    push({"STRAIGHT_FEED", {position_.x, position_.y, position_.z}, feed_});
  }
  if (const auto* a = std::get_if<canon::ArcFeed>(&call)) add_arc(*a);
  const auto* original = std::get_if<canon::NurbsFeed>(&call);
  std::optional<canon::NurbsFeed> n;
  if (original) {
    n = *original;
    canon::Pose end{};
    end.rotary = n->rotary;
    end.tool_axis = n->tool_axis;
    follow_orientation(end);
    for (auto& q : n->points) {
      const canon::Point p = program_point({q.x, q.y, q.z});
      q.x = p.x;
      q.y = p.y;
      q.z = p.z;
    }
  }
  if (n && options_.nurbs_samples > 0) {
    Motion m{"NURBS_FEED", {}, feed_};
    for (const auto& q : sample(*n, options_.nurbs_samples)) {
      position_ = map(q);
      m.values.insert(m.values.end(), {position_.x, position_.y, position_.z});
    }
    push(std::move(m));
  } else if (n) {
    for (const auto& q : linearize(*n, options_.chord_tolerance)) {
      position_ = map(q);
      push({"STRAIGHT_FEED", {position_.x, position_.y, position_.z}, feed_});
    }
  }
  // The expansion is a program of its own (its feed included); the feed in force after it is
  // the expansion's last, as for a controller running the cycle.
  if (const auto* c = std::get_if<canon::Cycle>(&call)) (void)canon::expand_cycle(*c, *this);
}

MotionOptions options_for(const profile::Profile& profile) {
  MotionOptions o;
  o.chord_tolerance = profile.chord_tolerance;
  if (profile.kinematics) o.kinematics = &*profile.kinematics;
  return o;
}

std::vector<canon::Point> sample(const canon::NurbsFeed& nurbs, int count) {
  std::vector<canon::Point> out;
  if (nurbs.knots.size() < 2 || count < 2) return out;
  const double u0 = nurbs.knots[static_cast<std::size_t>(nurbs.degree)];
  const double u1 = nurbs.knots[nurbs.knots.size() - 1 - static_cast<std::size_t>(nurbs.degree)];
  for (int k = 0; k < count; ++k)
    out.push_back(render::nurbs_point(nurbs, u0 + (u1 - u0) * double(k) / double(count - 1)));
  return out;
}

namespace {
bool same_direction(const std::vector<double>& a, const std::vector<double>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (std::abs(a[i] - b[i]) > 1e-9) return false;
  return true;
}
}  // namespace

std::vector<Motion> normalised(const std::vector<Motion>& motions) {
  std::vector<Motion> out;
  // Where the last kept motion ends and where the last kept traverse starts, when known.
  canon::Point at{}, from{};
  bool known_at = false, known_from = false;
  for (const auto& m : motions) {
    const bool straight = m.kind == "STRAIGHT_TRAVERSE" || m.kind == "STRAIGHT_FEED";
    if (!straight) {
      out.push_back(m);
      known_at = known_from = false;
      continue;
    }
    const canon::Point to{m.values[0], m.values[1], m.values[2]};
    // A five-axis motion that only turns the tool is a motion.
    const bool same_axis = known_at && same_direction(m.axis, out.back().axis);
    if (known_at && to == at && same_axis) continue;
    if (m.kind == "STRAIGHT_TRAVERSE" && known_from && known_at && same_axis &&
        out.back().kind == "STRAIGHT_TRAVERSE") {
      const double ax = at.x - from.x, ay = at.y - from.y, az = at.z - from.z;
      const double bx = to.x - at.x, by = to.y - at.y, bz = to.z - at.z;
      const double cross = std::hypot(ay * bz - az * by, az * bx - ax * bz, ax * by - ay * bx);
      const double dot = ax * bx + ay * by + az * bz;
      if (dot > 0 && cross <= 1e-9 * std::hypot(ax, ay, az) * std::hypot(bx, by, bz)) {
        out.back().values = m.values;
        at = to;
        continue;
      }
    }
    from = at;
    known_from = known_at;
    out.push_back(m);
    at = to;
    known_at = true;
  }
  return out;
}

std::vector<canon::Point> linearize(const canon::NurbsFeed& nurbs, double tolerance) {
  return render::linearize(nurbs, tolerance);
}

Outcome expect_same_motions(const std::vector<Motion>& ours, const std::vector<Motion>& theirs,
                            const std::string& who, double axis_tolerance) {
  Outcome outcome;
  EXPECT_EQ(ours.size(), theirs.size()) << "motion count, ours vs " << who;
  const std::size_t n = std::min(ours.size(), theirs.size());
  for (std::size_t i = 0; i < n; ++i) {
    const auto& a = ours[i];
    const auto& b = theirs[i];
    if (a.kind != b.kind || a.values.size() != b.values.size()) {
      ADD_FAILURE() << "motion " << i << ": ours " << describe(a) << ", " << who << " "
                    << describe(b);
      outcome.compared = i;
      return outcome;
    }
    double dev = std::abs(a.feed - b.feed);
    if (a.kind != "STRAIGHT_TRAVERSE")
      EXPECT_LE(dev, kTolerance) << "feed of motion " << i << ": ours " << describe(a) << ", "
                                 << who << " " << describe(b);
    else
      dev = 0;
    for (std::size_t k = 0; k < a.values.size(); ++k)
      dev = std::max(dev, std::abs(a.values[k] - b.values[k]));
    EXPECT_LE(dev, kTolerance) << "motion " << i << ": ours " << describe(a) << ", " << who << " "
                               << describe(b);
    outcome.max_deviation = std::max(outcome.max_deviation, dev);
    if (a.axis.size() != b.axis.size()) {
      ADD_FAILURE() << "motion " << i << ": a tool axis on one side only: ours " << describe(a)
                    << ", " << who << " " << describe(b);
      continue;
    }
    double axis_dev = 0;
    for (std::size_t k = 0; k < a.axis.size(); ++k)
      axis_dev = std::max(axis_dev, std::abs(a.axis[k] - b.axis[k]));
    EXPECT_LE(axis_dev, axis_tolerance) << "tool axis of motion " << i << ": ours " << describe(a)
                                        << ", " << who << " " << describe(b);
    outcome.max_axis_deviation = std::max(outcome.max_axis_deviation, axis_dev);
  }
  outcome.compared = n;
  return outcome;
}

Posted post_file(const std::filesystem::path& input, const std::string& profile_id) {
  xslt::initialise();
  static const express::SchemaRegistry registry;
  static profile::ProfileStore store(test::source_dir() / "stylesheets");
  Posted posted;
  std::vector<diag::FileDiagnostic> diagnostics;
  posted.profile = store.load(profile_id, diagnostics);
  EXPECT_TRUE(posted.profile) << profile_id << ": "
                              << (diagnostics.empty() ? "" : diag::format(diagnostics[0]));
  if (!posted.profile) return posted;
  auto loaded = pipeline::load(test::read_file(input), registry);
  EXPECT_TRUE(loaded.ok()) << input;
  if (!loaded.ok()) return posted;
  const stepnc::AttributeReader attributes(loaded.model, *loaded.schema);
  canon::ProgramBuffer buffer;
  EXPECT_TRUE(stepnc::interpret(loaded.model, attributes, buffer, {}).ok()) << input;
  posted.calls = buffer.calls();
  std::vector<diag::FileDiagnostic> render_diagnostics;
  posted.text = render::render_program(*posted.profile, posted.calls, render_diagnostics);
  EXPECT_FALSE(diag::has_errors(render_diagnostics))
      << profile_id << ": " << diag::format(render_diagnostics.front());
  return posted;
}

std::vector<Motion> motions_of(const std::vector<canon::Call>& calls,
                               const MotionOptions& options) {
  Motions m(options);
  for (const auto& c : calls) m.call(c);
  return std::move(m.motions);
}

// A five-axis program by hand: tilts in every direction, a wrap of the rotating axis, an arc
// and a NURBS with the tool tilted (they keep the orientation in force), and back to the pole.
std::vector<canon::Call> five_axis_program() {
  using canon::Direction;
  std::vector<canon::Call> calls;
  calls.emplace_back(canon::Begin{canon::Scope::Project, {1, "PROJECT", "FIVE"}});
  calls.emplace_back(canon::UseLengthUnits{canon::Units::Millimetres});
  calls.emplace_back(canon::SelectPlane{canon::Plane::Xy});
  calls.emplace_back(canon::Begin{canon::Scope::Workingstep, {2, "MACHINING_WORKINGSTEP", "5X"}});
  calls.emplace_back(canon::SelectTool{4});
  calls.emplace_back(canon::ChangeTool{4});
  calls.emplace_back(canon::UseToolLengthOffset{82.5});
  calls.emplace_back(canon::SetSpindleSpeed{9000});
  calls.emplace_back(canon::StartSpindleClockwise{});
  calls.emplace_back(canon::StraightTraverse{{0, 0, 60}});
  calls.emplace_back(canon::SetFeedRate{800});
  const double s = std::sin(25 * std::numbers::pi / 180), c = std::cos(25 * std::numbers::pi / 180);
  const auto feed = [&](double x, double y, double z, Direction d) {
    calls.emplace_back(canon::StraightFeed{{x, y, z, std::nullopt, d}});
  };
  feed(0, 0, 10, {0, 0, 1});
  for (int step = 0; step <= 8; ++step) {  // round Z in eighths of a turn, twice past +-180
    const double a = step * std::numbers::pi / 4;
    feed(10 * std::cos(a), 10 * std::sin(a), 5 - 0.5 * step, {s * std::cos(a), s * std::sin(a), c});
  }
  // An arc and a NURBS with the tool at 25 degrees towards +X (both keep it).
  feed(20, 0, 0, {s, 0, c});
  canon::ArcFeed arc;
  arc.end = {30, 10, 0};
  arc.centre = {30, 0, 0};
  arc.normal = {0, 0, 1};
  arc.turns = 1;
  calls.emplace_back(arc);
  canon::NurbsFeed nurbs;
  nurbs.degree = 2;
  nurbs.points = {{30, 10, 0, 1}, {30, 20, 0, 0.8}, {40, 20, -2, 1}};
  nurbs.knots = {0, 0, 0, 1, 1, 1};
  nurbs.tool_axis = Direction{s, 0, c};
  calls.emplace_back(nurbs);
  // A slanted line and back to the pole.
  feed(50, 20, -2, {-0.3, 0.4, std::sqrt(1 - 0.25)});
  feed(50, 20, 20, {0, 0, 1});
  calls.emplace_back(canon::StraightTraverse{{50, 20, 60}});
  calls.emplace_back(canon::End{canon::Scope::Workingstep, {2, "MACHINING_WORKINGSTEP", "5X"}});
  calls.emplace_back(canon::StopSpindleTurning{});
  calls.emplace_back(canon::ProgramEnd{});
  calls.emplace_back(canon::End{canon::Scope::Project, {1, "PROJECT", "FIVE"}});
  return calls;
}

}  // namespace ncpost::interop
