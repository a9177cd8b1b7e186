#pragma once
// The tests' own forward kinematics of a five-axis machine (profile::Kinematics): from the
// positions a post writes (linear axes, rotary axes) back to the tool axis and the tool tip in
// program coordinates, as the machine moves them. Written with rotation matrices along the
// machine's chains, independently of engine/render/kinematics.cpp (which solves the inverse
// problem in another form), so that a post re-read through it checks the engine.

#include <array>
#include <cmath>
#include <numbers>
#include <vector>

#include "ncpost/canon/call.hpp"
#include "ncpost/profile/profile.hpp"

namespace ncpost::test {

using Vector3 = std::array<double, 3>;
using Matrix3 = std::array<Vector3, 3>;

// The rotation by `degrees` about a machine axis, right-hand rule.
inline Matrix3 rotation(profile::MachineAxis axis, double degrees) {
  const double r = degrees * std::numbers::pi / 180.0;
  const double c = std::cos(r), s = std::sin(r);
  switch (axis) {
    case profile::MachineAxis::X:
      return {{{1, 0, 0}, {0, c, -s}, {0, s, c}}};
    case profile::MachineAxis::Y:
      return {{{c, 0, s}, {0, 1, 0}, {-s, 0, c}}};
    case profile::MachineAxis::Z:
      break;
  }
  return {{{c, -s, 0}, {s, c, 0}, {0, 0, 1}}};
}

inline Vector3 matrix_times(const Matrix3& m, const Vector3& v) {
  Vector3 out{};
  for (std::size_t r = 0; r < 3; ++r) out[r] = m[r][0] * v[0] + m[r][1] * v[1] + m[r][2] * v[2];
  return out;
}

inline Matrix3 transposed(const Matrix3& m) {
  Matrix3 t{};
  for (std::size_t r = 0; r < 3; ++r)
    for (std::size_t c = 0; c < 3; ++c) t[r][c] = m[c][r];
  return t;
}

inline Vector3 plus(const Vector3& a, const Vector3& b) {
  return {a[0] + b[0], a[1] + b[1], a[2] + b[2]};
}
inline Vector3 minus(const Vector3& a, const Vector3& b) {
  return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}
inline Vector3 scaled(double s, const Vector3& a) {
  return {s * a[0], s * a[1], s * a[2]};
}

// The angle of the rotary axis `name` in the canonical slots.
inline double angle_of(const canon::Rotary& r, char name) {
  return name == 'A' ? r.a : name == 'B' ? r.b : r.c;
}

struct ToolPose {
  Vector3 tip{};
  Vector3 axis{};  // unit, from the tip towards the spindle
};

// One rotary joint of a chain: its turn (as a matrix) and a point of its axis.
struct Joint {
  Matrix3 turn;
  Vector3 through;
};

// Where the machine's tool tip and axis are, in program coordinates, when its linear axes are
// at `linear` (program units) and its rotary axes at `rotary`, with a tool `tool_length` long
// and the profile's pivots times `pivot_scale`. Without tool-centre-point control the control
// puts the programmed point where the tip would be with the head at 0 (G43 along Z); with it,
// `linear` is the tip itself.
inline ToolPose forward(const profile::Kinematics& k, const Vector3& linear,
                        const canon::Rotary& rotary, double tool_length, double pivot_scale = 1) {
  const auto joint = [&](const profile::RotaryAxis& a) {
    return Joint{rotation(a.axis, a.direction * angle_of(rotary, a.name)),
                 scaled(pivot_scale, a.pivot)};
  };
  // Chains from the machine base outwards.
  std::vector<Joint> head, table;
  switch (k.type) {
    case profile::KinematicsType::HeadHead:
      head = {joint(k.primary), joint(k.secondary)};
      break;
    case profile::KinematicsType::TableTable:
      table = {joint(k.primary), joint(k.secondary)};
      break;
    case profile::KinematicsType::HeadTable:
      head = {joint(k.primary)};
      table = {joint(k.secondary)};
      break;
  }
  // The tool: a point on the spindle's side of the innermost head joint moves by each joint,
  // innermost first.
  Vector3 axis{0, 0, 1};
  Vector3 tip_from_gauge{0, 0, -tool_length};
  for (auto j = head.rbegin(); j != head.rend(); ++j) {
    axis = matrix_times(j->turn, axis);
    tip_from_gauge = plus(matrix_times(j->turn, minus(tip_from_gauge, j->through)), j->through);
  }
  Vector3 tip =
      k.tool_centre_point ? linear : plus(plus(linear, Vector3{0, 0, tool_length}), tip_from_gauge);
  // The workpiece: undo the table joints, outermost first, for the tip and the axis.
  for (const Joint& j : table) {
    const Matrix3 back = transposed(j.turn);
    axis = matrix_times(back, axis);
    if (!k.tool_centre_point) tip = plus(matrix_times(back, minus(tip, j.through)), j.through);
  }
  return {tip, axis};
}

}  // namespace ncpost::test
