#include "sun/solar_track.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>

#include "core/angles.h"
#include "sun/incidence_angle.h"

namespace glarecam::sun {
namespace {

using std::chrono::microseconds;

UtcTime yearStart(int year) {
  return std::chrono::time_point_cast<microseconds>(
      std::chrono::sys_days{std::chrono::year{year} / 1 / 1});
}

double angleDeg(const SunDirection& d, const SolarPosition& p) {
  const auto [x, y, z] = eastNorthUp({p.elevation_deg, p.azimuth_deg});
  const double cross =
      std::hypot(d.north * z - d.up * y, d.up * x - d.east * z, d.east * y - d.north * x);
  return degrees(std::atan2(cross, d.east * x + d.north * y + d.up * z));
}

// The largest angle between the track and full SPA over a year of minutes, every 7th minute (and
// so every minute of the day over the year), above the horizon and below it.
double worstOverAYear(int year, const SiteLocation& site, const SolarPositionOptions& options) {
  const microseconds minute(60'000'000);
  const std::size_t minutes = (std::chrono::year{year}.is_leap() ? 366 : 365) * 1440;
  const auto track = solarTrack(yearStart(year), minute, minutes, site, options);
  EXPECT_TRUE(track) << track.error().message;
  if (!track) return 1e9;
  double worst = 0;
  for (std::size_t i = 0; i < minutes; i += 7) {
    const SunDirection& d = (*track)[i];
    EXPECT_NEAR(std::hypot(d.east, d.north, d.up), 1, 1e-12);
    const auto spa =
        solarPosition(yearStart(year) + minute * static_cast<std::int64_t>(i), site, options);
    worst = std::max(worst, angleDeg(d, *spa));
  }
  return worst;
}

TEST(SolarTrack, WithinItsToleranceOfFullSpaOverAYear) {
  SiteLocation zurich{.latitude_deg = 47.37,
                      .longitude_deg = 8.54,
                      .altitude_m = 410,
                      .pressure_hpa = 965,
                      .temperature_c = 12};
  EXPECT_LT(worstOverAYear(2027, zurich, {}), kSolarTrackToleranceDeg);
  // Southern, high, far west, a leap year, no refraction.
  SiteLocation south{.latitude_deg = -66.5,
                     .longitude_deg = -170.2,
                     .altitude_m = 2500,
                     .pressure_hpa = 750,
                     .temperature_c = -10};
  EXPECT_LT(worstOverAYear(2028, south,
                           {.delta_t_s = std::nullopt, .delta_ut1_s = 0.3, .refraction = false}),
            kSolarTrackToleranceDeg);
}

TEST(SolarTrack, RefractionLiftsTheSunAsSpaDoes) {
  const SiteLocation site{.latitude_deg = 39.742476,
                          .longitude_deg = -105.1786,
                          .altitude_m = 1830.14,
                          .pressure_hpa = 820,
                          .temperature_c = 11};
  const UtcTime sunrise = yearStart(2026) + std::chrono::days(171) + std::chrono::hours(11) +
                          std::chrono::minutes(40);  // near sunrise in Golden, Colorado
  const auto with = solarTrack(sunrise, microseconds(10'000'000), 120, site, {});
  const auto without =
      solarTrack(sunrise, microseconds(10'000'000), 120, site,
                 {.delta_t_s = std::nullopt, .delta_ut1_s = 0, .refraction = false});
  ASSERT_TRUE(with && without);
  for (std::size_t i = 0; i < 120; ++i) {
    const auto spa =
        solarPosition(sunrise + microseconds(10'000'000 * static_cast<std::int64_t>(i)), site);
    EXPECT_NEAR(degrees(std::asin((*with)[i].up)), spa->elevation_deg, kSolarTrackToleranceDeg);
    EXPECT_NEAR(degrees(std::asin((*without)[i].up)), spa->true_elevation_deg,
                kSolarTrackToleranceDeg);
  }
}

TEST(SolarTrack, RefusesBadInput) {
  const SiteLocation site{.latitude_deg = 47, .longitude_deg = 8};
  EXPECT_EQ(solarTrack(yearStart(2027), microseconds(0), 10, site).error().code,
            ErrorCode::kBadInput);
  EXPECT_EQ(solarTrack(yearStart(2027), microseconds(-60), 10, site).error().code,
            ErrorCode::kBadInput);
  const auto far = solarTrack(yearStart(6000), std::chrono::hours(24 * 400), 2, site);
  ASSERT_FALSE(far);
  EXPECT_NE(far.error().message.find("outside SPA's range"), std::string::npos);
  const auto bad_site =
      solarTrack(yearStart(2027), microseconds(60'000'000), 10, {.latitude_deg = 95});
  ASSERT_FALSE(bad_site);
  EXPECT_NE(bad_site.error().message.find("latitude 95"), std::string::npos);
  EXPECT_TRUE(solarTrack(yearStart(2027), microseconds(60'000'000), 0, site)->empty());
}

}  // namespace
}  // namespace glarecam::sun
