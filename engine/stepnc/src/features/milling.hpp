#pragma once
// What the 2.5D milling generators share: stepover and depth levels from the operation, the
// tool checks, the entry into and exit from the material, the sense of the rings round a wall,
// and the clearing of a pocket-like region (closed pockets and the slots whose outline is a
// rounded rectangle). General profiles (general.cpp) use the same pieces.

#include <optional>
#include <string_view>
#include <vector>

#include "context.hpp"
#include "outline.hpp"
#include "shapes.hpp"

namespace ncpost::stepnc::features::legacy {

// Rings with sharp corners leave a cusp at each corner unless the step between them is at most
// (2 - √2)⁻¹ · R ≈ 1.707 R; a little less keeps the cusp inside the tool.
inline constexpr double kSharpCornerStep = 1.7;

double radians(double degrees);

// Stepover from the strategy's overlap (ISO 14649-11: the share of the tool diameter that
// neighbouring passes have in common) and the operation's radial depth, whichever is smaller.
double stepover(Context& ctx, const Tool& tool, const OperationData& o, double& overlap);
bool check_overlap(Context& ctx, const OperationData& o, double overlap);
// The cutting edge must take the deepest level step (the wall height cut at once).
bool check_edge(Context& ctx, const Tool& tool, const std::vector<double>& z);
// The tool's corner radius makes a pocket's floor fillet (planar_radius), within its tolerance.
bool check_fillet(Context& ctx, const Tool& tool, const OperationData& o, const Toleranced& fillet);
// Axial levels; allow_multiple_passes .F. asks for the whole depth at once.
std::optional<std::vector<double>> depth_levels(Context& ctx, const OperationData& o, double depth);

// How the tool gets from one height to another at a pattern's start point: straight along its
// axis, a helix, or a ramp back and forth along a line (PLUNGE_RAMP, PLUNGE_ZIGZAG).
struct Entry {
  enum class Kind { Plunge, Ramp, Helix } kind = Kind::Helix;
  double radius = 0;            // helix
  double angle = 0;             // ramp/helix/zigzag descent, radians
  double width = 0;             // zigzag leg
  bool explicit_entry = false;  // named by the operation (else the default helix)
};

// Reads a PLUNGE_STRATEGY (approach or retract) into `e`; `e` keeps its defaults for the values
// the strategy leaves unset. False after reporting a strategy that is not a plunge strategy or
// has an angle outside (0, 90) degrees.
bool read_plunge(Context& ctx, const Instance& strategy, std::string_view role, Entry& e);
// The operation's approach, else a helix of FeatureOptions' default size.
bool read_entry(Context& ctx, const OperationData& o, const Tool& tool, Entry& entry);
// The operation's retract: its strategy, taking the approach's radius and angle where it leaves
// them unset (the approach run backwards); straight up when the operation names none.
bool read_exit(Context& ctx, const OperationData& o, const Entry& entry, Entry& exit);

// Down from `from_z` to `to_z` at p0. `x` is the profile's x axis: the helix starts at
// p0 + radius · x, where the caller put the tool.
void enter(Context& ctx, const Entry& e, Vec3 p0, Vec3 x, Vec3 ramp_dir, double ramp_length,
           bool ccw, double from_z, double to_z);
// The mirror of `enter`: up from `from_z` to `to_z`, the tool being at p0 (a helix first feeds
// out to p0 + radius · x).
void leave(Context& ctx, const Entry& e, Vec3 p0, Vec3 x, Vec3 ramp_dir, double ramp_length,
           bool ccw, double from_z, double to_z);
// A full helix the height needs more turns, or a ramp more legs, than the motion limit allows.
bool entry_too_long(Context& ctx, const Entry& e, double ramp_length, double drop);

// The sense of the rings round a wall: counter-clockwise or not, from rotation_direction, else
// cutmode (climb when unset) and the spindle's direction. `wall_outside`: a pocket's wall is
// outside its rings, an outside profile's part inside.
bool rings_ccw(Context& ctx, const OperationData& o, bool wall_outside);

// What a pocket-like feature (closed pocket, slot) gives the region clearing.
struct Region {
  Shape shape;
  bool through = false;
  std::optional<Toleranced> fillet;  // floor radius
  // Corners that lie outside the material (open slot ends), or that the caller has checked
  // itself, need no corner check here.
  bool corners_in_material = true;
  // Only the centre line may be cut (center milling): the tool must fill the width.
  bool centre_only = false;
  // Side milling: only the wall ring at each level (the inside is the bottom operation's).
  bool walls_only = false;
};

bool clear_region(Context& ctx, const Region& region);

// The rings at height z in the feature's coordinates, from the innermost start (where the
// tool is), each ring entered from the previous one by a straight feed inside the pocket.
void play_rings(Context& ctx, const Rings& rings, const detail::Frame& frame, bool ccw, double z);

// Reads a closed profile of a pocket or outside profile (GENERAL_CLOSED_PROFILE with a POLYLINE,
// TRIMMED_CURVE or COMPOSITE_CURVE of lines and circular arcs; NGON_CLOSED_PROFILE) in the
// feature's coordinates, counter-clockwise. nullopt after reporting why (STEPNC-101/103).
std::optional<Outline> read_closed_outline(Context& ctx, const Instance& boundary);
// The walls of an OPEN_POCKET: a GENERAL_PROFILE's curve, in its own sense.
std::optional<Outline> read_open_outline(Context& ctx, const Instance& boundary);

// General profiles (general.cpp): a CLOSED_POCKET bounded by a GENERAL_CLOSED_PROFILE or an
// NGON_CLOSED_PROFILE, and a GENERAL_OUTSIDE_PROFILE with such a boundary.
bool general_pocket(Context& ctx, const Instance& boundary, bool through,
                    std::optional<Toleranced> fillet);
bool general_outside_profile(Context& ctx, const Instance& boundary);

}  // namespace ncpost::stepnc::features::legacy
