#pragma once
// A SLOT as the generator reads it (slots.cpp), and the passes of a form tool along its course
// of travel (slot_passes.cpp).

#include <vector>

#include "context.hpp"

namespace ncpost::stepnc::features::legacy {

// The course of travel in the feature's xy plane: a line from the placement's origin, or a
// circle (an arc of it) about the origin, starting on the x axis.
struct SlotPath {
  enum class Kind { Line, Arc, Circle } kind = Kind::Line;
  Vec3 dir{1, 0, 0};  // line: unit direction
  double length = 0;  // line: distance; arc, circle: arc length
  double radius = 0;  // arc, circle
  double sweep = 0;   // arc: signed angle (radians, counter-clockwise positive); circle: 2π
};

struct SlotSection {
  enum class Kind { SquareU, RoundedU, Vee, PartialCircular } kind = Kind::SquareU;
  double half = 0;                   // U profiles: half the width
  std::optional<Toleranced> fillet;  // square-U: the floor radius
  double angle = 0;                  // vee: the angle between its sides (radians)
  Toleranced radius{};               // vee: bottom radius; partial circle, rounded-U: radius
  double sweep = 0;                  // partial circle: its angle (radians)
};

struct SlotEnd {
  enum class Kind { Radiused, Flat, Open, Woodruff, Loop } kind = Kind::Radiused;
  const p21::Instance* instance = nullptr;
  double right = 0;  // flat: corner_radius1, on the right of the travel direction
  double left = 0;   // flat: corner_radius2
  Toleranced woodruff{};
};

// One pass along the course of travel: `offset` to its left and right (a closed ring about it
// when offset > 0) with the tool tip `depth` below the feature's top.
struct SlotPass {
  double offset = 0;
  double depth = 0;
};

struct SlotPlan {
  SlotPath path;
  SlotEnd end[2];
  std::vector<SlotPass> passes;  // the finishing passes, from the course of travel outwards
  double tool_radius = 0;
  double ball_radius = 0;  // a ball end mill (0: another tool)
  double stepover = 0;     // stepped passes: their largest spacing on a level above the bottom
  bool ccw = true;         // rings counter-clockwise
};

bool slot_passes(Context& ctx, const Tool& tool, const OperationData& o, const SlotPlan& plan,
                 double depth);

}  // namespace ncpost::stepnc::features::legacy
