#pragma once
// What the 2.5D milling generators share: stepover and depth levels from the operation, the
// cutting edge check, the entry and exit of the material, and the clearing of a pocket-like
// region (closed pockets and the slots whose outline is a rounded rectangle).

#include <optional>
#include <vector>

#include "context.hpp"
#include "shapes.hpp"

namespace ncpost::stepnc::features {

double radians(double degrees);

// Stepover from the strategy's overlap (ISO 14649-11: the share of the tool diameter that
// neighbouring passes have in common) and the operation's radial depth, whichever is smaller.
double stepover(Context& ctx, const Tool& tool, const OperationData& o, double& overlap);
bool check_overlap(Context& ctx, const OperationData& o, double overlap);
// The cutting edge must take the deepest level step (the wall height cut at once).
bool check_edge(Context& ctx, const Tool& tool, const std::vector<double>& z);
// Axial levels; allow_multiple_passes .F. asks for the whole depth at once.
std::optional<std::vector<double>> depth_levels(Context& ctx, const OperationData& o, double depth);

// How the tool gets from one height to another at a pattern's start point: straight along its
// axis, a helix, or a ramp back and forth along a line (PLUNGE_RAMP, PLUNGE_ZIGZAG).
struct Entry {
  enum class Kind { Plunge, Ramp, Helix } kind = Kind::Helix;
  double radius = 0;  // helix
  double angle = 0;   // ramp/helix/zigzag descent, radians
  double width = 0;   // zigzag leg
};

// Reads a PLUNGE_STRATEGY (approach or retract) into `e`; `e` keeps its defaults for the values
// the strategy leaves unset. False after reporting a strategy that is not a plunge strategy or
// has an angle outside (0, 90) degrees.
bool read_plunge(Context& ctx, const Instance& strategy, std::string_view role, Entry& e);

// Down from `from_z` to `to_z` at p0. `x` is the profile's x axis: the helix starts at
// p0 + radius · x, where the caller put the tool.
void enter(Context& ctx, const Entry& e, Vec3 p0, Vec3 x, Vec3 ramp_dir, double ramp_length,
           bool ccw, double from_z, double to_z);
// The mirror of `enter`: up from `from_z` to `to_z`, the tool being at p0 (a helix first feeds
// out to p0 + radius · x).
void leave(Context& ctx, const Entry& e, Vec3 p0, Vec3 x, Vec3 ramp_dir, double ramp_length,
           bool ccw, double from_z, double to_z);

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

}  // namespace ncpost::stepnc::features
