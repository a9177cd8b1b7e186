#pragma once
// What the specs of every feature kind share: the tool, the operation's common parameters and
// the way the tool goes down into the material and comes out of it. Readers fill them from the
// model (reader.hpp, milling_read.hpp); planners take them as they are, and unit tests write them
// by hand (docs/features.md, "Read, then plan").

#include <optional>
#include <vector>

#include "report.hpp"

namespace ncpost::stepnc::features {

// Rings with sharp corners leave a cusp at each corner unless the step between them is at most
// (2 - √2)⁻¹ · R ≈ 1.707 R; a little less keeps the cusp inside the tool.
inline constexpr double kSharpCornerStep = 1.7;

struct Toleranced {
  double size = 0;
  double upper = 0;  // allowed excess
  double lower = 0;  // allowed shortfall
};

struct Tool {
  Subject subject;  // the MACHINING_TOOL
  Subject body;     // its tool body, whose entity type says its shape
  double radius = 0;
  std::optional<double> edge_length;     // cutting_edge_length
  std::optional<double> tip_half_angle;  // degrees, as the file gives it (see tip_length)
  double corner_radius = 0;              // edge_radius
  bool left_hand = false;
};

// The parameters every milling and drilling operation has (absent values are nullopt).
struct Operation {
  Subject subject;
  std::optional<double> retract_plane;  // above the feature's top
  std::optional<double> axial;          // axial_cutting_depth
  std::optional<double> radial;         // radial_cutting_depth
  double allowance_side = 0;
  double allowance_bottom = 0;
  Subject strategy;  // its_machining_strategy
  Subject approach;  // approach strategy
  Subject retract;   // retract strategy
};

// How the tool gets from one height to another at a pattern's start point: straight along its
// axis, a helix, or a ramp back and forth along a line (PLUNGE_RAMP, PLUNGE_ZIGZAG).
struct Entry {
  enum class Kind { Plunge, Ramp, Helix } kind = Kind::Helix;
  double radius = 0;            // helix
  double angle = 0;             // ramp/helix/zigzag descent, radians
  double width = 0;             // zigzag leg
  bool explicit_entry = false;  // named by the operation (else the default helix)
  Subject strategy;             // the approach or retract strategy that asks for it, if any
};

// Equal depth levels from 0 down to -depth, none deeper than `step` (one level when no step).
[[nodiscard]] std::vector<double> levels(double depth, std::optional<double> step);

[[nodiscard]] double radians(double degrees);

// A pointed tool's point: the part below its full diameter, and its whole angle in degrees,
// from tool_tip_half_angle as NIST reads it (docs/features.md, hole depth).
[[nodiscard]] double tip_length(const Tool& tool);
[[nodiscard]] double point_angle(double tip_half_angle);

}  // namespace ncpost::stepnc::features
