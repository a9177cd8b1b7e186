#pragma once
// The readers of feature profiles, shared by the kinds whose boundary is one: a rectangular or
// circular closed profile as a Shape (pockets, outside profiles), a general closed profile or
// an n-gon as an Outline (general pockets and outside profiles), a general profile as the open
// walls of an open pocket; and the checks of a tool against an outline. Each reports what is
// wrong and returns false or nullopt.

#include <optional>
#include <string_view>

#include "outline.hpp"
#include "reader.hpp"
#include "shapes.hpp"

namespace ncpost::stepnc::features {

// A profile's placement in the feature's plane; the identity when it has none. `plane` names the
// plane in the message ("pocket's", "feature's"). Diagnostics: STEPNC-101 a placement out of
// that plane; the geometry reader's for a bad one.
bool read_profile_placement(Reader& reader, const Instance& profile, std::string_view plane,
                            detail::Frame& frame);

// A RECTANGULAR_CLOSED_PROFILE (length along its x axis, width along y, centred on its
// placement, as NIST's ex1/ex1E pair places it) or a CIRCULAR_CLOSED_PROFILE, in the feature's
// coordinates. `corner` is the rectangle's corner radius (0: sharp). Diagnostics: STEPNC-101
// another profile, or one placed out of the plane; STEPNC-103 sizes that are not positive, a
// corner radius beyond half the width.
bool read_closed_profile(Reader& reader, const Instance& boundary, double corner,
                         std::string_view plane, Shape& shape);

// A GENERAL_CLOSED_PROFILE (POLYLINE, TRIMMED_CURVE or COMPOSITE_CURVE of lines and circular
// arcs) or an NGON_CLOSED_PROFILE in the feature's coordinates, counter-clockwise.
// Diagnostics: STEPNC-101 another profile; B-spline pieces; arcs or pieces out of the plane;
// STEPNC-103 more elements or polygon points than FeatureOptions allows; points beyond
// poly::kMaxCoordinate; pieces that do not meet; an outline that does not close; arcs of no
// radius; n-gons without a positive diameter and a whole number of sides; and the curve
// reader's (STEPNC-011, STEPNC-012).
std::optional<Outline> read_closed_outline(Reader& reader, const Instance& boundary);
// The walls of an OPEN_POCKET: a GENERAL_PROFILE's curve, in its own sense (read_closed_outline's
// diagnostics, but for closing).
std::optional<Outline> read_open_outline(Reader& reader, const Instance& boundary);

// The tool against the corners and arcs of a general outline: a corner turning towards the
// material, or an arc curving that way, must take the tool's radius + the side allowance
// (orthogonal_radius, `corner_radius`, rounds a pocket's sharp corners). `material_outside`:
// a pocket's outline (the material beyond it), else an outside profile's. Diagnostics:
// STEPNC-102 a corner or an arc the tool does not fit, with where it is.
bool corner_checks(Reader& reader, const Outline& outline, const Tool& tool,
                   const Operation& operation, double corner_radius, bool material_outside);
// The outline's polygon on the side away from the material, checked simple. Diagnostics:
// STEPNC-103 more points than FeatureOptions::max_polygon_points; a polygon that crosses itself
// or encloses no area.
std::optional<poly::Ring> polygon_of(Reader& reader, const Instance& at, const Outline& outline,
                                     bool material_left);

// The material that ISO 14649's orthogonal_radius (`rho`) adds in a pocket's sharp corners
// (those turning away from the material, where a tool of radius + allowance `d` cannot reach):
// the part of each corner beyond a fillet arc of that radius tangent to both sides, as polygons
// that cover it. Diagnostics: STEPNC-103 two fillets that do not fit on one side between them.
std::optional<poly::Areas> fillet_material(Reader& reader, const Outline& outline, double rho,
                                           double d);

}  // namespace ncpost::stepnc::features
