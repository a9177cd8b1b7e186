#pragma once
// The arithmetic behind the urn:ncpost:ext functions, free of libxslt (ext.cpp wraps it).
// Conventions are documented in docs/xslt-extensions.md.

#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "ncpost/xslt/xslt.hpp"

namespace ncpost::xslt::detail {

// `value` (finite, already scaled) written as `format` says; C locale.
[[nodiscard]] std::string format_number(double value, const NumberFormat& format);
void append_number(std::string& out, double value, const NumberFormat& format);
// The room write_number() may need: DBL_MAX in fixed notation with 12 decimals fits.
inline constexpr std::size_t kNumberRoom = 400;
// append_number() into a buffer with kNumberRoom bytes free at `at`; returns the text's end.
[[nodiscard]] char* write_number(char* at, double value, const NumberFormat& format);

// The quantities ext:format knows, and their formats and scales.
enum class Quantity { Length, Angle, Feed, Speed, Dwell };
[[nodiscard]] std::optional<Quantity> quantity_named(std::string_view name);
// ext:format's scaling: `value` in the program's unit (`program_unit_mm`, for lengths and
// feeds) in the controller's unit and the format's own scale, and the format to write it with.
struct ScaledQuantity {
  double value;
  const NumberFormat* format;
};
[[nodiscard]] ScaledQuantity scale_quantity(const JobConfig& config, double program_unit_mm,
                                            Quantity quantity, double value);
// ext:format: `value` in the program's unit (`program_unit_mm`, for lengths and feeds) scaled
// to the controller's unit and the format's own scale, then appended to `out`; false when the
// scaled value is not finite (then nothing is appended).
[[nodiscard]] bool append_quantity(std::string& out, const JobConfig& config,
                                   double program_unit_mm, Quantity quantity, double value);

// One machine axis (row 0, 1, 2) of the set-up transform of p; a direction (an arc's offset)
// is turned without the translation.
[[nodiscard]] inline double setup_axis(const SetupTransform& s, int row,
                                       const std::array<double, 3>& p, bool translate) {
  const auto r = static_cast<std::size_t>(row) * 3;
  double v = s.matrix[r] * p[0] + s.matrix[r + 1] * p[1] + s.matrix[r + 2] * p[2];
  if (translate) v += s.translation[static_cast<std::size_t>(row)];
  return v;
}

// Shortest text that reads back to the same double (for numbers the functions put in nodes).
[[nodiscard]] std::string shortest(double value);

// An arc in a plane: start, end, centre; turns as the canonical program has them (positive
// counter-clockwise, |turns| - 1 full turns before the arc to the end point, never 0).
struct PlaneArc {
  double sx, sy, ex, ey, cx, cy;
  int turns;
};

// Signed sweep in degrees (positive counter-clockwise), full turns included; nothing for
// turns == 0 or a zero radius.
[[nodiscard]] std::optional<double> arc_sweep(const PlaneArc& arc);
// FANUC's signed R: the radius, negative for a sweep over 180 degrees; nothing for full
// circles (not expressible with R) and the cases arc_sweep refuses.
[[nodiscard]] std::optional<double> arc_radius(const PlaneArc& arc);
// Centre from a signed R (negative: the arc over 180 degrees) and the direction (clockwise or
// not); nothing when the chord is longer than the diameter (beyond a small tolerance) or zero.
[[nodiscard]] std::optional<std::array<double, 2>> arc_centre(double sx, double sy, double ex,
                                                              double ey, double r, bool clockwise);

struct Point3 {
  double x, y, z;
};
// End points of the pieces of the arc (the last is the arc's end), z interpolated linearly
// with the angle (helix). `max_sweep_degrees` > 0: equal pieces of at most that sweep.
[[nodiscard]] std::optional<std::vector<Point3>> arc_split(const PlaneArc& arc, double sz,
                                                           double ez, double max_sweep_degrees,
                                                           std::size_t max_pieces);
// Pieces that end where the arc crosses a quadrant boundary (0, 90, 180, 270 degrees about the
// centre), then the arc's end.
[[nodiscard]] std::optional<std::vector<Point3>> arc_split_quadrants(const PlaneArc& arc, double sz,
                                                                     double ez,
                                                                     std::size_t max_pieces);

// Rotary angles (degrees) that turn the +Z tool axis into (i, j, k) for "AC" (tilt A about X,
// then C about Z) or "BC" (tilt B about Y, then C about Z): tilt in [0, 180], C in (-180, 180].
// For a tool axis along Z (tilt 0 or 180) C is undefined; `previous_c` is kept.
struct Rotary {
  double tilt;
  double c;
  bool singular;
};
[[nodiscard]] std::optional<Rotary> rotary_angles(double i, double j, double k,
                                                  std::string_view kinematics, double previous_c);

// ext:comment: sanitise as the rules say (a replacement loses the characters that could close
// the comment).
[[nodiscard]] std::string sanitize_comment(std::string_view text, const CommentRules& rules);
// Number of characters (UTF-8 code points; an invalid byte counts as one).
[[nodiscard]] std::size_t characters(std::string_view text);

}  // namespace ncpost::xslt::detail
