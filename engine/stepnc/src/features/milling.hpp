#pragma once
// What the milling generators share: stepover, depth levels, tool checks, the entry into a
// pocket and the sense of its rings (milling.cpp; used by general.cpp for general profiles).

#include <optional>
#include <vector>

#include "context.hpp"

namespace ncpost::stepnc::features {

// Rings with sharp corners leave a cusp at each corner unless the step between them is at most
// (2 - √2)⁻¹ · R ≈ 1.707 R; a little less keeps the cusp inside the tool.
inline constexpr double kSharpCornerStep = 1.7;

// Stepover from the strategy's overlap and the operation's radial depth (the smaller).
double stepover(Context& ctx, const Tool& tool, const OperationData& o, double& overlap);
bool check_overlap(Context& ctx, const OperationData& o, double overlap);
// The cutting edge must take the deepest level step.
bool check_edge(Context& ctx, const Tool& tool, const std::vector<double>& z);
// The tool's corner radius makes a pocket's floor fillet (planar_radius), within its tolerance.
bool check_fillet(Context& ctx, const Tool& tool, const OperationData& o, const Toleranced& fillet);
// Axial levels; allow_multiple_passes .F. asks for the whole depth at once.
std::optional<std::vector<double>> depth_levels(Context& ctx, const OperationData& o, double depth);

// How the tool gets from `from_z` down to `to_z` at the pattern's start point p0.
struct Entry {
  enum class Kind { Plunge, Ramp, Helix } kind = Kind::Helix;
  double radius = 0;            // helix
  double angle = 0;             // ramp/helix/zigzag descent, radians
  double width = 0;             // zigzag leg
  bool explicit_entry = false;  // named by the operation (else the default helix)
};
// The operation's approach (PLUNGE_TOOLAXIS, _HELIX, _RAMP, _ZIGZAG), else a helix of
// FeatureOptions' default size. False after reporting an approach it cannot do.
bool read_entry(Context& ctx, const OperationData& o, const Tool& tool, Entry& entry);
// `x` is the profile's x axis: the helix starts at p0 + radius · x, where the caller put the tool.
void enter(Context& ctx, const Entry& e, Vec3 p0, Vec3 x, Vec3 ramp_dir, double ramp_length,
           bool ccw, double from_z, double to_z);
// A full helix the depth needs more turns, or a ramp more legs, than the motion limit allows.
bool entry_too_long(Context& ctx, const Entry& e, double ramp_length, double drop);

// The sense of the rings round a wall: counter-clockwise or not, from rotation_direction, else
// cutmode (climb when unset) and the spindle's direction. `wall_outside`: a pocket's wall is
// outside its rings, an outside profile's part inside.
bool rings_ccw(Context& ctx, const OperationData& o, bool wall_outside);

// General profiles (general.cpp): a CLOSED_POCKET bounded by a GENERAL_CLOSED_PROFILE or an
// NGON_CLOSED_PROFILE, and a GENERAL_OUTSIDE_PROFILE with such a boundary.
bool general_pocket(Context& ctx, const Instance& boundary, bool through,
                    std::optional<Toleranced> fillet);
bool general_outside_profile(Context& ctx, const Instance& boundary);

}  // namespace ncpost::stepnc::features
