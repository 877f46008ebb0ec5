#include "hazard/sun_brightness.h"

#include <algorithm>
#include <cmath>

#include "sun/clear_sky.h"

namespace glarecam::hazard {
namespace {

// IES RP-21's extraterrestrial illuminance peaks at perihelion, day 2 of the year (its cosine's
// phase, sun/clear_sky.h).
constexpr int kPerihelionDay = 2;
constexpr double kZenithDeg = 90;

}  // namespace

std::string SunBrightness::name() const {
  switch (kind) {
    case SunKind::kReference:
      return "reference";
    case SunKind::kClearSky:
      return "clear-sky";
    case SunKind::kWeather:
      return "weather";
  }
  return "reference";
}

std::string SunBrightness::description() const {
  switch (kind) {
    case SunKind::kReference:
      return "the profile's reference illuminance at every step";
    case SunKind::kClearSky:
      return "a clear sky's direct normal illuminance (IES RP-21, c = 0.21, Kasten & Young air "
             "mass)";
    case SunKind::kWeather:
      return "the direct normal illuminance of the weather file " +
             (weather ? weather->path.string() + " (" + weather->location.city + ")"
                      : std::string());
  }
  return {};
}

Result<SunBrightness> parseSunBrightness(const std::vector<std::string>& words) {
  SunBrightness sun;
  const std::string first = words.empty() ? std::string() : words[0];
  if (first == "reference" || first == "clear-sky") {
    if (words.size() != 1)
      return badInput("--sun " + first + " takes no file (only \"weather FILE.epw\" does)");
    sun.kind = first == "reference" ? SunKind::kReference : SunKind::kClearSky;
    return sun;
  }
  if (first == "weather") {
    if (words.size() != 2 || words[1].empty())
      return badInput("--sun weather needs the weather file: --sun weather FILE.epw");
    sun::EpwWeather weather;
    GLARECAM_ASSIGN(weather, sun::readEpw(words[1]));
    sun.kind = SunKind::kWeather;
    sun.weather = std::make_shared<const sun::EpwWeather>(std::move(weather));
    return sun;
  }
  return badInput("--sun \"" + first + "\" is not one of reference, clear-sky, weather FILE.epw");
}

double sourceIlluminanceLx(const SunBrightness& sun, UtcTime utc, double elevation_deg,
                           int day_of_year, const HazardSite& site) {
  if (elevation_deg <= 0) return 0;
  switch (sun.kind) {
    case SunKind::kReference:
      return 0;
    case SunKind::kClearSky: {
      const std::optional<sun::ClearSkyIlluminance> clear =
          sun::clearSkyIlluminance(elevation_deg, day_of_year, site.location.altitude_m);
      return clear ? clear->illuminance_lx : 0;
    }
    case SunKind::kWeather: {
      const double lx = sun::directNormalIlluminanceLx(*sun.weather, utc);
      return std::isfinite(lx) ? lx : 0;
    }
  }
  return 0;
}

double maxSourceIlluminanceLx(const SunBrightness& sun, const HazardSite& site) {
  switch (sun.kind) {
    case SunKind::kReference:
      return 0;
    case SunKind::kClearSky: {
      const std::optional<sun::ClearSkyIlluminance> clear =
          sun::clearSkyIlluminance(kZenithDeg, kPerihelionDay, site.location.altitude_m);
      return clear ? clear->illuminance_lx : 0;
    }
    case SunKind::kWeather: {
      const std::vector<double>& values = sun.weather->direct_normal_illuminance_lx;
      return values.empty() ? 0 : *std::max_element(values.begin(), values.end());
    }
  }
  return 0;
}

}  // namespace glarecam::hazard
