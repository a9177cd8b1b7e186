#pragma once
// PLANAR_FACE milled by plane milling: a rectangle from the feature's origin along its course of
// travel and to its right, cut by parallel passes that run past its ends (they start and end in
// the air), one depth level after the other (docs/features.md).

#include <optional>
#include <vector>

#include "draft.hpp"
#include "spec.hpp"

namespace ncpost::stepnc::features {

class Reader;

struct FaceSpec {
  Vec3 travel{1, 0, 0};  // course_of_travel's direction, in the face
  double length = 0;     // along the travel
  double width = 0;      // to the right of the travel
  Vec3 feed{1, 0, 0};    // unit direction of the passes: along the travel or across it
  bool bidirectional = true;
  bool left = true;  // each pass to the left of the one before (seen along the feed direction)
  double tool_radius = 0;
  double overlap = 0;          // the share of the diameter by which the tool passes each side edge
  double stepover = 0;         // between passes
  std::vector<double> levels;  // from the top (z = 0) down
  std::optional<double> retract_plane;  // above the top; else FeatureOptions::clearance
};

// Diagnostics (and Reader::read_depth's, read_tool's, read_operation's):
// - STEPNC-101: an operation other than plane milling; a face_boundary; bosses; a placed
//   course_of_travel or removal_boundary; a strategy other than uni- or bidirectional milling;
//   a stroke connection other than straight line; a feed direction oblique to the travel; an
//   approach or retract that is not a plunge strategy.
// - STEPNC-102: a cutting edge shorter than a level step; one pass asked beyond the axial depth.
// - STEPNC-103: no course_of_travel or removal_boundary; a travel or width that is not positive;
//   a travel or feed direction out of the face; an overlap outside [0, 1); allowance_bottom
//   that leaves the whole depth; more levels than the motion limit.
// - STEPNC-016: a cutmode (no effect on a face); an approach or retract other than along the
//   tool axis (the passes start and end in the air).
[[nodiscard]] bool read_face(Reader& reader, FaceSpec& spec);

// Diagnostics: STEPNC-103 more passes than the motion limit.
[[nodiscard]] bool plan_face(const FaceSpec& spec, Draft& draft);

}  // namespace ncpost::stepnc::features
