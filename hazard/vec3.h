// A direction or a point in the scene's local east–north–up frame (x east, y north, z up), in
// metres for points and unitless for directions, with the few operations the hazard geometry
// needs. A plain value; nothing here allocates.
#pragma once

#include <cmath>

namespace glarecam::hazard {

struct Vec3 {
  double x = 0, y = 0, z = 0;

  friend Vec3 operator+(Vec3 a, Vec3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
  friend Vec3 operator-(Vec3 a, Vec3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
  friend Vec3 operator*(double k, Vec3 a) { return {k * a.x, k * a.y, k * a.z}; }
  friend bool operator==(Vec3 a, Vec3 b) = default;
};

inline double dot(Vec3 a, Vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline Vec3 cross(Vec3 a, Vec3 b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline double norm(Vec3 a) { return std::sqrt(dot(a, a)); }
// `a` scaled to unit length; the zero vector stays zero.
inline Vec3 normalised(Vec3 a) {
  const double length = norm(a);
  return length > 0 ? (1.0 / length) * a : Vec3{};
}
// The angle between two directions in radians, accurate near 0 and π (atan2 of |a×b| and a·b).
inline double angleBetweenRad(Vec3 a, Vec3 b) { return std::atan2(norm(cross(a, b)), dot(a, b)); }

}  // namespace glarecam::hazard
