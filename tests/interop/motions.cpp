#include "motions.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>

#include "corpus.hpp"
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

void Motions::add_arc(const canon::ArcFeed& original) {
  canon::ArcFeed arc = original;
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
      motions.push_back(
          {"ARC_FEED", {q.x, q.y, cx, cy, double(p->rotation > 0 ? 1 : -1), q.z}, feed_});
    }
  } else {
    motions.push_back({"ARC_FEED",
                       {p->first_end, p->second_end, p->first_axis, p->second_axis,
                        double(p->rotation), p->axis_end_point},
                       feed_});
  }
  position_ = end;
}

void Motions::call(const canon::Call& call) {
  if (const auto* f = std::get_if<canon::SetFeedRate>(&call)) feed_ = f->rate;
  if (const auto* t = std::get_if<canon::StraightTraverse>(&call)) {
    position_ = map({t->to.x, t->to.y, t->to.z});
    motions.push_back({"STRAIGHT_TRAVERSE", {position_.x, position_.y, position_.z}, feed_});
  }
  if (const auto* t = std::get_if<canon::StraightFeed>(&call)) {
    position_ = map({t->to.x, t->to.y, t->to.z});
    motions.push_back({"STRAIGHT_FEED", {position_.x, position_.y, position_.z}, feed_});
  }
  if (const auto* a = std::get_if<canon::ArcFeed>(&call)) add_arc(*a);
  if (const auto* n = std::get_if<canon::NurbsFeed>(&call); n && options_.nurbs_samples > 0) {
    Motion m{"NURBS_FEED", {}, feed_};
    for (const auto& q : sample(*n, options_.nurbs_samples)) {
      position_ = map(q);
      m.values.insert(m.values.end(), {position_.x, position_.y, position_.z});
    }
    motions.push_back(std::move(m));
  } else if (n)
    for (const auto& q : linearize(*n, options_.chord_tolerance)) {
      position_ = map(q);
      motions.push_back({"STRAIGHT_FEED", {position_.x, position_.y, position_.z}, feed_});
    }
  // The expansion is a program of its own (its feed included); the feed in force after it is
  // the expansion's last, as for a controller running the cycle.
  if (const auto* c = std::get_if<canon::Cycle>(&call)) (void)canon::expand_cycle(*c, *this);
}

MotionOptions options_for(const profile::Profile& profile) {
  MotionOptions o;
  o.chord_tolerance = profile.chord_tolerance;
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
    if (known_at && to == at) continue;
    if (m.kind == "STRAIGHT_TRAVERSE" && known_from && known_at &&
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
                            const std::string& who) {
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
  }
  outcome.compared = n;
  return outcome;
}

Posted post_file(const std::filesystem::path& input, const std::string& profile_id, bool tolerant) {
  xslt::initialise();
  static const express::SchemaRegistry registry;
  static profile::ProfileStore store(test::source_dir() / "stylesheets");
  Posted posted;
  std::vector<diag::FileDiagnostic> diagnostics;
  posted.profile = store.load(profile_id, diagnostics);
  EXPECT_TRUE(posted.profile) << profile_id << ": "
                              << (diagnostics.empty() ? "" : diag::format(diagnostics[0]));
  if (!posted.profile) return posted;
  pipeline::LoadOptions load_options;
  load_options.tolerant = tolerant;
  auto loaded = pipeline::load(test::read_file(input), registry, load_options);
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

}  // namespace ncpost::interop
