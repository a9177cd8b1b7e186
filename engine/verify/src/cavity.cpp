#include "cavity.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "model.hpp"

namespace ncpost::verify::detail {
namespace {

constexpr double kPi = std::numbers::pi;
// A step's floor and section run this far (mm) onto its open side: beyond any tool.
constexpr double kFar = 1000;
// Near a woodruff end the tool's surface is sampled at this many angles round its axis.
constexpr int kAngles = 72;
// ... and its outline every this many mm there.
constexpr double kWoodruffSpacing = 0.1;

double length(double x, double y) {
  return std::sqrt(x * x + y * y);  // no overflow at these sizes, and much faster than hypot
}

// The unit vectors round a tool's axis at which its surface is sampled.
const std::vector<Vec2>& round_the_axis() {
  static const std::vector<Vec2> directions = [] {
    std::vector<Vec2> d;
    for (int k = 0; k < kAngles; ++k)
      d.push_back({std::cos(2 * kPi * k / kAngles), std::sin(2 * kPi * k / kAngles)});
    return d;
  }();
  return directions;
}

// The boundary of a section: its lower side from left to right (u increasing), then back over
// the top (or round the far side of a step).
struct Builder {
  Region region;
  std::vector<Vec2> lower;
  Vec2 first{};
  Vec2 at{};
  void start(Vec2 p) {
    first = at = p;
    region.add_polygon_point(p);
    lower.push_back(p);
  }
  void line(Vec2 p) {
    if ((p - at).length() > 1e-12) region.add_line(at, p);
    region.add_polygon_point(p);
    lower.push_back(p);
    at = p;
  }
  void arc(Vec2 centre, double radius, double from, double sweep) {
    if (radius <= 1e-12) return;
    region.add_arc(centre, radius, from, sweep);
    // The polygon only decides inside from outside (near the boundary the distance is ~0
    // either way); the lower side is interpolated for heights, so it is finer.
    const int n = std::max(8, static_cast<int>(std::ceil(std::abs(sweep) / 0.005)));
    const int every = 5;
    for (int k = 1; k <= n; ++k) {
      const double a = from + sweep * k / n;
      const Vec2 p = centre + Vec2{std::cos(a), std::sin(a)} * radius;
      if (k % every == 0 || k == n) region.add_polygon_point(p);
      lower.push_back(p);
    }
    at = centre + Vec2{std::cos(from + sweep), std::sin(from + sweep)} * radius;
  }
  // Back to the start through `via` (not part of the lower side).
  void close(std::initializer_list<Vec2> via) {
    for (const Vec2 p : via) {
      region.add_line(at, p);
      region.add_polygon_point(p);
      at = p;
    }
    region.add_line(at, first);
  }
};

}  // namespace

double ToolShape::lower(double rho) const {
  rho = std::max(0.0, rho);
  if (cone > 0) {
    // The rounded tip up to where the flank touches it, then the flank.
    const double c = corner;
    const double touch = c * std::cos(cone);
    if (rho <= touch) return c - std::sqrt(std::max(0.0, c * c - rho * rho));
    return c - c * std::sin(cone) + (rho - touch) / std::tan(cone);
  }
  const double c = std::min(corner, radius);
  const double flat = radius - c;
  if (rho <= flat || c <= 0) return 0;
  const double x = std::min(rho - flat, c);
  return c - std::sqrt(std::max(0.0, c * c - x * x));
}

std::vector<Vec2> ToolShape::outline(double spacing, double height) const {
  std::vector<Vec2> out;
  const int n = std::clamp(static_cast<int>(std::ceil(radius / (spacing / 2))), 1, 4000);
  for (int k = 0; k <= n; ++k) {
    const double rho = radius * k / n;
    out.push_back({rho, lower(rho)});
  }
  const double side = out.back().y;
  const int m = std::clamp(static_cast<int>(std::ceil((height - side) / spacing)), 0, 4000);
  for (int k = 1; k <= m; ++k) out.push_back({radius, side + (height - side) * k / m});
  return out;
}

// ---- sections ----------------------------------------------------------------------------

void Cavity::square_u(double half, double depth, double fillet) {
  fillet = std::clamp(fillet, 0.0, std::min(half, depth));
  Builder b;
  b.start({-half, 0});
  b.line({-half, -depth + fillet});
  b.arc({-half + fillet, -depth + fillet}, fillet, kPi, kPi / 2);
  b.line({half - fillet, -depth});
  b.arc({half - fillet, -depth + fillet}, fillet, 3 * kPi / 2, kPi / 2);
  b.line({half, 0});
  b.close({});
  section_ = b.region;
  lower_ = b.lower;
  build_open();
  floor_ = -depth;
  top_ = half;
}

void Cavity::rounded_u(double radius, double depth) {
  const double cz = -depth + radius;  // the circle's centre
  Builder b;
  if (cz <= 0) {
    b.start({-radius, 0});
    b.line({-radius, cz});
    b.arc({0, cz}, radius, kPi, kPi);
    b.line({radius, 0});
    top_ = radius;
  } else {
    const double u0 = std::sqrt(std::max(0.0, radius * radius - cz * cz));
    const double from = std::atan2(-cz, -u0);
    const double to = std::atan2(-cz, u0);
    b.start({-u0, 0});
    b.arc({0, cz}, radius, from, to - from);
    top_ = u0;
  }
  b.close({});
  section_ = b.region;
  lower_ = b.lower;
  build_open();
  floor_ = -depth;
}

bool Cavity::partial_circle(double radius, double sweep, double depth) {
  // The arc must reach the top; then the section is the circle's, cut by the top.
  if (radius * (1 - std::cos(sweep / 2)) + 1e-9 < depth || depth > radius + 1e-9) return false;
  rounded_u(radius, depth);
  return true;
}

void Cavity::vee(double angle, double radius, double depth) {
  const double half = angle / 2;
  Builder b;
  const double cz = -depth + radius;
  const double apex = cz - radius / std::sin(half);
  const double top = -apex * std::tan(half);
  b.start({-top, 0});
  if (radius > 0) {
    b.line({-radius * std::cos(half), cz - radius * std::sin(half)});
    b.arc({0, cz}, radius, -kPi + half, kPi - 2 * half);
  } else {
    b.line({0, -depth});
  }
  b.line({top, 0});
  b.close({});
  section_ = b.region;
  lower_ = b.lower;
  build_open();
  floor_ = -depth;
  top_ = top;
}

void Cavity::general(const std::vector<Vec2>& lower, bool symmetric) {
  // Cut off above the top, without what lies above it before the first point below and after
  // the last.
  std::vector<Vec2> cut;
  for (std::size_t i = 0; i < lower.size(); ++i) {
    const Vec2 p = lower[i];
    if (i > 0 && (lower[i - 1].y > 0) != (p.y > 0)) {
      const Vec2 q = lower[i - 1];
      cut.push_back({q.x + (p.x - q.x) * q.y / (q.y - p.y), 0});
    }
    cut.push_back({p.x, std::min(p.y, 0.0)});
  }
  std::size_t first = 0;
  while (first + 1 < cut.size() && cut[first + 1].y >= 0) ++first;
  std::size_t last = cut.size() - 1;
  while (last > first && cut[last - 1].y >= 0) --last;
  Builder b;
  b.start(cut[first]);
  for (std::size_t i = first + 1; i <= last; ++i) b.line(cut[i]);
  b.close({});
  section_ = b.region;
  lower_ = b.lower;
  build_open();
  floor_ = 0;
  for (const Vec2 p : lower_) floor_ = std::min(floor_, p.y);
  lo_ = lower_.front().x;
  hi_ = lower_.back().x;
  top_ = std::max(std::abs(lo_), std::abs(hi_));
  across_signed_ = !symmetric;
  two_sided_ = true;
}

void Cavity::step(double angle, double radius, double depth) {
  // The wall rises from its foot (0, -depth) at `angle` from the floor, which runs towards -u.
  const Vec2 foot{0, -depth};
  const Vec2 wall{-std::cos(angle), std::sin(angle)};
  const Vec2 floor_dir{-1, 0};
  Builder b;
  b.start({-kFar, -depth});
  if (radius > 0) {
    const Vec2 bisector = (floor_dir + wall) * (1 / (floor_dir + wall).length());
    const Vec2 centre = foot + bisector * (radius / std::sin(angle / 2));
    const Vec2 on_wall = foot + wall * (radius / std::tan(angle / 2));
    b.line({centre.x, -depth});
    const double to = std::atan2(on_wall.y - centre.y, on_wall.x - centre.x);
    b.arc(centre, radius, -kPi / 2, to + kPi / 2);
  } else {
    b.line(foot);
  }
  const Vec2 top = foot + wall * (depth / std::sin(angle));
  b.line({top.x, 0});
  b.close({Vec2{-kFar, 0}});
  section_ = b.region;
  lower_ = b.lower;
  build_open();
  floor_ = -depth;
  signed_ = true;
}

void Cavity::thread(double major, double length, double hole, double depth, bool through) {
  const double bottom = through ? -depth - kFar : -depth;
  Builder b;
  b.start({-major, 0});
  b.line({-major, -length});
  b.line({-hole, -length});
  b.line({-hole, bottom});
  b.line({hole, bottom});
  b.line({hole, -length});
  b.line({major, -length});
  b.line({major, 0});
  b.close({});
  section_ = b.region;
  lower_ = b.lower;
  build_open();
  floor_ = -depth;
  top_ = major;
}

void Cavity::taper(double top, double bottom, double depth, double cone, bool through) {
  Builder b;
  b.start({-top, 0});
  b.line({-bottom, -depth});
  if (through) {
    b.line({-bottom, -depth - kFar});
    b.line({bottom, -depth - kFar});
  } else if (cone > 0) {
    b.line({0, -depth - cone});
  }
  b.line({bottom, -depth});
  b.line({top, 0});
  b.close({});
  section_ = b.region;
  lower_ = b.lower;
  build_open();
  floor_ = -depth;
  top_ = std::max(top, bottom);
}

void Cavity::spherical_hole(double radius, double sphere, double depth) {
  const double centre = -depth + sphere;
  // The wall meets the sphere at an angle beta below the sphere's horizontal.
  const double rise = std::sqrt(std::max(0.0, sphere * sphere - radius * radius));
  const double beta = std::atan2(rise, radius);
  Builder b;
  b.start({-radius, 0});
  b.line({-radius, centre - rise});
  b.arc({0, centre}, sphere, kPi + beta, kPi - 2 * beta);
  b.line({radius, 0});
  b.close({});
  section_ = b.region;
  lower_ = b.lower;
  build_open();
  floor_ = -depth;
  top_ = radius;
}

// ---- spines ------------------------------------------------------------------------------

void Cavity::segment(Vec2 from, Vec2 to, bool open0, bool open1, double woodruff0,
                     double woodruff1) {
  spine_ = Spine::Segment;
  a_ = from;
  b_ = to;
  length_ = (to - from).length();
  along_ = (to - from) * (1 / length_);
  normal_ = {-along_.y, along_.x};
  open_[0] = open0;
  open_[1] = open1;
  woodruff_[0] = woodruff0;
  woodruff_[1] = woodruff1;
}

void Cavity::arc(Vec2 centre, double radius, double start, double sweep) {
  spine_ = Spine::Arc;
  a_ = centre;
  radius_ = radius;
  start_ = start;
  sweep_ = sweep;
}

void Cavity::circle(Vec2 centre, double radius) {
  spine_ = Spine::Circle;
  a_ = centre;
  radius_ = radius;
}

void Cavity::point(Vec2 centre) {
  spine_ = Spine::Point;
  a_ = centre;
}

void Cavity::line(Vec2 foot, Vec2 along, Vec2 into_wall, double length, double width) {
  spine_ = Spine::Line;
  a_ = foot;
  along_ = along;
  normal_ = into_wall;
  length_ = length;
  top_ = width;
}

double Cavity::u(Vec2 p) const {
  switch (spine_) {
    case Spine::Segment: {
      const double s = (p - a_).dot(along_);
      const double t = (p - a_).dot(normal_);
      if (across_signed_) return t;  // its ends are open: the section runs on past them
      // Past a radiused end the section turns about the end of the spine.
      if (s < 0 && !open_[0] && woodruff_[0] == 0) return std::hypot(s, t);
      if (s > length_ && !open_[1] && woodruff_[1] == 0) return std::hypot(s - length_, t);
      return std::abs(t);
    }
    case Spine::Arc: {
      const Vec2 v = p - a_;
      const double theta = std::atan2(v.y, v.x);
      double phi = sweep_ >= 0 ? theta - start_ : start_ - theta;
      phi = std::fmod(phi, 2 * kPi);
      if (phi < 0) phi += 2 * kPi;
      if (phi <= std::abs(sweep_)) return std::abs(v.length() - radius_);
      const Vec2 e0 = a_ + Vec2{std::cos(start_), std::sin(start_)} * radius_;
      const Vec2 e1 = a_ + Vec2{std::cos(start_ + sweep_), std::sin(start_ + sweep_)} * radius_;
      return std::min((p - e0).length(), (p - e1).length());
    }
    case Spine::Circle:
      // An asymmetric section: its left (of the counter-clockwise course) is inside.
      if (across_signed_) return radius_ - (p - a_).length();
      return std::abs((p - a_).length() - radius_);
    case Spine::Point:
      return (p - a_).length();
    case Spine::Line:
      return (p - a_).dot(normal_);
  }
  return 0;
}

double Cavity::woodruff_distance(Vec3 p, int end, double s, double t) const {
  // Outside the end plane: the straight part (cut off there) or the section turned about the
  // woodruff axis, whichever is nearer.
  const double beyond = end == 0 ? -s : s - length_;
  const double across = std::abs(t);
  const double in_section = section_distance({across, p.z});
  const double body = in_section >= 0 ? -beyond : -length(beyond, in_section);
  const double axis = floor_ + woodruff_[end];
  const double turned = axis - length(beyond, axis - p.z);
  return std::max(body, section_distance({across, turned}));
}

double Cavity::signed_distance(Vec3 p) const {
  if (spine_ == Spine::Segment) {
    const double s = (p.xy() - a_).dot(along_);
    const double t = (p.xy() - a_).dot(normal_);
    if (s < 0 && woodruff_[0] > 0) return woodruff_distance(p, 0, s, t);
    if (s > length_ && woodruff_[1] > 0) return woodruff_distance(p, 1, s, t);
  }
  return section_distance({u(p.xy()), p.z});
}

bool Cavity::near_woodruff(Vec2 p, double radius) const {
  if (spine_ != Spine::Segment) return false;
  const double s = (p - a_).dot(along_);
  return (woodruff_[0] > 0 && s < radius + 0.5) || (woodruff_[1] > 0 && s > length_ - radius - 0.5);
}

double Cavity::section_floor(double uu) const {
  // The lower side is ordered by u; a vertical piece keeps its lower end.
  if (lower_.empty() || uu < lower_.front().x || uu > lower_.back().x) return 0;
  auto it = std::lower_bound(lower_.begin(), lower_.end(), uu,
                             [](const Vec2& p, double x) { return p.x < x; });
  double best = 0;
  for (auto k = it == lower_.begin() ? it : it - 1; k + 1 != lower_.end(); ++k) {
    const Vec2 p = *k;
    const Vec2 q = *(k + 1);
    if (p.x > uu + 1e-12) break;
    if (q.x < uu - 1e-12) continue;
    const double z =
        q.x - p.x > 1e-12 ? p.y + (q.y - p.y) * (uu - p.x) / (q.x - p.x) : std::min(p.y, q.y);
    best = std::min(best, z);
  }
  return best;
}

void Cavity::build_open() {
  // The section and everything above the top: the top of the part beside it stays a boundary
  // (material below it), walls do not go on above it.
  constexpr double kHigh = 1e4;
  raised_ = Region{};
  if (lower_.empty()) return;
  std::vector<Vec2> loop;
  const Vec2 first = lower_.front();
  const Vec2 last = lower_.back();
  if (first.y < 0) {
    loop.push_back({first.x, kHigh});  // a step's far open side
  } else {
    loop.push_back({-kHigh, kHigh});
    loop.push_back({-kHigh, 0});
  }
  loop.insert(loop.end(), lower_.begin(), lower_.end());
  if (last.y < 0) {
    loop.push_back({last.x, kHigh});
  } else {
    loop.push_back({kHigh, 0});
    loop.push_back({kHigh, kHigh});
  }
  for (std::size_t k = 0; k < loop.size(); ++k) {
    const Vec2 a = loop[k];
    const Vec2 b = loop[(k + 1) % loop.size()];
    if ((b - a).length() > 1e-12) raised_.add_line(a, b);
    raised_.add_polygon_point(a);
  }
}

double Cavity::open_distance(Vec3 p) const {
  const auto in_section = [&](Vec2 q) { return raised_.signed_distance(q); };
  if (spine_ == Spine::Segment) {
    const double s = (p.xy() - a_).dot(along_);
    const double t = (p.xy() - a_).dot(normal_);
    for (int end = 0; end < 2; ++end) {
      const double beyond = end == 0 ? -s : s - length_;
      if (beyond <= 0 || woodruff_[end] <= 0) continue;
      const double inside = in_section({std::abs(t), p.z});
      const double body = inside >= 0 ? -beyond : -length(beyond, inside);
      const double axis = floor_ + woodruff_[end];
      return std::max(body, in_section({std::abs(t), axis - length(beyond, axis - p.z)}));
    }
  }
  return in_section({u(p.xy()), p.z});
}

double Cavity::general_distance(Vec2 p) const {
  // The lower side is ordered by u: only pieces within the best distance so far across can be
  // nearer (the same answer as the region's, without visiting every piece).
  double best = segment_distance(p, {lo_, 0}, {hi_, 0});
  // The lower side straight above or below p is on it too: a first bound that keeps the scan
  // short.
  if (p.x >= lo_ && p.x <= hi_) best = std::min(best, std::abs(p.y - section_floor(p.x)));
  const auto it = std::lower_bound(lower_.begin(), lower_.end(), p.x,
                                   [](const Vec2& q, double x) { return q.x < x; });
  const auto at = static_cast<std::size_t>(it - lower_.begin());
  for (std::size_t k = at == 0 ? 0 : at - 1; k + 1 < lower_.size(); ++k) {
    if (lower_[k].x - p.x > best) break;
    best = std::min(best, segment_distance(p, lower_[k], lower_[k + 1]));
  }
  for (std::size_t k = at == 0 ? 0 : at - 1; k-- > 0;) {
    if (p.x - lower_[k + 1].x > best) break;
    best = std::min(best, segment_distance(p, lower_[k], lower_[k + 1]));
  }
  return best;
}

double Cavity::section_distance(Vec2 p) const {
  const double d = two_sided_ ? general_distance(p) : section_.distance(p);
  const bool below_top = p.y < 0;
  const bool within = !lower_.empty() && p.x >= lower_.front().x && p.x <= lower_.back().x;
  const bool inside = below_top && within && p.y > section_floor(p.x);
  return inside ? d : -d;
}

double Cavity::wall_distance(Vec2 p, double allowance) const {
  // Within the allowance of the top and nearer it than anything else: the walls run on above
  // it (the top is no wall: a tool near the top alone keeps its allowance).
  const double d = section_distance(p);
  if (d > 0 && -p.y < allowance && d >= -p.y - 1e-12) return raised_.signed_distance(p);
  return d;
}

double Cavity::bottom(Vec2 p) const {
  if (spine_ == Spine::Segment) {
    const double s = (p - a_).dot(along_);
    const double t = (p - a_).dot(normal_);
    for (int end = 0; end < 2; ++end) {
      const double beyond = end == 0 ? -s : s - length_;
      if (beyond <= 0 || woodruff_[end] <= 0) continue;
      const double lowest = section_floor(std::abs(t));
      if (lowest >= 0) return 0;
      const double axis = floor_ + woodruff_[end];
      const double reach = axis - lowest;  // from the axis to the turned section's bottom
      if (beyond >= reach) return 0;
      return std::min(0.0, axis - std::sqrt(reach * reach - beyond * beyond));
    }
  }
  return section_floor(u(p));
}

bool Cavity::on_floor(Vec2 p) const {
  if (bottom(p) >= -1e-9) return false;
  if (spine_ == Spine::Segment) {
    const double s = (p - a_).dot(along_);
    if ((s < 0 && open_[0]) || (s > length_ && open_[1])) return false;
  }
  if (spine_ == Spine::Line) {
    const double s = (p - a_).dot(along_);
    const double uu = u(p);
    return s >= 0 && s <= length_ && uu >= -top_ && uu <= 0;
  }
  return true;
}

double Cavity::floor_distance(Vec2 p) const {
  if (spine_ == Spine::Line) {
    const double s = (p - a_).dot(along_);
    const double uu = u(p);
    return std::min({-uu, uu + top_, s, length_ - s});
  }
  const double across = u(p);
  double d = two_sided_ ? std::min(across - lo_, hi_ - across) : top_ - across;
  if (spine_ == Spine::Segment) {
    const double s = (p - a_).dot(along_);
    const double t = (p - a_).dot(normal_);
    if (open_[0]) d = std::min(d, s);
    if (open_[1]) d = std::min(d, length_ - s);
    for (int end = 0; end < 2; ++end) {
      if (woodruff_[end] <= 0) continue;
      const double beyond = end == 0 ? -s : s - length_;
      if (beyond <= 0) continue;
      const double axis = floor_ + woodruff_[end];
      const double reach = std::sqrt(std::max(0.0, woodruff_[end] * woodruff_[end] - axis * axis));
      d = std::min(top_ - std::abs(t), reach - beyond);
    }
  }
  return d;
}

Vec2 Cavity::min() const {
  switch (spine_) {
    case Spine::Segment: {
      double ext[2];
      for (int end = 0; end < 2; ++end) {
        const double axis = floor_ + woodruff_[end];
        ext[end] = woodruff_[end] > 0
                       ? std::sqrt(std::max(0.0, woodruff_[end] * woodruff_[end] - axis * axis))
                   : open_[end] ? 0
                                : top_;
      }
      const Vec2 p0 = a_ - along_ * ext[0];
      const Vec2 p1 = b_ + along_ * ext[1];
      return {std::min(p0.x, p1.x) - top_, std::min(p0.y, p1.y) - top_};
    }
    case Spine::Arc:
    case Spine::Circle:
      return {a_.x - radius_ - top_, a_.y - radius_ - top_};
    case Spine::Point:
      return {a_.x - top_, a_.y - top_};
    case Spine::Line: {
      Vec2 lo{1e300, 1e300};
      for (const Vec2 c :
           {a_, a_ + along_ * length_, a_ - normal_ * top_, a_ + along_ * length_ - normal_ * top_})
        lo = {std::min(lo.x, c.x), std::min(lo.y, c.y)};
      return lo;
    }
  }
  return {};
}

Vec2 Cavity::max() const {
  switch (spine_) {
    case Spine::Segment: {
      double ext[2];
      for (int end = 0; end < 2; ++end) {
        const double axis = floor_ + woodruff_[end];
        ext[end] = woodruff_[end] > 0
                       ? std::sqrt(std::max(0.0, woodruff_[end] * woodruff_[end] - axis * axis))
                   : open_[end] ? 0
                                : top_;
      }
      const Vec2 p0 = a_ - along_ * ext[0];
      const Vec2 p1 = b_ + along_ * ext[1];
      return {std::max(p0.x, p1.x) + top_, std::max(p0.y, p1.y) + top_};
    }
    case Spine::Arc:
    case Spine::Circle:
      return {a_.x + radius_ + top_, a_.y + radius_ + top_};
    case Spine::Point:
      return {a_.x + top_, a_.y + top_};
    case Spine::Line: {
      Vec2 hi{-1e300, -1e300};
      for (const Vec2 c :
           {a_, a_ + along_ * length_, a_ - normal_ * top_, a_ + along_ * length_ - normal_ * top_})
        hi = {std::max(hi.x, c.x), std::max(hi.y, c.y)};
      return hi;
    }
  }
  return {};
}

double Cavity::violation(Vec3 q, const ToolShape& tool, const std::vector<Vec2>& outline,
                         double allowance, Vec3* where) const {
  double worst = -std::numeric_limits<double>::infinity();
  const double radius = outline.empty() ? 0 : outline.back().x;
  if (near_woodruff(q.xy(), radius)) {
    // The cavity differs round the tool's axis: its surface sampled all round; a ball's
    // sphere is inside as far as its centre is from the cavity's boundary.
    const bool ball = tool.cone == 0 && tool.corner >= tool.radius - 1e-9 && tool.radius > 0;
    if (ball) {
      const Vec3 centre{q.x, q.y, q.z + tool.radius};
      worst = tool.radius + allowance - open_distance(centre);
      if (where) *where = centre;
    }
    Vec2 previous{-1, -1};
    for (const Vec2 o : outline) {
      if (ball && o.y < tool.radius) continue;
      if ((o - previous).length() < kWoodruffSpacing && o.x < radius) continue;
      if (o.x >= radius && std::abs(o.y - previous.y) < 2 * kWoodruffSpacing &&
          &o != &outline.back())
        continue;
      previous = o;
      const double z = q.z + o.y;
      if (z >= 0) continue;
      // Points kept about kWoodruffSpacing apart round the axis too (at most kAngles).
      const int every =
          o.x < 1e-9
              ? kAngles
              : std::max(
                    1, static_cast<int>(std::floor(kWoodruffSpacing * kAngles / (2 * kPi * o.x))));
      for (int k = 0; k < kAngles; k += every) {
        const Vec2 dir = round_the_axis()[static_cast<std::size_t>(k)];
        const Vec3 p{q.x + o.x * dir.x, q.y + o.x * dir.y, z};
        const double v = std::min(allowance - signed_distance(p), -z);
        if (v > worst) {
          worst = v;
          if (where) *where = p;
        }
      }
    }
    return worst;
  }
  // Elsewhere the cavity is the same at every distance from the spine: the tool's farthest
  // points from it (its outline on the far side) decide.
  const double u0 = u(q.xy());
  if (u0 == cached_u_ && q.z == cached_z_ && allowance == cached_allowance_ &&
      &outline == cached_outline_) {
    if (where) *where = {q.x, q.y, cached_where_.y};
    return cached_value_;
  }
  double worst_z = q.z;
  for (const Vec2 o : outline) {
    const double z = q.z + o.y;
    if (z >= 0) continue;
    double inside = wall_distance({u0 + o.x, z}, allowance);
    if (two_sided_) inside = std::min(inside, wall_distance({u0 - o.x, z}, allowance));
    const double v = std::min(allowance - inside, -z);
    if (v > worst) {
      worst = v;
      worst_z = z;
    }
  }
  if (where) *where = {q.x, q.y, worst_z};
  cached_u_ = u0;
  cached_z_ = q.z;
  cached_allowance_ = allowance;
  cached_outline_ = &outline;
  cached_value_ = worst;
  cached_where_ = {0, worst_z};
  return worst;
}

}  // namespace ncpost::verify::detail

