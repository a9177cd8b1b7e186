#pragma once
// Multi-axis output: a five-axis machine's kinematics (profile::Kinematics, profile.json
// "kinematics") turns the tool axes of the canonical program into positions of its two rotary
// axes, and, without tool-centre-point output, the tool tip into positions of its linear axes.
// docs/kinematics.md states every rule; the renderer applies KinematicsConverter to every call
// before it reaches the stylesheet.
//
// In: a tool axis (i, j, k) in program coordinates, the rotary positions in force.
// Out: rotary positions (degrees, by role: primary and secondary), or why there are none.

#include <optional>
#include <string>
#include <vector>

#include "ncpost/canon/call.hpp"
#include "ncpost/diag/diagnostic.hpp"
#include "ncpost/profile/profile.hpp"

namespace ncpost::render {

// Positions of the machine's two rotary axes in degrees, by role (profile::Kinematics).
struct RotaryPositions {
  double primary = 0;
  double secondary = 0;
  friend bool operator==(const RotaryPositions&, const RotaryPositions&) = default;
};

// One machine's kinematics, without state.
class Kinematics {
 public:
  explicit Kinematics(profile::Kinematics machine);

  [[nodiscard]] const profile::Kinematics& machine() const noexcept { return machine_; }

  // A solution before wrapping and limits: angles in (-180, 180].
  struct Candidate {
    RotaryPositions angles;
    bool singular = false;  // on the pole: the rotating axis's angle is `previous`'s
  };
  // The (one or two) solutions for `axis`; empty when it is no direction (KIN-002).
  [[nodiscard]] std::vector<Candidate> candidates(const canon::Direction& axis,
                                                  const RotaryPositions& previous) const;

  struct Choice {
    std::optional<RotaryPositions> positions;  // none: unreachable or no direction
    bool singular = false;
    std::string refusal;  // why there is none (KIN-001 / KIN-002 text)
    diag::Code code = diag::Code::KinUnreachable;
  };
  // The positions that follow `previous`: each candidate's angles moved by whole turns
  // (continuous axis: nearest to the previous angle; limited axis: nearest within the limits),
  // candidates outside the limits dropped, then the profile's preferred solution.
  [[nodiscard]] Choice choose(const canon::Direction& axis, const RotaryPositions& previous) const;

  // The tool axis (unit, program coordinates) that the positions give: forward kinematics.
  [[nodiscard]] canon::Direction tool_axis(const RotaryPositions& positions) const;
  // The rotary positions in the canonical slots (a, b, c) named by the axes; the third is 0.
  [[nodiscard]] canon::Rotary rotary(const RotaryPositions& positions) const;

  // Where the linear axes go so that the tool tip is at `tip` (program coordinates), with the
  // rotary axes at `positions`, a tool `tool_length` long (measured from the spindle's gauge
  // point along the tool) and the pivots of the profile multiplied by `pivot_scale` (the
  // controller's length unit in program units). With tool-centre-point output: `tip`.
  [[nodiscard]] canon::Point machine_point(const canon::Point& tip,
                                           const RotaryPositions& positions, double tool_length,
                                           double pivot_scale) const;
  // A program direction (an arc's normal) in machine axes: turned by the table axes.
  [[nodiscard]] canon::Direction machine_direction(const canon::Direction& direction,
                                                   const RotaryPositions& positions) const;

 private:
  profile::Kinematics machine_;
};

// The conversion of one program (per job): the rotary positions in force (all 0 at the
// start), the tool length and the program's length unit, followed call by call.
class KinematicsConverter {
 public:
  // `controller_unit_mm`: the controller's length unit in mm (pivots are in it).
  KinematicsConverter(const profile::Kinematics& machine, double controller_unit_mm);

  struct Issue {
    diag::Code code;
    std::string message;
  };
  // Converts `call` in place: motions with a tool axis get the rotary positions that point
  // the tool along it, every point the linear positions (without tool-centre-point output).
  // An error (KIN-001..004) leaves `call` and the state as they were; warnings (KIN-005) are
  // appended to `warnings`.
  [[nodiscard]] std::optional<Issue> convert(canon::Call& call, std::vector<Issue>& warnings);

  [[nodiscard]] const RotaryPositions& positions() const noexcept { return positions_; }
  [[nodiscard]] const Kinematics& kinematics() const noexcept { return kinematics_; }

 private:
  [[nodiscard]] std::optional<Issue> pose(canon::Pose& pose, bool feed,
                                          std::vector<Issue>& warnings);
  [[nodiscard]] std::optional<Issue> same_orientation(const std::optional<canon::Direction>& axis,
                                                      const char* what) const;
  [[nodiscard]] canon::Point to_machine(const canon::Point& p) const;

  Kinematics kinematics_;
  double controller_unit_mm_;
  double program_unit_mm_ = 1.0;
  double tool_length_ = 0;  // program units (USE_TOOL_LENGTH_OFFSET)
  RotaryPositions positions_{};
};

}  // namespace ncpost::render
