#pragma once
// GENERAL_OUTSIDE_PROFILE milled by side milling: one ring per level round the part, R +
// allowance_side outside its profile, entered and left at a lead-in point in the air beyond it.
// A rectangular or circular profile gives the ring in closed form (rounded by the tool at the
// corners); a general closed profile or an n-gon is grown as a polygon (polygons.hpp) whose arcs
// are fitted back (docs/features.md, "General profiles").

#include <optional>
#include <vector>

#include "draft.hpp"
#include "polygons.hpp"
#include "shapes.hpp"
#include "spec.hpp"

namespace ncpost::stepnc::features {

class Reader;

struct OutsideBoundary {
  const p21::Instance* boundary = nullptr;  // feature_boundary
  bool general = false;                     // a general closed profile or an n-gon
};

// Diagnostics: STEPNC-101 an operation other than side milling; STEPNC-103 no feature_boundary.
[[nodiscard]] bool read_outside_boundary(Reader& reader, OutsideBoundary& boundary);

// A rectangular (sharp corners) or circular profile.
struct OutsideSpec {
  Shape shape;
  double offset = 0;  // of the ring from the profile: tool radius + allowance_side
  double tool_radius = 0;
  bool ccw = true;  // the sense of the ring
  std::vector<double> levels;
  std::optional<double> retract_plane;
};

// Diagnostics (and read_closed_profile's, read_depth's, read_tool's, read_operation's):
// STEPNC-101 a strategy other than contour-parallel; an approach or retract that is not a plunge
// strategy; STEPNC-102 a cutting edge shorter than a level step, one pass asked beyond the axial
// depth; STEPNC-103 more levels than the motion limit.
[[nodiscard]] bool read_outside(Reader& reader, const OutsideBoundary& boundary, OutsideSpec& spec);
[[nodiscard]] bool plan_outside(const OutsideSpec& spec, Draft& draft);

// A general closed profile or an n-gon.
struct GeneralOutsideSpec {
  poly::Ring ring;  // where the tool centre goes round the part (counter-clockwise)
  double tool_radius = 0;
  bool ccw = true;  // the sense the ring is cut in
  std::vector<double> levels;
  std::optional<double> retract_plane;
};

// Diagnostics (and read_closed_outline's, read_depth's, read_tool's, read_operation's):
// - STEPNC-101: a strategy other than contour-parallel; an approach that is not a plunge
//   strategy.
// - STEPNC-102: a concave corner or arc the tool does not fit; a bay it does not fit into; a
//   cutting edge shorter than a level step; one pass asked beyond the axial depth.
// - STEPNC-103: a polygon that crosses itself or has too many points; an outline that cannot be
//   offset; more levels than the motion limit.
// - STEPNC-016: a rotation_direction against the cutmode.
[[nodiscard]] bool read_general_outside(Reader& reader, const OutsideBoundary& boundary,
                                        GeneralOutsideSpec& spec);
// Diagnostics: STEPNC-103 more motions than the motion limit.
[[nodiscard]] bool plan_general_outside(const GeneralOutsideSpec& spec, Draft& draft);

}  // namespace ncpost::stepnc::features
