#pragma once
// Units that do not add up (docs/interoperability.md, "Units"): a technology's spindle speed and
// feed cross-checked against what else the program says about them. ISO 14649 writes a spindle
// speed in revolutions per second, a cutting speed and a feed in metres per second and a feed per
// tooth in millimetres; other systems write rpm, m/min or mm/min in the same attributes, and a
// post then asks for 138,465 rpm. Each value is read in its ISO unit and in the unit others
// write; a pair agrees when the one predicts the other within a factor of kAgreement:
//
// - spindle n and cutting speed v on a tool of diameter d: v = pi * d * n, at a plausible n
//   (below);
// - feed f and feed per tooth fz on a tool of z teeth: f = fz * z * n;
// - a value with nothing to check it against: plausible when the tool's surface speed lies in
//   [kMinSurfaceSpeed, kMaxSurfaceSpeed] and the spindle is at most kMaxRpm, a feed in
//   [kMinFeed, kMaxFeed].
//
// When the ISO reading fits, nothing changes. When only another reading fits, it is taken, with
// a note naming the value and both readings (INTEROP-006). When none fits, an error names both
// values (INTEROP-007) and the values are kept as written. Pure: no model, so unit tests drive it.

#include <optional>
#include <string>
#include <vector>

namespace ncpost::stepnc::units {

inline constexpr double kAgreement = 2.0;          // readings agree within this factor
inline constexpr double kMinSurfaceSpeed = 0.005;  // m/s (0.3 m/min): slower cuts nothing
inline constexpr double kMaxSurfaceSpeed = 25.0;   // m/s (1500 m/min): beyond high-speed milling
inline constexpr double kMaxRpm = 100000.0;        // beyond the spindles of machining centres
inline constexpr double kMinFeed = 0.1;            // mm/min
inline constexpr double kMaxFeed = 100000.0;       // mm/min (100 m/min)

// A technology as the file writes it (ISO 14649 units); unset: not written.
struct Written {
  std::optional<double> spindle;         // rev/s, signed (negative: clockwise)
  std::optional<double> cutspeed;        // m/s
  std::optional<double> feed;            // m/s
  std::optional<double> feed_per_tooth;  // mm
};

// What the tool says: its cutting diameter (mm) and number of teeth, when known.
struct ToolSize {
  std::optional<double> diameter;
  std::optional<int> teeth;
};

struct Reading {
  std::optional<double> spindle;    // rev/s to use, signed as written
  std::optional<double> feed;       // m/s to use
  std::vector<std::string> notes;   // INTEROP-006: "<attribute> <value> read as ..."
  std::vector<std::string> errors;  // INTEROP-007: both values named
};

[[nodiscard]] Reading cross_check(const Written& written, const ToolSize& tool);

}  // namespace ncpost::stepnc::units
