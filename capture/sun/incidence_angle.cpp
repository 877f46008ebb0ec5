#include "capture/sun/incidence_angle.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

namespace glarecam::capture {

namespace {

constexpr double kRadPerDeg = std::numbers::pi / 180.0;

// A unit vector (east, north, up) at `elevation_deg` above the horizon towards `azimuth_deg`.
std::array<double, 3> eastNorthUp(double elevation_deg, double azimuth_deg) {
  const double e = elevation_deg * kRadPerDeg, a = azimuth_deg * kRadPerDeg;
  return {std::cos(e) * std::sin(a), std::cos(e) * std::cos(a), std::sin(e)};
}

}  // namespace

double incidenceAngleDeg(const ModuleOrientation& module, const SkyDirection& source) {
  // The normal of a module tilted by t stands 90° − t above the horizon.
  const auto n = eastNorthUp(90.0 - module.tilt_deg, module.azimuth_deg);
  const auto s = eastNorthUp(source.elevation_deg, source.azimuth_deg);
  const double cosine = n[0] * s[0] + n[1] * s[1] + n[2] * s[2];
  return std::acos(std::clamp(cosine, -1.0, 1.0)) / kRadPerDeg;
}

}  // namespace glarecam::capture
