#pragma once
// General outlines for the verifier: POLYLINE, TRIMMED_CURVE (of a LINE or CIRCLE, trimmed by
// points) and COMPOSITE_CURVE read into exact lines and arcs, with ISO 14649's orthogonal_radius
// as exact fillet arcs in the sharp corners, and turned into Regions (exact elements for the
// distance, a fine polygon for inside/outside). Written for the verifier alone: it shares no
// code with the generator's outlines or offsets (engine/stepnc/src/features), so that a mistake
// there is not repeated here.

#include <optional>
#include <string>
#include <vector>

#include "model.hpp"
#include "region.hpp"

namespace ncpost::verify::detail {

// A line from a to b, or an arc about `centre` from a to b sweeping `sweep` radians (positive
// counter-clockwise).
struct Piece2 {
  bool arc = false;
  Vec2 a{}, b{};
  Vec2 centre{};
  double radius = 0;
  double sweep = 0;
};

// Pieces of a curve in the plane of `local` (the profile's placement, already in the feature
// frame); nullopt with `reason` set when the curve is not one of the kinds above, leaves the
// plane, or its pieces do not join.
std::optional<std::vector<Piece2>> read_curve(const Reader& r, const p21::Instance& curve,
                                              const Frame& local, std::string& reason);

// Counter-clockwise closed chain: reverses an open or closed chain when the closed polygon it
// encloses (with the chord from its end to its start) runs clockwise.
void make_counter_clockwise(std::vector<Piece2>& chain);

// The corners of a closed counter-clockwise chain that turn left (convex, seen from inside) get a
// fillet arc of `radius` tangent to both pieces. With `closed` false, the chain's two ends are
// not corners.
std::vector<Piece2> with_fillets(const std::vector<Piece2>& chain, double radius, bool closed);

// The region inside a closed chain.
Region region_of(const std::vector<Piece2>& closed);
// An open pocket: the walls (counter-clockwise with the open side closing them) with the open
// side's line continued `far` beyond both ends as material faces, and a box of `far` beyond the
// open side; the floor region is the walls closed by the open side.
Region open_walls_region(const std::vector<Piece2>& walls, double far);

}  // namespace ncpost::verify::detail
