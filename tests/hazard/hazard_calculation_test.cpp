#include "hazard/hazard_calculation.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <numbers>

#include "hazard/glare_region.h"
#include "sun/solar_position.h"
#include "tests/hazard/hazard_fixtures.h"

namespace glarecam::hazard {
namespace {

using std::chrono::microseconds;
using testing::constantProfile;
using testing::sceneOf;
using testing::squareArray;
using testing::zurichSite;

constexpr double kRadPerDeg = std::numbers::pi / 180;
constexpr int kYear = 2027;
constexpr int kMarch21 = 79;  // day of the year, from 0 = 1 January
constexpr int kApril20 = 109;

Vec3 sunVector(const sun::SolarPosition& position) {
  const double e = position.elevation_deg * kRadPerDeg, a = position.azimuth_deg * kRadPerDeg;
  return {std::cos(e) * std::sin(a), std::cos(e) * std::cos(a), std::sin(e)};
}

UtcTime localMidnightUtc(const HazardSite& site, int day) {
  const auto midnight =
      std::chrono::sys_days{std::chrono::year{kYear} / 1 / 1} + std::chrono::days(day);
  return std::chrono::time_point_cast<microseconds>(midnight) -
         microseconds(std::llround(site.utc_offset_h * 3600e6));
}

struct SolarNoon {
  double seconds_of_day = 0;  // local standard time
  sun::SolarPosition position;
};

// The sun's highest point of a local day at the Zürich site, to 10 s, by full SPA.
SolarNoon solarNoon(const HazardSite& site, int day) {
  SolarNoon noon;
  noon.position.elevation_deg = -90;
  const UtcTime midnight = localMidnightUtc(site, day);
  for (int s = 10 * 3600; s < 15 * 3600; s += 10) {  // solar noon is near 12:25 here
    const auto position =
        sun::solarPosition(midnight + microseconds(std::int64_t{s} * 1'000'000), site.location);
    if (position->elevation_deg > noon.position.elevation_deg) {
      noon.position = *position;
      noon.seconds_of_day = s;
    }
  }
  return noon;
}

// An array whose glare reaches an observer at the origin exactly when the sun stands at `sun`:
// the array (a square of `side_m` facing `normal`) lies at `distance_m` along the sun's mirror
// image c.
ArrayPolygon arrayReflecting(Vec3 sun, Vec3 normal, double distance_m, double side_m) {
  const Vec3 c = sun - 2 * dot(normal, sun) * normal;
  return squareArray("array", distance_m * c, normal, side_m);
}

HazardOptions oneDay(int day, int step_s, std::vector<GlareModel> models) {
  HazardOptions options;
  options.year = kYear;
  options.step_s = step_s;
  options.models = std::move(models);
  options.first_day = day;
  options.day_count = 1;
  options.threads = 1;
  return options;
}

const Vec3 kSouthTilted30 = normalised({0, -0.5, std::sqrt(3.0) / 2});

TEST(HazardCalculation, PassDurationIsTheChordOverTheSunsAngularSpeed) {
  // hazard.md's check: a point-like array far away, the mirror image's track through the centre
  // of a constant region: duration = chord / (0.25°/min · cos δ). At solar noon the sun moves
  // across the plane of incidence, so the track crosses the H axis.
  const HazardSite site = zurichSite();
  const SolarNoon noon = solarNoon(site, kMarch21);
  const double cos_delta = std::cos(noon.position.declination_deg * kRadPerDeg);
  // 0.2 m at 1 km: 0.011°, point-like against a 4° region (adds at most 0.05 min).
  const Scene scene =
      sceneOf(site, {arrayReflecting(sunVector(noon.position), kSouthTilted30, 1000, 0.2)},
              {{.name = "window", .position_m = {0, 0, 0}}});
  const ProfileTable h_is_4 = constantProfile(8, 4);  // V 8°, H 4°
  const ProfileTable h_is_8 = constantProfile(4, 8);
  const std::vector<GlareModel> models{{ModelKind::kEllipse}, {ModelKind::kCone, 4.0}};
  // 10-s steps: each end of the window is found to one step, 1/6 min, so ±0.25 min in all with
  // the array's own size.
  constexpr double kToleranceMin = 0.25;
  const double expected_4 = 4.0 / (0.25 * cos_delta);  // 16 min at the equinox
  {
    const Result<HazardResult> result =
        computeHazard(scene, {&h_is_4}, oneDay(kMarch21, 10, models));
    ASSERT_TRUE(result) << result.error().message;
    EXPECT_NEAR(result->observers[0].models[0].minutes_per_day[0], expected_4, kToleranceMin);
    EXPECT_NEAR(result->observers[0].models[1].minutes_per_day[0], expected_4, kToleranceMin);
    // The window is centred on solar noon (within a step).
    const auto [first, last] = *result->observers[0].models[0].first_last_step[0];
    EXPECT_NEAR((first + last + 1) * 10 / 2.0, noon.seconds_of_day, 15);
  }
  {
    // Across the 8° H axis: twice as long. Not exactly twice: over the 32 minutes the plane of
    // incidence turns with the sun by a few degrees, and the long, narrow ellipse (V 4°) turns
    // with it, which shortens a chord along it (by ~6 % here; the 16-min pass across the short
    // axis of the wide ellipse barely changes). The constant 8° circle has no frame to turn.
    const std::vector<GlareModel> wide{{ModelKind::kEllipse}, {ModelKind::kCone, 8.0}};
    const Result<HazardResult> result = computeHazard(scene, {&h_is_8}, oneDay(kMarch21, 10, wide));
    ASSERT_TRUE(result) << result.error().message;
    const double ellipse = result->observers[0].models[0].minutes_per_day[0];
    EXPECT_GT(ellipse, 0.9 * 2 * expected_4);  // crossed H, not the 4° V (16 min)
    EXPECT_LT(ellipse, 2 * expected_4 + kToleranceMin);
    EXPECT_NEAR(result->observers[0].models[1].minutes_per_day[0], 2 * expected_4, kToleranceMin);
  }
}

TEST(HazardCalculation, ConeOfDegreesEqualsAnEllipseWithBothAxesThoseDegrees) {
  const HazardSite site = zurichSite();
  const SolarNoon noon = solarNoon(site, kApril20);
  const Scene scene =
      sceneOf(site, {arrayReflecting(sunVector(noon.position), kSouthTilted30, 60, 8)},
              {{.name = "window", .position_m = {0, 0, 0}}});
  const ProfileTable round = constantProfile(3, 3);
  HazardOptions options = oneDay(
      kApril20 - 10, 60, {{ModelKind::kEllipse}, {ModelKind::kCone, 3.0}, {ModelKind::kCircle}});
  options.day_count = 20;
  const Result<HazardResult> result = computeHazard(scene, {&round}, options);
  ASSERT_TRUE(result) << result.error().message;
  const ObserverHazard& observer = result->observers[0];
  EXPECT_GT(observer.models[0].minutes_per_year, 60);  // it glares
  for (const std::uint8_t mask : observer.steps) {
    const bool ellipse = mask & 1, cone = mask & 2, circle = mask & 4;
    EXPECT_EQ(ellipse, cone);
    EXPECT_EQ(ellipse, circle);  // a 3° circle's equal-solid-angle cone is itself
  }
}

TEST(HazardCalculation, ATinyRegionIsThePointMirror) {
  // With a region of 0.001° the observer sees glare exactly when the ray along c meets the array:
  // the point-mirror model. Checked against that ray cast, step by step, with full SPA.
  const HazardSite site = zurichSite();
  const SolarNoon noon = solarNoon(site, kApril20);
  const ArrayPolygon array = arrayReflecting(sunVector(noon.position), kSouthTilted30, 100, 10);
  const Scene scene = sceneOf(site, {array}, {{.name = "window", .position_m = {0, 0, 0}}});
  const ProfileTable tiny = constantProfile(6, 6);
  const Result<HazardResult> result =
      computeHazard(scene, {&tiny}, oneDay(kApril20, 30, {{ModelKind::kCone, 0.001}}));
  ASSERT_TRUE(result) << result.error().message;
  int expected = 0, mismatched = 0;
  const UtcTime midnight = localMidnightUtc(site, kApril20);
  for (int k = 0; k < result->steps_per_day; ++k) {
    const auto position = sun::solarPosition(
        midnight + microseconds(std::int64_t{k} * 30'000'000 + 15'000'000), site.location);
    const Vec3 s = sunVector(*position);
    bool hits = false;
    if (position->elevation_deg > 0 && dot(s, array.normal) > 0) {
      const Vec3 c = s - 2 * dot(array.normal, s) * array.normal;
      const double t = dot(array.centroid_m, array.normal) / dot(c, array.normal);
      hits = t > 0 && containsPlanePoint(array, t * c);
    }
    expected += hits ? 1 : 0;
    mismatched += hits != ((result->observers[0].steps[static_cast<std::size_t>(k)] & 1) != 0);
  }
  EXPECT_GT(expected, 20);  // 10 m at 100 m: ~5.7°, some 20 min
  // The fast sun track agrees with SPA to 0.0005°: a step can differ only at the array's edge.
  EXPECT_LE(mismatched, 2);
}

// A south-facing array whose glare reaches an observer on its north–south axis around solar
// noon in mid-April and again in late August.
Scene symmetricScene(const HazardSite& site) {
  // The noon sun of 20 April, due south (azimuth exactly 180°): the array's centre lies on the
  // observer's north–south axis.
  const double elevation = solarNoon(site, kApril20).position.elevation_deg * kRadPerDeg;
  const Vec3 noon_sun{0, -std::cos(elevation), std::sin(elevation)};
  return sceneOf(site, {arrayReflecting(noon_sun, kSouthTilted30, 50, 10)},
                 {{.name = "window", .position_m = {0, 0, 0}}});
}

TEST(HazardCalculation, GlareIsSymmetricAboutSolarNoonAndTheSolstice) {
  const HazardSite site = zurichSite();
  const Scene scene = symmetricScene(site);
  EXPECT_NEAR(scene.arrays[0].centroid_m.x, 0, 1e-9);  // on the observer's north–south axis
  const ProfileTable profile = constantProfile(6, 3);
  HazardOptions options;
  options.year = kYear;
  options.models = {{ModelKind::kEllipse}};
  const Result<HazardResult> result = computeHazard(scene, {&profile}, options);
  ASSERT_TRUE(result) << result.error().message;
  const ModelSummary& summary = result->observers[0].models[0];
  ASSERT_GT(summary.days_with_glare, 10);
  // Each glaring day's window is centred on that day's solar noon, within a 60-s step (each end
  // is found to one step) and the sun's drift in declination over the window.
  int checked = 0;
  for (int day = 0; day < result->days; day += 3) {
    const auto& window = summary.first_last_step[static_cast<std::size_t>(day)];
    if (!window) continue;
    const double middle_s = (window->first + window->second + 1) * 60 / 2.0;
    EXPECT_NEAR(middle_s, solarNoon(site, day).seconds_of_day, 75) << "day " << day;
    ++checked;
  }
  EXPECT_GT(checked, 5);
  // The year mirrors about the June solstice (21 June 2027, 14:11 UTC: day 171.6): the glare
  // days before it and after it carry the same minutes within 3 % (the sun's declination is not
  // exactly symmetric: the Earth's orbit is an ellipse).
  const double solstice = 171.6;
  double before = 0, after = 0, first_before = 400, last_after = -1;
  for (int day = 0; day < result->days; ++day) {
    const double minutes = summary.minutes_per_day[static_cast<std::size_t>(day)];
    if (minutes == 0) continue;
    if (day + 0.5 < solstice) {
      before += minutes;
      first_before = std::min(first_before, day + 0.5);
    } else {
      after += minutes;
      last_after = std::max(last_after, day + 0.5);
    }
  }
  EXPECT_NEAR(after / before, 1, 0.03);
  EXPECT_NEAR(solstice - first_before, last_after - solstice, 2.0);
}

TEST(HazardCalculation, TenSecondStepsAgreeWithSixtyWithinOnePercent) {
  const HazardSite site = zurichSite();
  const Scene scene = symmetricScene(site);
  const ProfileTable profile = constantProfile(6, 3);
  HazardOptions options = oneDay(kApril20 - 20, 60, {{ModelKind::kEllipse}, {ModelKind::kCircle}});
  options.day_count = 40;
  const Result<HazardResult> coarse = computeHazard(scene, {&profile}, options);
  options.step_s = 10;
  const Result<HazardResult> fine = computeHazard(scene, {&profile}, options);
  ASSERT_TRUE(coarse && fine);
  for (std::size_t m = 0; m < 2; ++m) {
    const double a = coarse->observers[0].models[m].minutes_per_year;
    const double b = fine->observers[0].models[m].minutes_per_year;
    ASSERT_GT(b, 100);
    EXPECT_NEAR(a / b, 1, 0.01) << "model " << m;
  }
}

TEST(HazardCalculation, NothingBehindTheArrayOrWhereNoReflectionCanReach) {
  const HazardSite site = zurichSite();
  const ArrayPolygon array = squareArray("roof", {0, 0, 0}, kSouthTilted30, 10);
  // Behind: south of and below the array's plane. Unreachable: due north at the array's height,
  // where the reflection would need a sun below the horizon.
  const Scene scene = sceneOf(site, {array},
                              {{.name = "behind", .position_m = {0, -20, -20}},
                               {.name = "level-north", .position_m = {0, 50, 0}}});
  const ProfileTable profile = constantProfile(20, 20);
  HazardOptions options;
  options.year = kYear;
  options.step_s = 300;
  const Result<HazardResult> result = computeHazard(scene, {&profile}, options);
  ASSERT_TRUE(result) << result.error().message;
  for (const ObserverHazard& observer : result->observers) {
    for (const ModelSummary& summary : observer.models) {
      EXPECT_EQ(summary.minutes_per_year, 0);
      EXPECT_EQ(summary.steps_beyond_method, 0);
    }
  }
  EXPECT_TRUE(result->events.empty());
}

TEST(HazardCalculation, GrazingReflectionsAreBeyondTheMethodNotGlare) {
  // A level array and an observer barely above its plane far away: only a sun near the horizon
  // (α near 90°) reflects there.
  const HazardSite site = zurichSite();
  const ArrayPolygon array = squareArray("flat", {0, 0, 0}, {0, 0, 1}, 20);
  const Scene scene = sceneOf(site, {array}, {{.name = "far", .position_m = {-300, 0, 5}}});
  const ProfileTable profile = constantProfile(10, 10);
  HazardOptions options;
  options.year = kYear;
  options.step_s = 120;
  const Result<HazardResult> result = computeHazard(scene, {&profile}, options);
  ASSERT_TRUE(result) << result.error().message;
  const ModelSummary& summary = result->observers[0].models[0];
  EXPECT_EQ(summary.minutes_per_year, 0);
  EXPECT_GT(summary.steps_beyond_method, 0);
}

TEST(HazardCalculation, AnUnknownSpreadIsCountedNeverNoGlare) {
  const HazardSite site = zurichSite();
  const Scene scene = symmetricScene(site);
  nlohmann::json document = testing::constantProfileJson(6, 3);
  for (nlohmann::json& row : document["profile"]) {
    row["vertical_deg"] = nullptr;
    row["horizontal_deg"] = nullptr;
    row["circular_beam"] = nullptr;
  }
  const ProfileTable profile = *ProfileTable::fromJson(document, "p.json");
  const Result<HazardResult> result = computeHazard(
      scene, {&profile}, oneDay(kApril20, 60, {{ModelKind::kEllipse}, {ModelKind::kCone, 3.0}}));
  ASSERT_TRUE(result) << result.error().message;
  EXPECT_EQ(result->observers[0].models[0].minutes_per_year, 0);
  EXPECT_GT(result->observers[0].models[0].steps_unknown_spread, 0);
  EXPECT_GT(result->observers[0].models[1].minutes_per_year, 0);  // a cone needs no spread
  EXPECT_EQ(result->observers[0].models[1].steps_unknown_spread, 0);
}

TEST(HazardCalculation, OnlyTheObserversHoursCount) {
  const HazardSite site = zurichSite();
  Scene scene = symmetricScene(site);
  const SolarNoon noon = solarNoon(site, kApril20);
  const double noon_h = noon.seconds_of_day / 3600.0;
  scene.observers.push_back(
      {.name = "mornings", .position_m = {0, 0, 0}, .from_h = 0, .to_h = noon_h});
  const ProfileTable profile = constantProfile(6, 3);
  const Result<HazardResult> result =
      computeHazard(scene, {&profile}, oneDay(kApril20, 60, {{ModelKind::kEllipse}}));
  ASSERT_TRUE(result) << result.error().message;
  const double all_day = result->observers[0].models[0].minutes_per_day[0];
  const double mornings = result->observers[1].models[0].minutes_per_day[0];
  ASSERT_GT(all_day, 10);
  // The window is centred on noon: the morning half, within a step.
  EXPECT_NEAR(mornings, all_day / 2, 1.0);
  EXPECT_LE((*result->observers[1].models[0].first_last_step[0]).second * 60, noon_h * 3600);
}

TEST(HazardCalculation, EventsFollowTheStepsAndPeakAtLmax) {
  const HazardSite site = zurichSite();
  Scene scene = symmetricScene(site);
  // A second array beside the first: the observer's minutes are the union, events per array.
  ArrayPolygon second = scene.arrays[0];
  second.name = "second";
  for (Vec3& v : second.vertices_m) v = v + Vec3{0.5, 0, 0};
  second = *makeArrayPolygon("second", second.vertices_m, "scene.json", "arrays[1]");
  scene.arrays.push_back(second);
  const ProfileTable profile = constantProfile(6, 3);
  const Result<HazardResult> result =
      computeHazard(scene, {&profile, &profile}, oneDay(kApril20, 60, {{ModelKind::kEllipse}}));
  ASSERT_TRUE(result) << result.error().message;
  ASSERT_EQ(result->events.size(), 2u);  // one per array
  const ModelSummary& summary = result->observers[0].models[0];
  const auto [first, last] = *summary.first_last_step[0];
  std::int64_t union_first = 1 << 30, union_end = 0;
  for (const GlareEvent& event : result->events) {
    union_first = std::min(union_first, event.first_step);
    union_end = std::max(union_end, event.end_step);
    EXPECT_LE(event.alpha_min_deg, event.alpha_max_deg);
    // The track passes close to the region's centre (q ≈ 0): L ≈ Lmax = 10⁶ cd/m².
    ASSERT_TRUE(event.peak_luminance_cd_m2);
    EXPECT_NEAR(*event.peak_luminance_cd_m2 / 1e6, 1, 0.05);
  }
  const std::int64_t day_start = std::int64_t{kApril20} * result->steps_per_day;
  EXPECT_EQ(union_first, day_start + first);
  EXPECT_EQ(union_end, day_start + last + 1);
  EXPECT_EQ(summary.minutes_per_day[0], static_cast<double>(last - first + 1));
}

TEST(HazardCalculation, ThreadsGiveIdenticalResults) {
  const HazardSite site = zurichSite();
  const Scene scene = symmetricScene(site);
  const ProfileTable profile = constantProfile(6, 3);
  HazardOptions options = oneDay(kApril20 - 5, 120, {{ModelKind::kEllipse}, {ModelKind::kCircle}});
  options.day_count = 10;
  const Result<HazardResult> one = computeHazard(scene, {&profile}, options);
  options.threads = 3;
  const Result<HazardResult> three = computeHazard(scene, {&profile}, options);
  ASSERT_TRUE(one && three);
  EXPECT_EQ(one->observers[0].steps, three->observers[0].steps);
  EXPECT_EQ(one->events.size(), three->events.size());
}

TEST(HazardCalculation, RefusesBadOptions) {
  const Scene scene = symmetricScene(zurichSite());
  const ProfileTable profile = constantProfile(6, 3);
  HazardOptions options;
  options.year = 7000;
  EXPECT_NE(computeHazard(scene, {&profile}, options).error().message.find("--year 7000"),
            std::string::npos);
  options.year = kYear;
  options.step_s = 7;  // does not divide a day
  EXPECT_NE(computeHazard(scene, {&profile}, options).error().message.find("--step-s 7"),
            std::string::npos);
  options.step_s = 60;
  EXPECT_EQ(computeHazard(scene, {}, options).error().code, ErrorCode::kBadInput);
  options.models.clear();
  EXPECT_EQ(computeHazard(scene, {&profile}, options).error().code, ErrorCode::kBadInput);
}

TEST(HazardCalculation, DaysOfTheYear) {
  EXPECT_EQ(daysInYear(2027), 365);
  EXPECT_EQ(daysInYear(2028), 366);
  EXPECT_EQ(daysInYear(2100), 365);
  EXPECT_EQ(daysInYear(2000), 366);
}

}  // namespace
}  // namespace glarecam::hazard
