// throng::core::Vec2 — a 2D vector in metres (positions) or metres per second (velocities).
// Single precision: the hot simulation columns are float, as Recast/Detour and RVO2.
#pragma once
#include <cmath>

namespace throng::core {

struct Vec2 {
  float x = 0.0f;
  float y = 0.0f;

  constexpr Vec2() = default;
  constexpr Vec2(float xIn, float yIn) : x(xIn), y(yIn) {}

  constexpr Vec2 operator+(Vec2 o) const { return {x + o.x, y + o.y}; }
  constexpr Vec2 operator-(Vec2 o) const { return {x - o.x, y - o.y}; }
  constexpr Vec2 operator-() const { return {-x, -y}; }
  constexpr Vec2 operator*(float s) const { return {x * s, y * s}; }
  constexpr Vec2 operator/(float s) const { return {x / s, y / s}; }
  constexpr Vec2& operator+=(Vec2 o) { x += o.x; y += o.y; return *this; }
  constexpr Vec2& operator-=(Vec2 o) { x -= o.x; y -= o.y; return *this; }
  constexpr Vec2& operator*=(float s) { x *= s; y *= s; return *this; }
  constexpr bool operator==(const Vec2&) const = default;
};

constexpr Vec2 operator*(float s, Vec2 v) { return {v.x * s, v.y * s}; }
constexpr float dot(Vec2 a, Vec2 b) { return a.x * b.x + a.y * b.y; }
/// z component of the 3D cross product (a, 0) x (b, 0): the determinant det(a, b).
constexpr float cross(Vec2 a, Vec2 b) { return a.x * b.y - a.y * b.x; }
constexpr float lengthSq(Vec2 v) { return dot(v, v); }
inline float length(Vec2 v) { return std::sqrt(lengthSq(v)); }
inline float distance(Vec2 a, Vec2 b) { return length(a - b); }
inline Vec2 normalize(Vec2 v) {
  const float l = length(v);
  return l > 0.0f ? v / l : Vec2{};
}
/// v rotated by +90 degrees.
constexpr Vec2 perp(Vec2 v) { return {-v.y, v.x}; }

}  // namespace throng::core
