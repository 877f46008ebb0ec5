// The angle of incidence α between a module's normal and the direction of the light source (the
// sun, or a lab lamp), method.md's α. Directions are horizontal coordinates: elevation above the
// horizon and azimuth clockwise from north, in degrees. A module is its tilt from horizontal and
// the azimuth it faces (the horizontal projection of its normal), so a south-facing module tilted
// 30° has normal (tilt 30, azimuth 180). α = acos(n · s); above 90° the source is behind it.
#pragma once

#include <array>

namespace glarecam::sun {

struct SkyDirection {
  double elevation_deg = 0.0;
  double azimuth_deg = 0.0;  // clockwise from north
};

struct ModuleOrientation {
  double tilt_deg = 0.0;     // normal vs vertical: 0 = lying flat, 90 = vertical
  double azimuth_deg = 0.0;  // where the normal points, clockwise from north
};

// The unit vector (east, north, up) of a direction.
std::array<double, 3> eastNorthUp(const SkyDirection& direction);

double incidenceAngleDeg(const ModuleOrientation& module, const SkyDirection& source);

}  // namespace glarecam::sun
