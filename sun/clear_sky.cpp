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

namespace {

int dayOfYear(UtcTime utc) {
  const auto day = std::chrono::floor<std::chrono::days>(utc);
  const std::chrono::year_month_day date{day};
  return static_cast<int>((day - std::chrono::sys_days{date.year() / 1 / 1}).count()) + 1;
}

// The estimate as a source; `where` begins the message when the sun is down.
Result<SourceIlluminance> clearSkySourceAt(double elevation_deg, UtcTime utc, double altitude_m,
                                           const std::string& where) {
  const std::optional<ClearSkyIlluminance> sky =
      clearSkyIlluminance(elevation_deg, dayOfYear(utc), altitude_m);
  if (!sky)
    return badInput(fmt::format(
        "{}: the sun is {:.1f}° below the horizon at {}: no direct light for a clear-sky estimate",
        where, -elevation_deg, formatIsoSeconds(utc)));
  return SourceIlluminance{
      .illuminance_lx = sky->illuminance_lx,
      .illuminance_u_lx = sky->illuminance_u_lx,
      .origin = IlluminanceOrigin::kClearSky,
      .instrument = fmt::format("clear sky (IES RP-21, c = {}), sun at {:.1f}°",
                                kIesClearSkyExtinction, elevation_deg)};
}

}  // namespace

Result<SourceIlluminance> clearSkySource(UtcTime utc, const SiteLocation& site) {
  SolarPosition sun;
  GLARECAM_ASSIGN(sun, solarPosition(utc, site));
  return clearSkySourceAt(sun.elevation_deg, utc, site.altitude_m, "clear sky");
}

Result<SourceIlluminance> clearSkySourceOfStack(const StackManifest& manifest) {
  const std::string stack = manifest.id.value_or("the stack");
  const nlohmann::json* geometry =
      manifest.source.contains("geometry") ? &manifest.source["geometry"] : nullptr;
  if (!geometry || !geometry->is_object() || !geometry->contains("sun_elevation_deg") ||
      !(*geometry)["sun_elevation_deg"].is_number() || !geometry->contains("time") ||
      !(*geometry)["time"].is_string())
    return badInput(fmt::format(
        "{}: its geometry records no sun (a lab lamp, or no [site]): no clear-sky estimate; give "
        "--source-illuminance LX",
        stack));
  UtcTime time;
  GLARECAM_ASSIGN(time, parseIsoTime((*geometry)["time"].get<std::string>()));
  return clearSkySourceAt((*geometry)["sun_elevation_deg"].get<double>(), time, 0.0, stack);
}

}  // namespace glarecam::sun
