#include "sun/clear_sky.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/angles.h"

namespace glarecam::sun {
namespace {

// Above this elevation the stated uncertainty is kClearSkyRelativeUncertainty; below it, it grows
// linearly to kClearSkyRelativeUncertaintyHorizon at 0°.
constexpr double kLowSunElevationDeg = 10.0;

}  // namespace

double relativeAirMass(double elevation_deg) {
  // Kasten & Young (1989), equation (3), with the elevation in degrees.
  return 1.0 /
         (std::sin(radians(elevation_deg)) + 0.50572 * std::pow(elevation_deg + 6.07995, -1.6364));
}

std::optional<ClearSkyIlluminance> clearSkyIlluminance(double elevation_deg, int day_of_year,
                                                       double altitude_m) {
  if (!(elevation_deg > 0) || elevation_deg > 90) return std::nullopt;
  const double eccentricity =
      1.0 + 0.034 * std::cos(2.0 * std::numbers::pi * (day_of_year - 2) / 365.0);
  const double air_mass =
      relativeAirMass(elevation_deg) * std::exp(-altitude_m / kAirMassScaleHeightM);
  ClearSkyIlluminance sky;
  sky.air_mass = air_mass;
  sky.illuminance_lx = kIesExtraterrestrialIlluminanceLx * eccentricity *
                       std::exp(-kIesClearSkyExtinction * air_mass);
  const double low = std::clamp(1.0 - elevation_deg / kLowSunElevationDeg, 0.0, 1.0);
  const double relative =
      kClearSkyRelativeUncertainty +
      low * (kClearSkyRelativeUncertaintyHorizon - kClearSkyRelativeUncertainty);
  sky.illuminance_u_lx = relative * sky.illuminance_lx;
  return sky;
}

Result<SourceIlluminance> clearSkySource(std::chrono::sys_time<std::chrono::microseconds> utc,
                                         const SiteLocation& site) {
  SolarPosition sun;
  GLARECAM_ASSIGN(sun, solarPosition(utc, site));
  const auto day = std::chrono::floor<std::chrono::days>(utc);
  const std::chrono::year_month_day date{day};
  const int day_of_year =
      static_cast<int>((day - std::chrono::sys_days{date.year() / 1 / 1}).count()) + 1;
  const std::optional<ClearSkyIlluminance> sky =
      clearSkyIlluminance(sun.elevation_deg, day_of_year, site.altitude_m);
  if (!sky)
    return badInput(fmt::format(
        "the sun is {:.1f}° below the horizon at {}: no direct light for a clear-sky estimate",
        -sun.elevation_deg, formatIsoSeconds(utc)));
  SourceIlluminance source;
  source.illuminance_lx = sky->illuminance_lx;
  source.illuminance_u_lx = sky->illuminance_u_lx;
  source.origin = IlluminanceOrigin::kClearSky;
  source.instrument = fmt::format("clear sky (IES RP-21, c = {}), sun at {:.1f}°",
                                  kIesClearSkyExtinction, sun.elevation_deg);
  return source;
}

}  // namespace glarecam::sun
