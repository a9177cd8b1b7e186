// PLANAR_FACE: the planner (face.hpp). Passes from one side edge (the tool overhanging it by the
// overlap) until the tool reaches past the other edge by the overlap, each from the overtravel
// before the face to as far past it; between levels the tool rises to the clearance plane.

#include <algorithm>

#include "face.hpp"

namespace ncpost::stepnc::features {
namespace {

constexpr double kEps = 1e-9;

}  // namespace

bool plan_face(const FaceSpec& spec, Draft& draft) {
  const FeatureOptions& options = draft.options();
  const Vec3 z{0, 0, 1};
  const Vec3 t = spec.travel;
  const Vec3 p = t.cross(z);
  const Vec3 u = spec.feed;
  const Vec3 v = z.cross(u);  // left of the feed direction
  const Vec3 corners[4] = {
      {0, 0, 0}, t * spec.length, p * spec.width, t * spec.length + p * spec.width};
  double u0 = 1e300, u1 = -1e300, v0 = 1e300, v1 = -1e300;
  for (const Vec3& c : corners) {
    u0 = std::min(u0, c.dot(u));
    u1 = std::max(u1, c.dot(u));
    v0 = std::min(v0, c.dot(v));
    v1 = std::max(v1, c.dot(v));
  }
  const double r = spec.tool_radius;
  const double hang = spec.overlap * 2 * r;  // how far the tool passes each side edge
  const double over = options.overtravel * r;
  const std::vector<double>& z_levels = spec.levels;
  const bool left = spec.left;

  std::vector<double> passes;
  const double first = left ? v0 + r - hang : v1 - r + hang;
  for (std::size_t k = 0;; ++k) {
    const double c = first + (left ? 1 : -1) * static_cast<double>(k) * spec.stepover;
    passes.push_back(c);
    if (left ? c + r >= v1 + hang - kEps : c - r <= v0 - hang + kEps) break;
    if (passes.size() * z_levels.size() > options.max_moves) return draft.limit_reached();
  }

  const double top = 0;
  const double clear = top + options.clearance;
  const double retract = top + spec.retract_plane.value_or(options.clearance);
  const auto at = [&](double uu, double vv, double zz) { return u * uu + v * vv + z * zz; };
  const double ua = u0 - over;
  const double ub = u1 + over;
  draft.rapid(at(ua, passes.front(), std::max(retract, clear)));
  for (std::size_t level = 0; level < z_levels.size(); ++level) {
    const double zz = z_levels[level];
    if (level > 0 || retract > clear) draft.rapid(at(ua, passes.front(), clear));
    draft.feed(at(ua, passes.front(), zz));
    for (std::size_t k = 0; k < passes.size(); ++k) {
      const bool forward = !spec.bidirectional || k % 2 == 0;
      const double from = forward ? ua : ub;
      const double to = forward ? ub : ua;
      if (k > 0) {
        if (spec.bidirectional) {
          draft.feed(at(from, passes[k], zz));  // step over, outside the face
        } else {
          draft.rapid(at(draft.here().dot(u), passes[k - 1], clear));
          draft.rapid(at(from, passes[k], clear));
          draft.feed(at(from, passes[k], zz));
        }
      }
      draft.feed(at(to, passes[k], zz));
    }
    const Vec3 end = draft.here();
    draft.rapid({end.x, end.y, clear});
  }
  const Vec3 end = draft.here();
  if (retract > clear) draft.rapid({end.x, end.y, retract});
  return true;
}

}  // namespace ncpost::stepnc::features
