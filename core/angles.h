// Degrees at every interface, radians inside the maths (style.md): the one conversion.
#pragma once

#include <numbers>

namespace glarecam {

inline constexpr double kDegreesPerRadian = 180.0 / std::numbers::pi;

constexpr double radians(double degrees) { return degrees / kDegreesPerRadian; }
constexpr double degrees(double radians) { return radians * kDegreesPerRadian; }

}  // namespace glarecam
