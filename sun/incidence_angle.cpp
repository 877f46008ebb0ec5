#include "sun/incidence_angle.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "core/angles.h"

namespace glarecam::sun {

namespace {

// A unit vector (east, north, up) at `elevation_deg` above the horizon towards `azimuth_deg`.
std::array<double, 3> eastNorthUp(double elevation_deg, double azimuth_deg) {
  const double e = radians(elevation_deg), a = radians(azimuth_deg);
  return {std::cos(e) * std::sin(a), std::cos(e) * std::cos(a), std::sin(e)};
}

}  // namespace

double incidenceAngleDeg(const ModuleOrientation& module, const SkyDirection& source) {
  // The normal of a module tilted by t stands 90° − t above the horizon.
  const auto n = eastNorthUp(90.0 - module.tilt_deg, module.azimuth_deg);
  const auto s = eastNorthUp(source.elevation_deg, source.azimuth_deg);
  const double cosine = n[0] * s[0] + n[1] * s[1] + n[2] * s[2];
  return degrees(std::acos(std::clamp(cosine, -1.0, 1.0)));
}

}  // namespace glarecam::sun
