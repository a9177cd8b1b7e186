// The passes of a slot whose section is a general profile (slot.hpp), level by level:
// - straight passes (a section between two open ends): from beyond one end to beyond the other
//   and back, each pass at its offset, the tool crossing between passes beyond the ends at the
//   height that clears the section between them; the next level comes back through the passes
//   in the other order; round a complete circle the same with whole circles;
// - rings (a section symmetric about the course of travel, with a radiused end): the course of
//   travel out and back, then each offset as a ring about it, half circles about radiused ends
//   (the section turned about the end), crossings over the section beyond an open end.
// A level above the deepest runs each pass of `rough` no deeper than the level.

#include <algorithm>
#include <cmath>
#include <functional>

#include "motion.hpp"
#include "slot.hpp"

namespace ncpost::stepnc::features {
namespace {

constexpr double kEps = 1e-9;

// One move of a ring to (u, v) in slot coordinates (u along the course of travel, v to its
// left): a line, an arc about (cu, 0), or a crossing over the section beyond an open end.
struct Step {
  double u = 0, v = 0;
  bool arc = false;
  double cu = 0;
  bool over = false;
};

class SectionPasses {
 public:
  SectionPasses(const SectionSlotSpec& spec, Draft& draft)
      : spec_(spec), draft_(draft), options_(draft.options()) {}
  bool run();

 private:
  [[nodiscard]] Vec3 at(double u, double v, double z) const {
    const Vec3 dir = spec_.path.dir;
    const Vec3 left = Vec3{0, 0, 1}.cross(dir);
    return dir * u + left * v + Vec3{0, 0, z};
  }
  // Where the tool leaves the slot past end k (open: the tool radius and the clearance beyond
  // it; radiused: the end of the course of travel).
  [[nodiscard]] double beyond(int k) const {
    const double run = spec_.tool_radius + options_.clearance;
    if (spec_.end[k].kind != SlotEnd::Kind::Open) return k == 0 ? 0 : spec_.path.length;
    return k == 0 ? -run : spec_.path.length + run;
  }
  [[nodiscard]] bool open(int k) const { return spec_.end[k].kind == SlotEnd::Kind::Open; }
  // The passes a level runs and the height of each there.
  [[nodiscard]] std::vector<std::size_t> level_passes(std::size_t level) const;
  [[nodiscard]] double z_of(std::size_t pass, std::size_t level) const {
    return std::max(spec_.levels[level], -spec_.passes[pass].depth);
  }
  // The height at which the tool crosses from pass a to pass b (either order).
  [[nodiscard]] double cross(std::size_t a, std::size_t b) const;
  // Up to `height`, across to (u, v), down to z: feeds, over the section.
  void over(double u, double v, double height, double z);
  // Down from above to the first pass of a level at (u, v, z): from the clearance plane on the
  // first level, from the last level's height `from_z` afterwards; into the material (a plunge
  // or a ramp along the course of travel towards `inward`) or in the air past an open end.
  void descend(double u, double v, double z, double from_z, bool first, bool in_material,
               double inward);
  // Each level's passes, in the other order than the level before (the next level starts where
  // the last ended), then up: `visit(pass, z, first, previous pass)` draws each.
  using Visit = std::function<void(std::size_t, double, bool, std::size_t)>;
  bool back_and_forth(const Visit& visit);
  bool straight();
  bool rings();
  bool circle();
  void ring(double e, double z, double height);
  // A note, once, that the tool goes down into the material along its axis when no approach
  // is named.
  void plunge_note();

