// libFuzzer target: an EnergyPlus weather file (EPW, docs/weather-files.md), read by parseEpw()
// as `--sun weather FILE.epw` reads it. When it parses: written again by formatEpw() and read
// back, which must give the same location and every hour's value; asked for the illuminance
// across the year, which must be a number and never negative; its distance to a site taken.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>

#include "sun/epw_weather.h"
#include "tests/fuzz/fuzz_support.h"

namespace {

bool sameLocation(const glarecam::sun::EpwLocation& a, const glarecam::sun::EpwLocation& b) {
  return a.city == b.city && a.state_province == b.state_province && a.country == b.country &&
         a.source == b.source && a.wmo == b.wmo && a.latitude_deg == b.latitude_deg &&
         a.longitude_deg == b.longitude_deg && a.utc_offset_h == b.utc_offset_h &&
         a.elevation_m == b.elevation_m;
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  glarecam::fuzz::silenceLogging();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace glarecam::sun;
  const auto weather = parseEpw(glarecam::fuzz::asText(data, size), "fuzz.epw");
  if (!weather) return 0;
  // What the writer writes, the reader reads.
  const auto again =
      parseEpw(formatEpw(weather->location, weather->direct_normal_illuminance_lx), "again.epw");
  if (!again || !sameLocation(again->location, weather->location) ||
      again->direct_normal_illuminance_lx != weather->direct_normal_illuminance_lx)
    std::abort();
  // Every 7 hours and 13 minutes (coprime to the day) through the year and past both ends.
  for (double hour = -30; hour < 365 * 24 + 30; hour += 7 + 13.0 / 60) {
    const double lx = directNormalIlluminanceLx(*weather, 1, 1, hour);
    if (!(lx >= 0) || lx > kEpwMaxDirectNormalIlluminanceLx) std::abort();
  }
  SiteLocation site;
  site.latitude_deg = 48.0;
  site.longitude_deg = 7.8;
  const double distance_km = distanceKm(weather->location, site);
  if (!(distance_km >= 0) || distance_km > kEarthMeanRadiusKm * 3.1416) std::abort();
  (void)weatherSiteWarning(*weather, site);
  return 0;
}
