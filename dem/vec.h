// Small fixed-size vectors for the DEM inner loops. Vec4 packs a 3-vector
// with one extra per-particle scalar (radius, inverse mass, inverse moment of
// inertia) so that a neighbour access touches a single 32-byte line, as
// HOOMD-blue's Scalar4 position-and-type does.
#pragma once

#include <cmath>

namespace granasym::dem {

struct Vec3 {
  double x = 0, y = 0, z = 0;
};

struct alignas(32) Vec4 {
  double x = 0, y = 0, z = 0, w = 0;
};

inline Vec3 operator+(Vec3 a, Vec3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline Vec3 operator-(Vec3 a, Vec3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline Vec3 operator*(double s, Vec3 a) { return {s * a.x, s * a.y, s * a.z}; }
inline double Dot(Vec3 a, Vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline Vec3 Cross(Vec3 a, Vec3 b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline double Norm(Vec3 a) { return std::sqrt(Dot(a, a)); }
inline Vec3 Xyz(const Vec4& a) { return {a.x, a.y, a.z}; }

}  // namespace granasym::dem