namespace ncpost::verify::detail {

CavityCoverage cover(const Cavity& cavity, const std::vector<SweptShape>& swept,
                     const ToolShape& smallest, double allowance, double tolerance,
                     std::optional<double> grid, double max_work) {
  CavityCoverage out;
  const double r = smallest.radius;
  Grid g;
  g.step = grid.value_or(std::clamp(r / 10, 0.05, 1.0));
  const double margin = r + 1;
  const Vec2 lo = cavity.min() - Vec2{margin, margin};
  const Vec2 hi = cavity.max() + Vec2{margin, margin};
  // Two passes of the tool's disc over every cell: bounded work (counted in doubles, so that
  // no size overflows an int before the grid is coarse enough).
  const auto work = [&] {
    const double k = r / g.step + 1;
    return (std::ceil((hi.x - lo.x) / g.step) + 1) * (std::ceil((hi.y - lo.y) / g.step) + 1) * 3.2 *
           k * k;
  };
  while (!(work() <= max_work)) {
    g.step *= 1.25;
    out.coarsened = true;
    if (!std::isfinite(g.step)) return out;
  }
  g.nx = static_cast<int>(std::ceil((hi.x - lo.x) / g.step)) + 1;
  g.ny = static_cast<int>(std::ceil((hi.y - lo.y) / g.step)) + 1;
  g.origin = lo;
  out.grid = g.step;
  const std::size_t cells = g.cells();
  const double inf = std::numeric_limits<double>::infinity();
  // The floor (0: material up to the top), its target, and the tolerance along the normal
  // turned vertical: steeper floor, more height for the same distance.
  std::vector<double> bottom(cells);
  std::vector<unsigned char> floor(cells);
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i) {
      const Vec2 c = g.centre(i, j);
      bottom[g.index(i, j)] = cavity.bottom(c);
      floor[g.index(i, j)] = cavity.on_floor(c);
    }
  // The floor's slope at a cell (capped: at a vertical wall it is the cell's edge).
  const auto slope = [&](int i, int j) {
    const auto at = [&](int a, int b) {
      a = std::clamp(a, 0, g.nx - 1);
      b = std::clamp(b, 0, g.ny - 1);
      return bottom[g.index(a, b)];
    };
    const double dx = (at(i + 1, j) - at(i - 1, j)) / (2 * g.step);
    const double dy = (at(i, j + 1) - at(i, j - 1)) / (2 * g.step);
    return std::min(std::hypot(dx, dy), 10.0);
  };
  // What the floor's height changes across half a cell's diagonal: tool positions are cell
  // centres, the best ones lie between them.
  std::vector<double> sink(cells, 0);
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i)
      sink[g.index(i, j)] = slope(i, j) * g.step * std::numbers::sqrt2 / 2;
  // ... and the tolerance along the surface's normal, seen vertically.
  const auto slack = [&](int i, int j) {
    const double s = slope(i, j);
    return tolerance * std::sqrt(1 + s * s) + sink[g.index(i, j)];
  };
  // The tool's disc as cell offsets with its lower surface's height there.
  struct Offset {
    int di, dj;
    double h;
  };
  std::vector<Offset> disc;
  const int reach_cells = static_cast<int>(std::ceil(r / g.step)) + 1;
  for (int dj = -reach_cells; dj <= reach_cells; ++dj)
    for (int di = -reach_cells; di <= reach_cells; ++di) {
      const double d = std::hypot(di, dj) * g.step;
      if (d <= r) disc.push_back({di, dj, smallest.lower(d)});
    }
  // Lowest tip without crossing the floor (raised by the allowance) anywhere under the tool.
  std::vector<double> tip(cells, -inf);
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i) {
      double t = -inf;
      for (const Offset& o : disc) {
        const int a = i + o.di;
        const int b = j + o.dj;
        if (a < 0 || b < 0 || a >= g.nx || b >= g.ny) continue;
        const std::size_t c = g.index(a, b);
        const double z = bottom[c];
        t = std::max(t, (z < 0 ? z + allowance : z) - sink[c] - o.h);
      }
      tip[g.index(i, j)] = t;
    }
  // The lowest the tool's surface can be over each cell, and the lowest it was.
  std::vector<double> reachable(cells, inf);
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i) {
      if (!floor[g.index(i, j)]) continue;
      double best = inf;
      for (const Offset& o : disc) {
        const int a = i + o.di;
        const int b = j + o.dj;
        if (a < 0 || b < 0 || a >= g.nx || b >= g.ny) continue;
        best = std::min(best, tip[g.index(a, b)] + o.h);
      }
      reachable[g.index(i, j)] = best;
    }
  // A cell is reached when the tool's disc touches it, not only its centre (as the outline
  // model's coverage does): half a cell's diagonal of slack, at the height of the disc's rim.
  const double touch = g.step * std::numbers::sqrt2 / 2;
  std::vector<double> low(cells, inf);
  for (const SweptShape& w : swept) {
    const double rr = w.tool.radius + touch;
    const Vec2 a = w.a.xy();
    const Vec2 b = w.b.xy();
    const int i0 =
        std::max(0, static_cast<int>(std::floor((std::min(a.x, b.x) - rr - lo.x) / g.step)));
    const int i1 =
        std::min(g.nx - 1, static_cast<int>(std::ceil((std::max(a.x, b.x) + rr - lo.x) / g.step)));
    const int j0 =
        std::max(0, static_cast<int>(std::floor((std::min(a.y, b.y) - rr - lo.y) / g.step)));
    const int j1 =
        std::min(g.ny - 1, static_cast<int>(std::ceil((std::max(a.y, b.y) + rr - lo.y) / g.step)));
    if (std::abs(w.a.z - w.b.z) < 1e-9) {
      // Level: the lowest surface over a cell is where the axis passes nearest to it.
      for (int j = j0; j <= j1; ++j)
        for (int i = i0; i <= i1; ++i) {
          const double d = segment_distance(g.centre(i, j), a, b);
          if (d <= rr)
            low[g.index(i, j)] =
                std::min(low[g.index(i, j)], w.a.z + w.tool.lower(std::min(d, w.tool.radius)));
        }
      continue;
    }
    // Sloped: positions along it, closer than a quarter cell.
    const double length = (w.b - w.a).length();
    const int n = std::clamp(static_cast<int>(std::ceil(length / (g.step / 4))), 1, 100000);
    for (int k = 0; k <= n; ++k) {
      const Vec3 p = w.a + (w.b - w.a) * (static_cast<double>(k) / n);
      const int ci = static_cast<int>(std::floor((p.x - lo.x) / g.step));
      const int cj = static_cast<int>(std::floor((p.y - lo.y) / g.step));
      const int rc = static_cast<int>(std::ceil(rr / g.step)) + 1;
      for (int dj = -rc; dj <= rc; ++dj)
        for (int di = -rc; di <= rc; ++di) {
          const int i = ci + di;
          const int j = cj + dj;
          if (i < 0 || j < 0 || i >= g.nx || j >= g.ny) continue;
          const double d = (g.centre(i, j) - p.xy()).length();
          if (d <= rr)
            low[g.index(i, j)] =
                std::min(low[g.index(i, j)], p.z + w.tool.lower(std::min(d, w.tool.radius)));
        }
    }
  }
  std::size_t counted = 0;
  std::size_t unreachable = 0;
  Vec2 sum{};
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i) {
      const std::size_t c = g.index(i, j);
      if (!floor[c]) continue;
      const double target = bottom[c] + allowance;
      const double s = slack(i, j);
      if (reachable[c] > target + s) {
        ++unreachable;
        continue;
      }
      ++counted;
      if (low[c] > target + s) {
        ++out.uncovered;
        sum = sum + g.centre(i, j);
      }
    }
  const double cell = g.step * g.step;
  out.reachable_area = static_cast<double>(counted) * cell;
  out.unreachable_area = static_cast<double>(unreachable) * cell;
  out.uncovered_fraction =
      counted ? static_cast<double>(out.uncovered) / static_cast<double>(counted) : 0;
  if (out.uncovered > 0) {
    const Vec2 centroid = sum * (1.0 / static_cast<double>(out.uncovered));
    double best = inf;
    for (int j = 0; j < g.ny; ++j)
      for (int i = 0; i < g.nx; ++i) {
        const std::size_t c = g.index(i, j);
        if (!floor[c] || reachable[c] > bottom[c] + allowance + slack(i, j) ||
            low[c] <= bottom[c] + allowance + slack(i, j))
          continue;
        const double d = (g.centre(i, j) - centroid).length();
        if (d < best) {
          best = d;
          out.sample = {g.centre(i, j).x, g.centre(i, j).y, bottom[c] + allowance};
        }
      }
  }
  return out;
}

}  // namespace ncpost::verify::detail
