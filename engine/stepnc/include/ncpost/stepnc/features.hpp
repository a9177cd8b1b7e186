#pragma once
// Toolpath generation from ISO 14649 features (conformance class 3): the knobs the standard
// leaves to the NC. A workingstep whose operation has no explicit toolpath gets its motion
// generated from the feature, the operation, its strategy and the tool (docs/features.md);
// anything the generator cannot do is a diagnostic naming the instances, never a guessed path.

#include <cstddef>

namespace ncpost::stepnc {

struct FeatureOptions {
  // Height (mm) above the feature's top where rapid approaches end and feeding starts when the
  // operation has no retract_plane.
  double clearance = 2.0;
  // How far (mm) a drill's full diameter goes past the bottom of a through hole.
  double through_clearance = 1.0;
  // Planar faces: how far (as a multiple of the tool radius) each pass runs past the face's
  // ends, so that the tool enters and leaves outside the material.
  double overtravel = 1.5;
  // Helical entry when the operation names no approach: helix radius as a share of the tool
  // radius, and its descent angle (degrees), as NIST's ex1E does.
  double default_helix_radius = 0.8;
  double default_helix_angle = 10.0;
  // How far (mm) a path that approximates a curved surface may stay off it: the scallop left
  // between stepped passes across a partial-circular slot, and the chord error of the arcs in
  // a vertical plane (woodruff slot ends) that are played as straight feeds. Below the
  // verifier's default tolerance (0.01 mm), so that what is left is within it.
  double profile_tolerance = 0.005;
  // Lengths (mm) of slots, steps and threads beyond this are refused (STEPNC-103): next to the
  // profile tolerance, the arithmetic of a path of that size cannot be trusted.
  double max_length = 1e6;
  // A workingstep whose generated path would need more motions than this is refused
  // (STEPNC-103): a hostile stepover or depth must not exhaust memory.
  std::size_t max_moves = 1'000'000;
  // General profiles (polylines, composite curves, n-gons): at most this many elements, and at
  // most this many points in the polygon that approximates them for offsetting.
  std::size_t max_profile_elements = 100'000;
  std::size_t max_polygon_points = 1'000'000;
  // mm. How far the polygons of general profiles and their offsets may deviate from the exact
  // curves; always towards the inside of the region the tool may use (never into material).
  double chord_tolerance = 0.001;
  // mm. Material that a path may leave at a sharp corner (the tool's rounding of a slightly bent
  // polyline vertex) or unswept on a floor before that is a STEPNC-102 or a denser path.
  double corner_tolerance = 0.01;
};

}  // namespace ncpost::stepnc
