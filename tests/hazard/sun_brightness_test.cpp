#include "hazard/sun_brightness.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>

#include "core/angles.h"
#include "hazard/hazard_calculation.h"
#include "sun/clear_sky.h"
#include "tests/hazard/hazard_fixtures.h"
#include "tests/support/test_support.h"

namespace glarecam::hazard {
namespace {

using std::chrono::microseconds;
using testing::ladderProfile;
using testing::sceneOf;
using testing::zurichSite;

constexpr int kBrightYear = 2027;
constexpr int kBrightApril20 = 109;
const Vec3 kSouthFacing30 = normalised({0, -0.5, std::sqrt(3.0) / 2});

sun::EpwLocation zurichStation() {
  sun::EpwLocation location;
  location.city = "Zurich";
  location.latitude_deg = 47.37;
  location.longitude_deg = 8.54;
  location.utc_offset_h = 1;
  location.elevation_m = 410;
  return location;
}

// A weather file of the given hourly values, read back as glarecam reads one.
SunBrightness weatherOf(const std::vector<double>& values, glarecam::testing::TempDir& dir) {
  const std::filesystem::path path = dir / "weather.epw";
  glarecam::testing::writeText(path, sun::formatEpw(zurichStation(), values));
  const Result<SunBrightness> sun = parseSunBrightness({"weather", path.string()});
  if (!sun) throw std::runtime_error(sun.error().message);
  return *sun;
}

// The noon sun of 20 April at the Zürich site, by SPA at 12:25 local standard time.
Vec3 noonSun() {
  const auto utc = std::chrono::time_point_cast<microseconds>(
                       std::chrono::sys_days{std::chrono::year{kBrightYear} / 4 / 20}) +
                   std::chrono::minutes(11 * 60 + 25);
  const auto position = sun::solarPosition(utc, zurichSite().location);
  return testing::unitToward(position->elevation_deg, position->azimuth_deg);
}

// An observer at the origin sees an 8 m array 60 m away glare around noon on 20 April.
Scene noonScene() {
  const Vec3 sun = noonSun();
  const Vec3 c = sun - 2 * dot(kSouthFacing30, sun) * kSouthFacing30;
  return sceneOf(zurichSite(), {testing::squareArray("array", 60 * c, kSouthFacing30, 8)},
                 {{.name = "window", .position_m = {0, 0, 0}}});
}

HazardOptions daysAround(SunBrightness sun) {
  HazardOptions options;
  options.year = kBrightYear;
  options.step_s = 60;
  options.first_day = kBrightApril20 - 5;
  options.day_count = 11;
  options.threads = 1;
  options.models = {{ModelKind::kEllipse}, {ModelKind::kCircle}, {ModelKind::kCone, 3.0}};
  options.sun = std::move(sun);
  return options;
}

TEST(SunBrightness, ParsesTheOption) {
  EXPECT_EQ(parseSunBrightness({"reference"})->kind, SunKind::kReference);
  EXPECT_EQ(parseSunBrightness({"clear-sky"})->kind, SunKind::kClearSky);
  const Result<SunBrightness> bad = parseSunBrightness({"cloudy"});
  ASSERT_FALSE(bad);
  EXPECT_EQ(bad.error().code, ErrorCode::kBadInput);
  EXPECT_NE(bad.error().message.find("--sun \"cloudy\""), std::string::npos);
  EXPECT_FALSE(parseSunBrightness({"weather"}));
  EXPECT_FALSE(parseSunBrightness({"clear-sky", "x.epw"}));
  const Result<SunBrightness> missing = parseSunBrightness({"weather", "/nonexistent/w.epw"});
  ASSERT_FALSE(missing);
  EXPECT_NE(missing.error().message.find("/nonexistent/w.epw"), std::string::npos);
}

TEST(SunBrightness, TheClearSkyIsTheProfilesOwnModel) {
  const HazardSite site = zurichSite();
  const SunBrightness clear = *parseSunBrightness({"clear-sky"});
  const UtcTime utc{};
  EXPECT_DOUBLE_EQ(sourceIlluminanceLx(clear, utc, 30, 100, site),
                   sun::clearSkyIlluminance(30, 100, site.location.altitude_m)->illuminance_lx);
  EXPECT_EQ(sourceIlluminanceLx(clear, utc, -1, 100, site), 0);
  // The most: the sun at the zenith at perihelion, above any step's.
  EXPECT_GT(maxSourceIlluminanceLx(clear, site), sourceIlluminanceLx(clear, utc, 89, 3, site));
}

TEST(SunBrightness, ADimmerSunNeverAddsGlare) {
  glarecam::testing::TempDir dir;
  const Scene scene = noonScene();
  const ProfileTable profile = ladderProfile(4, 6);
  const std::vector<double> bright(sun::kEpwHoursPerYear, 100'000);
  const std::vector<double> dim(sun::kEpwHoursPerYear, 40'000);
  const Result<HazardResult> full =
      computeHazard(scene, {&profile}, daysAround(weatherOf(bright, dir)));
  ASSERT_TRUE(full) << full.error().message;
  const Result<HazardResult> less =
      computeHazard(scene, {&profile}, daysAround(weatherOf(dim, dir)));
  ASSERT_TRUE(less) << less.error().message;
  const std::vector<std::uint8_t>& a = full->observers[0].steps;
  const std::vector<std::uint8_t>& b = less->observers[0].steps;
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) EXPECT_EQ(b[i] & ~a[i], 0) << "step " << i;
  for (std::size_t m = 0; m < 3; ++m) {
    EXPECT_GT(full->observers[0].models[m].minutes_per_year, 0);
    // The ellipse and circle shrink at 2.5× the level; the constant cone only loses where the
    // level would pass the peak, which a 1e6 cd/m² peak never does at 7.5e4 cd/m².
    if (m < 2) {
      EXPECT_LT(less->observers[0].models[m].minutes_per_year,
                full->observers[0].models[m].minutes_per_year);
    }
  }
  // So dim that even the referred peak stays below the limit: no glare at all.
  const std::vector<double> dusk(sun::kEpwHoursPerYear, 2'000);
  const Result<HazardResult> none =
      computeHazard(scene, {&profile}, daysAround(weatherOf(dusk, dir)));
  ASSERT_TRUE(none) << none.error().message;
  for (const ModelSummary& model : none->observers[0].models) EXPECT_EQ(model.minutes_per_year, 0);
}

TEST(SunBrightness, AtTheReferenceIlluminanceTheLadderGivesTheLimitEllipse) {
  // A constant 100 klx (the profile's E_ref) puts every step's level at the limit, whose contour
  // the ladder holds (between rungs, linear in ln level: within 0.6 % of the exact √ln lobe's
  // axes at 3e4 cd/m²): the minutes match the reference sun's within that, about 1 %.
  glarecam::testing::TempDir dir;
  const Scene scene = noonScene();
  const ProfileTable profile = ladderProfile(4, 6);
  const std::vector<double> reference(sun::kEpwHoursPerYear, 100'000);
  const Result<HazardResult> weather =
      computeHazard(scene, {&profile}, daysAround(weatherOf(reference, dir)));
  const Result<HazardResult> classic = computeHazard(scene, {&profile}, daysAround({}));
  ASSERT_TRUE(weather && classic);
  for (std::size_t m = 0; m < 3; ++m) {
    const double expected = classic->observers[0].models[m].minutes_per_year;
    EXPECT_GT(expected, 100);
    EXPECT_NEAR(weather->observers[0].models[m].minutes_per_year, expected, 0.02 * expected + 2)
        << m;
  }
}

TEST(SunBrightness, AWeatherFileOfTheClearSkyEqualsTheClearSky) {
  // Every hour of the file the clear-sky model at the hour's middle: interpolated to a step, it
  // is the model to well under a percent around noon (the curve is smooth there), so the minutes
  // agree to a step or two per day.
  glarecam::testing::TempDir dir;
  const HazardSite site = zurichSite();
  std::vector<double> hourly;
  const auto january_1 = std::chrono::time_point_cast<microseconds>(
      std::chrono::sys_days{std::chrono::year{kBrightYear} / 1 / 1});
  for (std::size_t h = 0; h < sun::kEpwHoursPerYear; ++h) {
    // Hour h + 1 of local standard time (UTC+1) ends at h + 1 h: its middle is h + 0.5 h local.
    const UtcTime utc = january_1 + std::chrono::minutes(static_cast<int>(h) * 60 + 30 - 60);
    const auto position = sun::solarPosition(utc, site.location);
    const int day = static_cast<int>(h / 24) + 1;
    const auto clear =
        sun::clearSkyIlluminance(position->elevation_deg, day, site.location.altitude_m);
    hourly.push_back(clear ? clear->illuminance_lx : 0);
  }
  const Scene scene = noonScene();
  const ProfileTable profile = ladderProfile(4, 6);
  const Result<HazardResult> weather =
      computeHazard(scene, {&profile}, daysAround(weatherOf(hourly, dir)));
  const Result<HazardResult> clear =
      computeHazard(scene, {&profile}, daysAround(*parseSunBrightness({"clear-sky"})));
  ASSERT_TRUE(weather && clear);
  for (std::size_t m = 0; m < 3; ++m) {
    const ModelSummary& w = weather->observers[0].models[m];
    const ModelSummary& c = clear->observers[0].models[m];
    EXPECT_GT(c.minutes_per_year, 50);
    for (std::size_t d = 0; d < c.minutes_per_day.size(); ++d)
      EXPECT_NEAR(w.minutes_per_day[d], c.minutes_per_day[d], 2) << "model " << m << " day " << d;
  }
}

TEST(SunBrightness, AProfileWithoutALadderIsRefusedNamingIt) {
  const Scene scene = noonScene();
  const ProfileTable profile = testing::constantProfile(4, 6);
  const Result<HazardResult> result =
      computeHazard(scene, {&profile}, daysAround(*parseSunBrightness({"clear-sky"})));
  ASSERT_FALSE(result);
  EXPECT_EQ(result.error().code, ErrorCode::kBadInput);
  EXPECT_NE(result.error().message.find("test module"), std::string::npos)
      << result.error().message;
  EXPECT_NE(result.error().message.find("--sun reference"), std::string::npos);
}

TEST(GlareSighting, TheEventSaysWhereTheGlareIsAndWhatItDoesToTheEye) {
  // The noon glare of the 8 m array 60 m away, seen by the reference sun: at the brightest step
  // the region's centre c falls on the array, so the glare is seen along c, at about 60 m; the
  // 4° × 6° region (0.0057 sr) is smaller than the array (about 0.015 sr), so the spot is the
  // region at its mean luminance, the logarithmic mean of 1e6 and 3e4 cd/m² (hand: 9.7e5 /
  // ln 33.3 = 2.766e5 cd/m²).
  const Scene scene = noonScene();
  const ProfileTable profile = testing::constantProfile(4, 6);
  HazardOptions options = daysAround({});
  options.first_day = kBrightApril20;
  options.day_count = 1;
  options.models = {{ModelKind::kEllipse}};
  const Result<HazardResult> result = computeHazard(scene, {&profile}, options);
  ASSERT_TRUE(result) << result.error().message;
  ASSERT_EQ(result->events.size(), 1u);
  const GlareEvent& event = result->events[0];
  const GlareSighting& peak = event.peak;
  const Vec3 towards = normalised(scene.arrays[0].centroid_m);
  EXPECT_NEAR(peak.glare_elevation_deg, degrees(std::asin(towards.z)), 0.5);
  EXPECT_NEAR(peak.distance_m, 60, 4);  // the point seen lies within the array's 4 m half-side
  EXPECT_NEAR(peak.sun_elevation_deg, degrees(std::asin(noonSun().z)), 0.5);
  ASSERT_TRUE(peak.ocular);
  const double spot_cd_m2 = (1e6 - 3e4) / std::log(1e6 / 3e4);
  const double spot_sr = pipeline::circularBeamSpread(4, 6).solid_angle_sr;
  const OcularExposure expected = *ocularExposure(spot_cd_m2, spot_sr);
  EXPECT_NEAR(peak.ocular->retinal_irradiance_w_cm2, expected.retinal_irradiance_w_cm2,
              1e-9 * expected.retinal_irradiance_w_cm2);
  // The calculation takes the region's solid angle from its series (within 5e-6 of the integral
  // for half-axes under 11.5°): ω, from √Ω, within 3e-6 of the integral's.
  EXPECT_NEAR(peak.ocular->subtended_angle_mrad, expected.subtended_angle_mrad,
              3e-6 * expected.subtended_angle_mrad);
  ASSERT_TRUE(event.worst_class);
  EXPECT_EQ(*event.worst_class, expected.ocular_class);
  const ModelSummary& summary = result->observers[0].models[0];
  EXPECT_DOUBLE_EQ(summary.ocular_minutes[0] + summary.ocular_minutes[1] +
                       summary.ocular_minutes[2] + summary.unclassified_minutes,
                   summary.minutes_per_year);
}

}  // namespace
}  // namespace glarecam::hazard
