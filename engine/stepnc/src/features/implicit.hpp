#pragma once
// Values a program from another system leaves implicit, which the feature readers fill in the
// tolerant mode (the default; `--strict` reads the file as written), each with a note naming the
// instance and the value assumed, which the posted program carries as a comment at the
// workingstep (docs/interoperability.md, "Implicit values"):
//
// - INTEROP-003: a hole whose depth plane is '$' and whose bottom is THROUGH_BOTTOM_CONDITION
//   goes through the workpiece: its depth is where its axis leaves the workpiece's bounding
//   BLOCK (its_bounding_geometry, else its raw piece's); INTEROP-008 when there is no block;
// - INTEROP-004: a drilling-type operation without a cutting_depth goes to the hole's depth
//   (and bottom), which the reader takes;
// - INTEROP-005: a polyline of a closed profile that ends away from its first point is closed
//   with a straight line back to it.

#include <optional>

#include "../geometry.hpp"
#include "report.hpp"

namespace ncpost::stepnc::features {

class Reader;

// Where a ray from `from` along `direction` (unit) leaves the box [0, size] of `box` (a frame in
// the same coordinates as `from`); nullopt when it misses the box or leaves it at or behind
// `from`. Pure: unit-tested.
[[nodiscard]] std::optional<double> exit_distance(const detail::Frame& box, detail::Vec3 size,
                                                  detail::Vec3 from, detail::Vec3 direction);

// The depth of the feature being read when its depth plane is '$': true when it is a through
// hole in the tolerant mode, with `depth` set (INTEROP-003) or, after an INTEROP-008, unset;
// false otherwise (the caller reports the missing depth).
[[nodiscard]] bool implicit_through_depth(Reader& reader, std::optional<double>& depth);

// INTEROP-004 when the operation leaves cutting_depth unset (tolerant mode): the tool's tip
// goes to `bottom_z` (negative, below the top) of the hole.
void note_implicit_cutting_depth(Reader& reader, double bottom_z);

// INTEROP-005 about `curve` of `profile`, closed across `gap` mm; true in the tolerant mode,
// false in the strict one (then the caller refuses the open profile).
[[nodiscard]] bool close_implicitly(Reader& reader, const p21::Instance& profile,
                                    const p21::Instance& curve, double gap);

}  // namespace ncpost::stepnc::features
