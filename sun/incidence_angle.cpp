#include "sun/incidence_angle.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "core/angles.h"

namespace glarecam::sun {

std::array<double, 3> eastNorthUp(const SkyDirection& direction) {
  const double e = radians(direction.elevation_deg), a = radians(direction.azimuth_deg);
  return {std::cos(e) * std::sin(a), std::cos(e) * std::cos(a), std::sin(e)};
}

double incidenceAngleDeg(const ModuleOrientation& module, const SkyDirection& source) {
  // The normal of a module tilted by t stands 90° − t above the horizon.
  const auto n = eastNorthUp({90.0 - module.tilt_deg, module.azimuth_deg});
  const auto s = eastNorthUp(source);
  const double cosine = n[0] * s[0] + n[1] * s[1] + n[2] * s[2];
  return degrees(std::acos(std::clamp(cosine, -1.0, 1.0)));
}

}  // namespace glarecam::sun
