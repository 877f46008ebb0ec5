// The sun's brightness at each step of a glare assessment (docs/hazard.md, "The sun's
// brightness"; ../shared/docs/method.md, "Reference illuminance and the contour ladder"):
//   - reference: every step under the profile's reference illuminance, the glare region its
//     limit ellipse (the profile's rows): the assessment as glarecam made it before the sun's
//     brightness was modelled;
//   - clear-sky: the direct normal illuminance E(t) of a clear sky at the site (sun/clear_sky.h,
//     the model the profile's clear-sky sources use): the astronomically possible glare as
//     Germany's LAI counts it, with the real clear sky's brightness;
//   - weather: E(t) from an EnergyPlus weather file (sun/epw_weather.h), interpolated to the step:
//     the glare to *expect* with the site's weather.
// Under a source of illuminance E the glare region at α is the profile's referred contour at
// L_limit(α) · E_ref / E (ProfileTable::regionAtLevel): a dimmer sun's region is smaller, and
// none where that level exceeds the referred peak.
#pragma once

#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "core/error.h"
#include "core/time.h"
#include "hazard/scene.h"
#include "sun/epw_weather.h"

namespace glarecam::hazard {

enum class SunKind { kReference, kClearSky, kWeather };

struct SunBrightness {
  SunKind kind = SunKind::kReference;
  std::shared_ptr<const sun::EpwWeather> weather;  // kWeather's file

  // "reference", "clear-sky", "weather".
  std::string name() const;
  // What the report says: "clear sky (IES RP-21, c = 0.21)", "weather file FILE (CITY)".
  std::string description() const;
};

// `--sun` as given: "reference", "clear-sky" or "weather FILE.epw" (the file read now); kBadInput
// naming the option or the file.
Result<SunBrightness> parseSunBrightness(const std::vector<std::string>& words);

// The direct normal illuminance at a step, lx (0 when the sun is not up, or the weather says
// so), for the sun at apparent elevation `elevation_deg` at `utc` on day `day_of_year` (1–366)
// of the site. Not for kReference.
double sourceIlluminanceLx(const SunBrightness& sun, UtcTime utc, double elevation_deg,
                           int day_of_year, const HazardSite& site);

// The most it can give at the site over a year: a clear sky's at the zenith and the year's
// nearest approach to the sun, or the weather file's largest value.
double maxSourceIlluminanceLx(const SunBrightness& sun, const HazardSite& site);

}  // namespace glarecam::hazard
