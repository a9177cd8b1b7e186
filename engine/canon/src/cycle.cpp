#include "ncpost/canon/cycle.hpp"

#include <algorithm>
#include <cmath>

namespace ncpost::canon {
namespace {

// Emits motions at (x, y) with the cycle's rotary axes and tool axis.
class Emitter {
 public:
  Emitter(const Cycle& cycle, Sink& out) : cycle_(cycle), out_(out) {}

  void rapid(double z) { out_.call(StraightTraverse{pose(z)}); }
  void feed(double z) { out_.call(StraightFeed{pose(z)}); }
  void dwell() {
    if (cycle_.dwell > 0) out_.call(Dwell{cycle_.dwell});
  }
  void call(const Call& call) { out_.call(call); }

 private:
  Pose pose(double z) const { return {cycle_.x, cycle_.y, z, cycle_.rotary, cycle_.tool_axis}; }
  const Cycle& cycle_;
  Sink& out_;
};

bool finite(const Cycle& c) {
  const double values[] = {
      c.x,     c.y,    c.safe_z, c.r_z,          c.bottom_z,       c.feed,
      c.dwell, c.peck, c.pitch,  c.peck_retract, c.peck_clearance, c.spindle_speed};
  for (const double v : values) {
    if (!std::isfinite(v)) return false;
  }
  if (c.rotary &&
      !(std::isfinite(c.rotary->a) && std::isfinite(c.rotary->b) && std::isfinite(c.rotary->c)))
    return false;
  if (c.tool_axis && !(std::isfinite(c.tool_axis->i) && std::isfinite(c.tool_axis->j) &&
                       std::isfinite(c.tool_axis->k)))
    return false;
  return true;
}

// Depth of peck n (1-based), computed from r_z each time so that no rounding accumulates; the
// last peck lands exactly on the bottom.
double peck_depth(const Cycle& c, std::size_t n) {
  const double depth = c.r_z - static_cast<double>(n) * c.peck;
  // A peck that would stop within a hair of the bottom goes to the bottom instead of leaving a
  // last peck of 1e-12.
  const double hair = 1e-9 * std::max(1.0, std::fabs(c.bottom_z));
  return depth <= c.bottom_z + hair ? c.bottom_z : depth;
}

void expand_pecks(const Cycle& c, Emitter& e) {
  double previous = c.r_z;
  for (std::size_t n = 1;; ++n) {
    const double depth = peck_depth(c, n);
    if (c.peck_retract == 0 && n > 1) e.rapid(previous + c.peck_clearance);
    e.feed(depth);
    if (depth == c.bottom_z) break;
    e.rapid(c.peck_retract == 0 ? c.r_z : depth + c.peck_retract);
    previous = depth;
  }
  e.dwell();
  e.rapid(c.safe_z);
}

}  // namespace

std::string_view describe(CycleError error) noexcept {
  switch (error) {
    case CycleError::None:
      return "ok";
    case CycleError::NotFinite:
      return "a cycle parameter is not a finite number";
    case CycleError::BadHeights:
      return "cycle heights are not safe_z >= r_z >= bottom_z";
    case CycleError::BadFeed:
      return "cycle feed rate is not positive";
    case CycleError::BadPeck:
      return "peck drilling needs a positive peck and non-negative retract and clearance";
    case CycleError::TooManyPecks:
      return "peck drilling would need more pecks than allowed";
    case CycleError::NegativeDwell:
      return "cycle dwell is negative";
  }
  return "?";
}

CycleError check(const Cycle& c, const ExpandOptions& options) noexcept {
  if (!finite(c)) return CycleError::NotFinite;
  if (!(c.safe_z >= c.r_z && c.r_z >= c.bottom_z)) return CycleError::BadHeights;
  if (!(c.feed > 0)) return CycleError::BadFeed;
  if (c.dwell < 0) return CycleError::NegativeDwell;
  if (c.kind == CycleKind::PeckDrill) {
    if (!(c.peck > 0) || c.peck_retract < 0 || c.peck_clearance < 0) return CycleError::BadPeck;
    // Compare as doubles: the quotient may be far beyond any integer type.
    const double pecks = std::ceil((c.r_z - c.bottom_z) / c.peck);
    if (pecks > static_cast<double>(options.max_pecks)) return CycleError::TooManyPecks;
  }
  return CycleError::None;
}

CycleError expand_cycle(const Cycle& c, Sink& out, const ExpandOptions& options) {
  if (const auto error = check(c, options); error != CycleError::None) return error;
  Emitter e(c, out);
  e.call(SetFeedRate{c.feed});
  e.rapid(c.safe_z);
  e.rapid(c.r_z);
  switch (c.kind) {
    case CycleKind::Drill:
      e.feed(c.bottom_z);
      e.dwell();
      e.rapid(c.safe_z);
      break;
    case CycleKind::PeckDrill:
      expand_pecks(c, e);
      break;
    case CycleKind::Tap: {
      const Call forward =
          c.left_hand ? Call{StartSpindleCounterclockwise{}} : Call{StartSpindleClockwise{}};
      const Call reverse =
          c.left_hand ? Call{StartSpindleClockwise{}} : Call{StartSpindleCounterclockwise{}};
      e.feed(c.bottom_z);
      e.call(StopSpindleTurning{});
      e.call(reverse);
      e.dwell();
      e.feed(c.r_z);
      e.call(StopSpindleTurning{});
      e.call(forward);
      e.rapid(c.safe_z);
      break;
    }
    case CycleKind::Bore:
      if (c.spindle_stop) {
        e.feed(c.bottom_z);
        e.dwell();
        e.call(StopSpindleTurning{});
        e.rapid(c.safe_z);
        e.call(StartSpindleClockwise{});
        break;
      }
      [[fallthrough]];
    case CycleKind::Ream:
      e.feed(c.bottom_z);
      e.dwell();
      e.feed(c.r_z);
      e.rapid(c.safe_z);
      break;
  }
  return CycleError::None;
}

}  // namespace ncpost::canon