  const SectionSlotSpec& spec_;
  Draft& draft_;
  const FeatureOptions& options_;
  double clear_ = 0;
  double top_ = 0;
  bool noted_ = false;
};

void SectionPasses::plunge_note() {
  if (noted_ || spec_.entry.strategy) return;
  noted_ = true;
  draft_.report().note(spec_.feature, spec_.tool.name() + " machines " + spec_.feature.name() +
                                          " in passes along its course of travel; it enters "
                                          "along its axis, as there is no room for a helix");
}

std::vector<std::size_t> SectionPasses::level_passes(std::size_t level) const {
  std::vector<std::size_t> out;
  const bool last = level + 1 == spec_.levels.size();
  const double above = level == 0 ? 0 : spec_.levels[level - 1];
  if (!last) {
    for (const std::size_t k : spec_.rough)
      if (-spec_.passes[k].depth < above - kEps) out.push_back(k);
    return out;
  }
  for (std::size_t k = 0; k < spec_.passes.size(); ++k) {
    const bool done = level > 0 && -spec_.passes[k].depth >= above - kEps &&
                      std::binary_search(spec_.rough.begin(), spec_.rough.end(), k);
    if (!done) out.push_back(k);
  }
  return out;
}

double SectionPasses::cross(std::size_t a, std::size_t b) const {
  if (spec_.rings) return spec_.cross[std::max(a, b)];
  double h = -1e300;
  for (std::size_t k = std::min(a, b) + 1; k <= std::max(a, b); ++k)
    h = std::max(h, spec_.cross[k]);
  return h;
}

void SectionPasses::over(double u, double v, double height, double z) {
  const Vec3 here = draft_.here();
  if (height > here.z + kEps) draft_.feed({here.x, here.y, height});
  const Vec3 to = at(u, v, std::max(height, z));
  if ((draft_.here() - to).length() > kEps) draft_.feed(to);
  if (z < to.z - kEps) draft_.feed(at(u, v, z));
}

void SectionPasses::descend(double u, double v, double z, double from_z, bool first,
                            bool in_material, double inward) {
  if (first) {
    draft_.rapid(at(u, v, top_));
    if (top_ > clear_) draft_.rapid(at(u, v, clear_));
  } else {
    const Vec3 here = draft_.here();
    draft_.rapid({here.x, here.y, top_});
    draft_.rapid(at(u, v, top_));
    if (top_ > clear_) draft_.rapid(at(u, v, clear_));
    if (in_material && from_z < clear_) draft_.feed(at(u, v, from_z));
  }
  if (!in_material) {
    draft_.feed(at(u, v, z));
    return;
  }
  const double from = first ? clear_ : from_z;
  if (spec_.entry.kind == Entry::Kind::Plunge) plunge_note();
  const Vec3 dir = at(inward, 0, 0);
  double length = spec_.path.length;
  if (spec_.entry.width > 0) length = std::min(length, spec_.entry.width);
  enter(draft_, spec_.entry, at(u, v, from), dir, dir, length, spec_.ccw, from, z);
}

bool SectionPasses::back_and_forth(const Visit& visit) {
  bool first = true;
  bool reverse = false;
  std::size_t previous = 0;
  for (std::size_t level = 0; level < spec_.levels.size(); ++level) {
    std::vector<std::size_t> passes = level_passes(level);
    if (reverse) std::reverse(passes.begin(), passes.end());
    reverse = !reverse;
    for (const std::size_t k : passes) {
      visit(k, z_of(k, level), first, previous);
      first = false;
      previous = k;
      if (draft_.too_many()) return draft_.limit_reached();
    }
  }
  const Vec3 end = draft_.here();
  draft_.rapid({end.x, end.y, top_});
  return true;
}

bool SectionPasses::straight() {
  // Each pass runs from the end where the last one ended.
  int side = 0;
  return back_and_forth([&](std::size_t k, double z, bool first, std::size_t previous) {
    const double v = spec_.passes[k].offset;
    if (first)
      descend(beyond(side), v, z, clear_, true, false, 0);
    else
      over(beyond(side), v, std::max(cross(previous, k), z), z);
    side = 1 - side;
    draft_.feed(at(beyond(side), v, z));
  });
}

void SectionPasses::ring(double e, double z, double height) {
  // Counter-clockwise from the left side at end 1: along to end 0, round (or across) it, back
  // along the right side, round (or across) end 1.
  std::vector<Step> steps;
  const double u0 = beyond(0);
  const double u1 = beyond(1);
  steps.push_back({u0, e});
  steps.push_back({u0, -e, !open(0), u0, open(0)});
  steps.push_back({u1, -e});
  steps.push_back({u1, e, !open(1), u1, open(1)});
  const auto play = [&](const Step& to, const Step& along, int turns) {
    if (along.over)
      over(to.u, to.v, height, z);
    else if (along.arc)
      draft_.arc(at(to.u, to.v, z), at(along.cu, 0, z), turns);
    else
      draft_.feed(at(to.u, to.v, z));
  };
  if (spec_.ccw) {
    for (const Step& s : steps) play(s, s, 1);
  } else {
    // Clockwise: the same ring backwards, each move to where the one before it started.
    const Step start{u1, e};
    for (std::size_t i = steps.size(); i-- > 0;) play(i == 0 ? start : steps[i - 1], steps[i], -1);
  }
}

bool SectionPasses::rings() {
  // The ring of each offset starts and ends on its left side at end 1: there it crosses to the
  // next, over the section. An open end, if any, is end 1, where the tool comes down in the air.
  const bool air = open(1);
  double from_z = clear_;
  bool first = true;
  for (std::size_t level = 0; level < spec_.levels.size(); ++level) {
    const std::vector<std::size_t> passes = level_passes(level);
    if (passes.empty()) continue;
    for (std::size_t i = 0; i < passes.size(); ++i) {
      const std::size_t k = passes[i];
      const double e = spec_.passes[k].offset;
      const double z = z_of(k, level);
      if (i == 0) {
        if (level > 0) from_z = std::max(spec_.levels[level - 1], -spec_.passes[k].depth);
        descend(beyond(1), e, z, from_z, first, !air, -1);
        first = false;
      } else {
        over(beyond(1), e, std::max(cross(passes[i - 1], k), z), z);
      }
      if (e < kEps) {
        // The course of travel itself: to end 0 and back.
        draft_.feed(at(beyond(0), 0, z));
        draft_.feed(at(beyond(1), 0, z));
      } else {
        ring(e, z, std::max(spec_.cross[k], z));
      }
      if (draft_.too_many()) return draft_.limit_reached();
    }
  }
  const Vec3 end = draft_.here();
  draft_.rapid({end.x, end.y, top_});
  return true;
}

bool SectionPasses::circle() {
  // Each pass a whole circle about the centre, of the path's radius less its offset (the left
  // of a counter-clockwise course is its inside), starting and ending on the +x axis, where the
  // tool crosses to the next over the section.
  const double radius = spec_.path.radius;
  const auto on = [&](double v, double z) { return Vec3{radius - v, 0, z}; };
  return back_and_forth([&](std::size_t k, double z, bool first, std::size_t previous) {
    const double v = spec_.passes[k].offset;
    if (first) {
      draft_.rapid(on(v, top_));
      if (top_ > clear_) draft_.rapid(on(v, clear_));
      plunge_note();
      draft_.feed(on(v, z));
    } else {
      const double height = std::max(cross(previous, k), z);
      const Vec3 here = draft_.here();
      if (height > here.z + kEps) draft_.feed({here.x, here.y, height});
      draft_.feed(on(v, height));
      if (z < height - kEps) draft_.feed(on(v, z));
    }
    draft_.arc(on(v, z), {0, 0, z}, spec_.ccw ? 1 : -1);
  });
}

bool SectionPasses::run() {
  clear_ = options_.clearance;
  top_ = std::max(spec_.retract_plane.value_or(clear_), clear_);
  if (spec_.passes.empty() || spec_.levels.empty()) return true;
  const bool ok = spec_.path.kind == SlotPath::Kind::Circle ? circle()
                  : spec_.rings                             ? rings()
                                                            : straight();
  if (ok && spec_.exit_strategy)
    draft_.report().note(spec_.exit_strategy,
                         spec_.exit_strategy.name() + ": the last pass of " + spec_.feature.name() +
                             " ends where the tool can leave along its axis; it does");
  return ok;
}

}  // namespace

bool plan_section_slot(const SectionSlotSpec& spec, Draft& draft) {
  return SectionPasses(spec, draft).run();
}

}  // namespace ncpost::stepnc::features
