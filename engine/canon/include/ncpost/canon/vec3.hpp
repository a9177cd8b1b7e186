#pragma once
// A free 3-vector for the arithmetic of readers and converters that work on canonical
// coordinates (the CL reader's arcs and MSYS/, the kinematics' tool axes). The verifier keeps a
// geometry of its own on purpose (docs/verify.md: independent of what it checks).

#include <cmath>

namespace ncpost::canon {

struct Vec3 {
  double x = 0, y = 0, z = 0;
};

[[nodiscard]] inline Vec3 operator+(Vec3 a, Vec3 b) {
  return {a.x + b.x, a.y + b.y, a.z + b.z};
}
[[nodiscard]] inline Vec3 operator-(Vec3 a, Vec3 b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}
[[nodiscard]] inline Vec3 operator*(double s, Vec3 a) {
  return {s * a.x, s * a.y, s * a.z};
}
[[nodiscard]] inline double dot(Vec3 a, Vec3 b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
[[nodiscard]] inline Vec3 cross(Vec3 a, Vec3 b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
[[nodiscard]] inline double length(Vec3 a) {
  return std::sqrt(dot(a, a));
}

}  // namespace ncpost::canon
