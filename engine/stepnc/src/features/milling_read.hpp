#pragma once
// What the 2.5D milling readers share: the stepover and the depth levels an operation asks for,
// the checks of the tool against them and against a floor fillet, the approach and retract
// strategies, and the sense of the rings round a wall. Each reports what is wrong and returns
// false (or nullopt).

#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "reader.hpp"

namespace ncpost::stepnc::features {

// Stepover from the strategy's overlap (ISO 14649-11: the share of the tool diameter that
// neighbouring passes have in common; 0.5 when unset) and the operation's radial depth,
// whichever is smaller. Diagnostics: STEPNC-103 an overlap that is not a number.
double stepover(Reader& reader, const Tool& tool, const Operation& operation, double& overlap);
// Diagnostics: STEPNC-103 an overlap outside [0, 1).
bool check_overlap(Reader& reader, const Operation& operation, double overlap);
// The cutting edge must take the deepest level step (the wall height cut at once).
// Diagnostics: STEPNC-102 a cutting edge shorter than that.
bool check_edge(Reader& reader, const Tool& tool, const std::vector<double>& z);

// The workingstep's operation is a roughing one (BOTTOM_AND_SIDE_ROUGH_MILLING,
// SIDE_ROUGH_MILLING, PLANE_ROUGH_MILLING): what it cannot reach is the finishing pass's.
[[nodiscard]] bool roughing(Reader& reader);
// The tool's corner radius makes a floor fillet (planar_radius), within its tolerance.
// Diagnostics: STEPNC-102 a corner radius larger than the fillet (+ allowance), or smaller.
bool check_fillet(Reader& reader, const Tool& tool, const Operation& operation,
                  const Toleranced& fillet);
// Axial levels down to `depth`; allow_multiple_passes .F. asks for the whole depth at once.
// Diagnostics: STEPNC-102 one pass asked for a depth beyond the axial depth; STEPNC-103 more
// levels than FeatureOptions::max_moves.
std::optional<std::vector<double>> depth_levels(Reader& reader, const Operation& operation,
                                                double depth);

// Reads a PLUNGE_STRATEGY (approach or retract) into `entry`, which keeps its defaults for the
// values the strategy leaves unset. Diagnostics: STEPNC-101 a strategy that is not a plunge
// strategy; STEPNC-103 an angle outside (0, 90) degrees.
bool read_plunge(Reader& reader, const Instance& strategy, std::string_view role, Entry& entry);
// The operation's approach, else a helix of FeatureOptions' default size (read_plunge's
// diagnostics).
bool read_entry(Reader& reader, const Operation& operation, const Tool& tool, Entry& entry);
// The operation's retract: its strategy, taking the approach's radius and angle where it leaves
// them unset (the approach run backwards); straight up when the operation names none
// (read_plunge's diagnostics).
bool read_exit(Reader& reader, const Operation& operation, const Entry& entry, Entry& exit);

// The approach and retract of passes that start and end in the air (faces, steps, outside
// profiles), where the tool goes down and up along its axis whatever they say.
// Diagnostics: STEPNC-101 an approach or retract that is not a plunge strategy; STEPNC-016 one
// that is not PLUNGE_TOOLAXIS, the strategy's name followed by what `note` says of it (called
// with true for the approach, false for the retract; no note when `note` is empty).
bool check_air_plunges(Reader& reader, const Operation& operation,
                       const std::function<std::string(bool approach)>& note = {});

// The sense of the rings round a wall: counter-clockwise or not, from rotation_direction, else
// cutmode (climb when unset) and the spindle's direction. `wall_outside`: a pocket's wall is
// outside its rings, an outside profile's part inside. Diagnostics: STEPNC-016 a
// rotation_direction that mills the other way than the cutmode asks, unless `note_conflict` is
// false (slots along their course, outside profiles with a closed-form ring: as they always
// were).
bool rings_ccw(Reader& reader, const Operation& operation, bool wall_outside,
               bool note_conflict = true);

// The largest step (radians) between two ball centres on a circle of radius rc (a ball of
// radius r in a concave circle of radius rc + r: a slot's partial circle, a hole's spherical
// bottom along a meridian) that leaves a cusp of at most h.
[[nodiscard]] double scallop_step(double rc, double r, double h);

}  // namespace ncpost::stepnc::features
