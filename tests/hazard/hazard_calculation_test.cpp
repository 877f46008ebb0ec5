#include "hazard/hazard_calculation.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <limits>

#include "core/angles.h"
#include "hazard/glare_region.h"
#include "hazard/obstruction.h"
#include "sun/solar_position.h"
#include "tests/hazard/hazard_fixtures.h"

namespace glarecam::hazard {
namespace {

using std::chrono::microseconds;
using testing::constantProfile;
using testing::sceneOf;
using testing::squareArray;
using testing::zurichSite;

constexpr int kYear = 2027;
constexpr int kMarch21 = 79;  // day of the year, from 0 = 1 January
constexpr int kApril20 = 109;

Vec3 sunVector(const sun::SolarPosition& position) {
  return testing::unitToward(position.elevation_deg, position.azimuth_deg);
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

// Days [first_day, first_day + day_count) of kYear on one thread.
HazardOptions someDays(int first_day, int day_count, int step_s, std::vector<GlareModel> models) {
  HazardOptions options;
  options.year = kYear;
  options.step_s = step_s;
  options.models = std::move(models);
  options.first_day = first_day;
  options.day_count = day_count;
  options.threads = 1;
  return options;
}

HazardOptions oneDay(int day, int step_s, std::vector<GlareModel> models) {
  return someDays(day, 1, step_s, std::move(models));
}

const Vec3 kSouthTilted30 = normalised({0, -0.5, std::sqrt(3.0) / 2});

TEST(HazardCalculation, PassDurationIsTheChordOverTheSunsAngularSpeed) {
  // hazard.md's check: a point-like array far away, the mirror image's track through the centre
  // of a constant region: duration = chord / (0.25°/min · cos δ). At solar noon the sun moves
  // across the plane of incidence, so the track crosses the H axis.
  const HazardSite site = zurichSite();
  const SolarNoon noon = solarNoon(site, kMarch21);
  const double cos_delta = std::cos(radians(noon.position.declination_deg));
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
  // H a part in 10⁹ wider than V: the ellipse takes the sampled branch-and-bound path, the cone
  // the analytic circle.
  const ProfileTable round = constantProfile(3, 3 * (1 + 1e-9));
  const HazardOptions options =
      someDays(kApril20 - 10, 20, 60,
               {{ModelKind::kEllipse}, {ModelKind::kCone, 3.0}, {ModelKind::kCircle}});
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
  const double elevation = radians(solarNoon(site, kApril20).position.elevation_deg);
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
  HazardOptions options;
  options.year = kYear;
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
  // Behind: north of and below the array's plane. Unreachable: in front, due south at the
  // array's height, looking north at it: the reflection would need the sun 60° high in the
  // north, which it never is at 47° N.
  const Scene scene = sceneOf(site, {array},
                              {{.name = "behind", .position_m = {0, 20, -20}},
                               {.name = "level-south", .position_m = {0, -50, 0}}});
  ASSERT_FALSE(viewFrom(array, scene.observers[0].position_m).in_front);
  ASSERT_TRUE(viewFrom(array, scene.observers[1].position_m).in_front);
  const ProfileTable profile = constantProfile(6, 6);
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
  HazardOptions options =
      someDays(kApril20 - 5, 10, 120, {{ModelKind::kEllipse}, {ModelKind::kCircle}});
  const Result<HazardResult> one = computeHazard(scene, {&profile}, options);
  options.threads = 3;
  const Result<HazardResult> three = computeHazard(scene, {&profile}, options);
  ASSERT_TRUE(one && three);
  EXPECT_EQ(one->observers[0].steps, three->observers[0].steps);
  for (std::size_t m = 0; m < 2; ++m) {
    EXPECT_EQ(one->observers[0].models[m].minutes_per_day,
              three->observers[0].models[m].minutes_per_day);
    EXPECT_EQ(one->observers[0].models[m].first_last_step,
              three->observers[0].models[m].first_last_step);
  }
  ASSERT_EQ(one->events.size(), three->events.size());
  for (std::size_t i = 0; i < one->events.size(); ++i) {
    EXPECT_EQ(one->events[i].first_step, three->events[i].first_step);
    EXPECT_EQ(one->events[i].end_step, three->events[i].end_step);
    EXPECT_EQ(one->events[i].peak_luminance_cd_m2, three->events[i].peak_luminance_cd_m2);
  }
}

TEST(HazardCalculation, TheUtcOffsetShiftsLocalTimeOnly) {
  // The same glare seen on clocks one hour ahead and 3½ hours behind: the same minutes, the
  // window moved by exactly the offsets' difference in steps.
  HazardSite site = zurichSite();
  const Scene base = symmetricScene(site);
  const ProfileTable profile = constantProfile(6, 3);
  const HazardOptions options = oneDay(kApril20, 60, {{ModelKind::kEllipse}});
  const Result<HazardResult> plus_one = computeHazard(base, {&profile}, options);
  Scene shifted = base;
  shifted.site.utc_offset_h = -3.5;
  const Result<HazardResult> minus_three_half = computeHazard(shifted, {&profile}, options);
  ASSERT_TRUE(plus_one && minus_three_half);
  const auto a = *plus_one->observers[0].models[0].first_last_step[0];
  const auto b = *minus_three_half->observers[0].models[0].first_last_step[0];
  EXPECT_EQ(a.first - b.first, 270);  // 4.5 h of 60-s steps
  EXPECT_EQ(a.second - b.second, 270);
  EXPECT_EQ(plus_one->observers[0].models[0].minutes_per_day[0],
            minus_three_half->observers[0].models[0].minutes_per_day[0]);
}

TEST(HazardCalculation, AnEventAcrossMidnightIsOneEvent) {
  // The midnight sun at 70° N (UTC+0 at the Greenwich meridian): a north-facing array reflects
  // it to an observer around local midnight of the June solstice, across the day boundary.
  HazardSite site;
  site.location.latitude_deg = 70;
  site.location.longitude_deg = 0;
  site.location.pressure_hpa = 1013.25;
  site.utc_offset_h = 0;
  const auto midnight = std::chrono::time_point_cast<microseconds>(
      std::chrono::sys_days{std::chrono::year{kYear} / 6 / 22});
  const auto sun = sun::solarPosition(midnight, site.location);
  ASSERT_GT(sun->elevation_deg, 1);
  const Vec3 north_facing = normalised({0, 0.5, std::sqrt(3.0) / 2});
  const Scene scene = sceneOf(site, {arrayReflecting(sunVector(*sun), north_facing, 50, 5)},
                              {{.name = "window", .position_m = {0, 0, 0}}});
  const ProfileTable profile = constantProfile(8, 8);
  const Result<HazardResult> result =
      computeHazard(scene, {&profile}, someDays(171, 2, 60, {{ModelKind::kEllipse}}));
  ASSERT_TRUE(result) << result.error().message;
  // Midnights at both ends of the two days glare too; the one between them is one event.
  const std::int64_t boundary = std::int64_t{172} * result->steps_per_day;
  int spanning = 0;
  for (const GlareEvent& event : result->events) {
    spanning += event.first_step < boundary && event.end_step > boundary;
    EXPECT_NE(event.end_step, boundary) << "split at midnight";
    EXPECT_NE(event.first_step, boundary) << "split at midnight";
  }
  EXPECT_EQ(spanning, 1);
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
  options.threads = 4294967295u;  // would overflow the days handed to each thread
  EXPECT_NE(computeHazard(scene, {&profile}, options).error().message.find("--threads"),
            std::string::npos);
  options.threads = 1;
  EXPECT_EQ(computeHazard(scene, {}, options).error().code, ErrorCode::kBadInput);
  options.models.clear();
  EXPECT_EQ(computeHazard(scene, {&profile}, options).error().code, ErrorCode::kBadInput);
}

TEST(HazardOptions, AYearFarFromNowIsComputedButWarnedAbout) {
  HazardOptions options;
  for (int year : {kLikelyFirstYear, 2027, kLikelyLastYear}) {
    options.year = year;
    EXPECT_FALSE(options.yearWarning()) << year;
  }
  options.year = 27;  // a two-digit year
  ASSERT_TRUE(options.validate());
  EXPECT_EQ(options.yearWarning(),
            "--year 27 is outside 1950\u20132200 (did you mean 2027?); computed for the year 27 "
            "as given");
  options.year = 1800;  // a historical year: no guess
  ASSERT_TRUE(options.validate());
  EXPECT_EQ(options.yearWarning(),
            "--year 1800 is outside 1950\u20132200; computed for the year 1800 as given");
  options.year = 2201;
  EXPECT_TRUE(options.yearWarning());
}

}  // namespace
}  // namespace glarecam::hazard

namespace glarecam::hazard {
namespace {

// Compass azimuth of a direction's horizontal part.
double azimuthOf(Vec3 d) { return std::fmod(degrees(std::atan2(d.x, d.y)) + 360, 360); }

// A square screen of `side_m` at `distance_m` along `direction` from `from_m`, facing it; with
// `half`, only the part on one side of the vertical line through its centre.
Obstruction screenAcross(Vec3 from_m, Vec3 direction, double distance_m, double side_m,
                         bool half = false) {
  const Vec3 h = normalised(cross(direction, {0, 0, 1}));
  const Vec3 up = cross(h, direction);
  const Vec3 centre = from_m + distance_m * direction;
  const double left = half ? 0 : -side_m / 2, right = side_m / 2;
  return *makePlanarObstruction(
      "screen",
      {centre + left * h - side_m / 2 * up, centre + right * h - side_m / 2 * up,
       centre + right * h + side_m / 2 * up, centre + left * h + side_m / 2 * up},
      "scene.json", "obstructions[0]");
}

TEST(HazardReceptors, AFieldOfViewExcludesGlareFromBehind) {
  // A driver at the origin sees the array's noon glare in direction c. Travelling toward it
  // (50° each side) the glare counts; travelling away it never does; both ways, it does as if
  // there were no field of view. A window facing it (90°) sees it too.
  const HazardSite site = zurichSite();
  const SolarNoon noon = solarNoon(site, kApril20);
  const Vec3 sun = sunVector(noon.position);
  const Vec3 c = normalised(sun - 2 * dot(kSouthTilted30, sun) * kSouthTilted30);
  const double toward_deg = azimuthOf(c), away_deg = std::fmod(toward_deg + 180, 360);
  const Scene scene = sceneOf(site, {arrayReflecting(sun, kSouthTilted30, 60, 8)},
                              {{.name = "free", .position_m = {0, 0, 0}},
                               {.name = "toward",
                                .position_m = {0, 0, 0},
                                .view_azimuths_deg = {toward_deg},
                                .field_of_view_deg = 50},
                               {.name = "away",
                                .position_m = {0, 0, 0},
                                .view_azimuths_deg = {away_deg},
                                .field_of_view_deg = 50},
                               {.name = "both",
                                .position_m = {0, 0, 0},
                                .view_azimuths_deg = {toward_deg, away_deg},
                                .field_of_view_deg = 50},
                               {.name = "window",
                                .position_m = {0, 0, 0},
                                .view_azimuths_deg = {toward_deg},
                                .field_of_view_deg = 90}});
  const ProfileTable profile = constantProfile(4, 6);
  const Result<HazardResult> result =
      computeHazard(scene, {&profile}, oneDay(kApril20, 60, {{ModelKind::kEllipse}}));
  ASSERT_TRUE(result) << result.error().message;
  const double free = result->observers[0].models[0].minutes_per_day[0];
  EXPECT_GT(free, 10);
  EXPECT_EQ(result->observers[1].models[0].minutes_per_day[0], free);
  EXPECT_EQ(result->observers[2].models[0].minutes_per_day[0], 0);
  EXPECT_EQ(result->observers[3].models[0].minutes_per_day[0], free);
  EXPECT_EQ(result->observers[4].models[0].minutes_per_day[0], free);
}

TEST(HazardObstructions, AScreenThatCoversTheArrayRemovesAllGlare) {
  const HazardSite site = zurichSite();
  const SolarNoon noon = solarNoon(site, kApril20);
  const Vec3 sun = sunVector(noon.position);
  const ArrayPolygon array = arrayReflecting(sun, kSouthTilted30, 60, 8);
  const Vec3 c = normalised(array.centroid_m);
  const ProfileTable profile = constantProfile(4, 6);
  const HazardOptions options = oneDay(kApril20, 60, {{ModelKind::kEllipse}, {ModelKind::kCircle}});
  Scene scene = sceneOf(site, {array}, {{.name = "window", .position_m = {0, 0, 0}}});
  const Result<HazardResult> open = computeHazard(scene, {&profile}, options);
  ASSERT_TRUE(open) << open.error().message;
  ASSERT_GT(open->observers[0].models[0].minutes_per_day[0], 10);
  // Between the observer and the array: hides it (a 20 m screen at 30 m covers 37°, the array
  // 8 m at 60 m only 7.6°).
  scene.obstructions = {screenAcross({0, 0, 0}, c, 30, 20)};
  Result<HazardResult> hidden = computeHazard(scene, {&profile}, options);
  ASSERT_TRUE(hidden) << hidden.error().message;
  for (const ModelSummary& model : hidden->observers[0].models)
    EXPECT_EQ(model.minutes_per_year, 0);
  // Between the sun and the array: shades it (30 m across, 10 m toward the noon sun, so the
  // shadow covers the array for an hour around noon, longer than the glare lasts).
  scene.obstructions = {screenAcross(array.centroid_m, sun, 10, 30)};
  hidden = computeHazard(scene, {&profile}, options);
  ASSERT_TRUE(hidden) << hidden.error().message;
  for (const ModelSummary& model : hidden->observers[0].models)
    EXPECT_EQ(model.minutes_per_year, 0);
  // Behind the observer, or behind the array: nothing changes.
  scene.obstructions = {screenAcross({0, 0, 0}, -1 * c, 5, 20),
                        screenAcross(array.centroid_m, c, 5, 20)};
  const Result<HazardResult> behind = computeHazard(scene, {&profile}, options);
  ASSERT_TRUE(behind) << behind.error().message;
  EXPECT_EQ(behind->observers[0].steps, open->observers[0].steps);
}

TEST(HazardObstructions, HalfCoveredHalvesAFarObserversGlare) {
  // A 40 m array 1 km away (2.3°) and a tiny 0.05° region: the glare lasts while the mirror
  // image crosses the array, which at noon it does horizontally. A screen halfway hiding the
  // half of it on one side of the vertical through its centre halves that crossing: the pass
  // takes (2.3° + 0.05°)/(0.25°/min) against (1.15° + 0.05°)/(0.25°/min), a ratio of 0.51; the
  // 60-s steps give each duration to ±1 min, so 0.51 ± 0.15.
  const HazardSite site = zurichSite();
  const SolarNoon noon = solarNoon(site, kApril20);
  const Vec3 sun = sunVector(noon.position);
  const ArrayPolygon array = arrayReflecting(sun, kSouthTilted30, 1000, 40);
  const Vec3 c = normalised(array.centroid_m);
  const ProfileTable profile = constantProfile(0.05, 0.05);
  const HazardOptions options = oneDay(kApril20, 60, {{ModelKind::kEllipse}});
  Scene scene = sceneOf(site, {array}, {{.name = "window", .position_m = {0, 0, 0}}});
  const Result<HazardResult> open = computeHazard(scene, {&profile}, options);
  ASSERT_TRUE(open) << open.error().message;
  scene.obstructions = {screenAcross({0, 0, 0}, c, 500, 60, /*half=*/true)};
  const Result<HazardResult> half = computeHazard(scene, {&profile}, options);
  ASSERT_TRUE(half) << half.error().message;
  const double full_min = open->observers[0].models[0].minutes_per_day[0];
  const double half_min = half->observers[0].models[0].minutes_per_day[0];
  EXPECT_NEAR(full_min, 2.35 / 0.25, 1.5);
  EXPECT_NEAR(half_min / full_min, 0.51, 0.15);
}

}  // namespace
}  // namespace glarecam::hazard

namespace glarecam::hazard {
namespace {

// Whether the segment from a to b crosses a face (its plane between them, the crossing inside).
bool crossesFace(const ArrayPolygon& face, Vec3 a, Vec3 b) {
  const double da = dot(a - face.centroid_m, face.normal),
               db = dot(b - face.centroid_m, face.normal);
  if ((da > 0) == (db > 0) || da == db) return false;
  const Vec3 x = a + (da / (da - db)) * (b - a);
  return containsPlanePoint(face, x);
}

bool blocked(const std::vector<Obstruction>& obstructions, Vec3 a, Vec3 b) {
  for (const Obstruction& obstruction : obstructions)
    for (const ArrayPolygon& face : obstruction.faces)
      if (crossesFace(face, a, b)) return true;
  return false;
}

TEST(HazardObstructions, AgreeWithBruteForceRayTracing) {
  // The noon glare of an 8 m array 60 m away, with a screen halfway hiding a corner of it from
  // the observer and a box south of it shading another part at noon. Each minute of the day, the
  // brute force samples the array on a 160 × 160 grid, keeps the points the observer sees (the
  // segment to them crosses no face) and the sun lights (nor does the ray toward the sun, 1 km
  // long), and decides glare by the least f over them. The calculation must agree at every
  // minute whose brute-force least √f is not within the grid's resolution of 1: the grid's
  // spacing, 5 cm at 60 m, is 0.048°, 0.024° half a cell, which moves √f by at most 0.024° / 1°
  // (the smaller half-axis) = 0.024.
  const HazardSite site = zurichSite();
  const SolarNoon noon = solarNoon(site, kApril20);
  const Vec3 sun_noon = sunVector(noon.position);
  const ArrayPolygon array = arrayReflecting(sun_noon, kSouthTilted30, 60, 8);
  const Vec3 c = normalised(array.centroid_m);
  const Vec3 h = normalised(cross(c, {0, 0, 1}));
  const Vec3 up = cross(h, c);
  Scene scene = sceneOf(site, {array}, {{.name = "window", .position_m = {0, 0, 0}}});
  // The screen at 30 m covers the array's half right of its centre.
  const Vec3 middle = 30 * c;
  scene.obstructions.push_back(*makePlanarObstruction(
      "screen", {middle - 5 * up, middle + 5 * h - 5 * up, middle + 5 * h + 5 * up, middle + 5 * up},
      "scene.json",
      "obstructions[0]"));
  // A box 6 m toward the noon sun from the array's centre, 3 m wide: shades a patch of it.
  const Vec3 shade = array.centroid_m + 6 * sun_noon;
  scene.obstructions.push_back(*makeExtrudedObstruction("box",
                                                        {{shade.x - 1.5, shade.y - 1.5},
                                                         {shade.x + 1.5, shade.y - 1.5},
                                                         {shade.x + 1.5, shade.y + 1.5},
                                                         {shade.x - 1.5, shade.y + 1.5}},
                                                        shade.z - 1.5, shade.z + 1.5, "scene.json",
                                                        "obstructions[1]"));
  const ProfileTable profile = constantProfile(2, 3);
  const HazardOptions options = oneDay(kApril20, 60, {{ModelKind::kEllipse}});
  const Result<HazardResult> result = computeHazard(scene, {&profile}, options);
  ASSERT_TRUE(result) << result.error().message;
  const Result<HazardResult> open = computeHazard(
      sceneOf(site, {array}, {{.name = "window", .position_m = {0, 0, 0}}}), {&profile}, options);
  ASSERT_TRUE(open);

  constexpr int kGrid = 160;
  constexpr double kResolution = 0.024;
  const RegionHalfAxes axes = halfAxesRad(2, 3);
  const UtcTime midnight = localMidnightUtc(site, kApril20);
  int compared = 0, glaring = 0, hidden_by_obstructions = 0;
  for (int k = 0; k < 1440; ++k) {
    const bool open_glare = open->observers[0].steps[static_cast<std::size_t>(k)] & 1u;
    if (!open_glare) continue;  // nothing to hide
    const auto position = sun::solarPosition(
        midnight + microseconds(std::int64_t{k} * 60'000'000 + 30'000'000), site.location);
    const Vec3 sun = sunVector(*position);
    const RegionFrame frame = regionFrame(array.normal, sun, array.up_slope);
    double least = std::numeric_limits<double>::infinity();
    for (int i = 0; i < kGrid; ++i) {
      for (int j = 0; j < kGrid; ++j) {
        const double u = -4 + 8 * (i + 0.5) / kGrid, w = -4 + 8 * (j + 0.5) / kGrid;
        const Vec3 p = array.centroid_m + u * array.axis_u + w * array.axis_w;
        if (blocked(scene.obstructions, {0, 0, 0}, p)) continue;
        if (blocked(scene.obstructions, p, p + 1000 * sun)) continue;
        least = std::min(least, std::sqrt(normalisedDistance(frame, axes, normalised(p))));
      }
    }
    const bool computed = result->observers[0].steps[static_cast<std::size_t>(k)] & 1u;
    hidden_by_obstructions += computed ? 0 : 1;
    if (std::abs(least - 1) < kResolution) continue;
    ++compared;
    glaring += least < 1 ? 1 : 0;
    EXPECT_EQ(computed, least < 1) << "minute " << k << ": brute force √f " << least;
  }
  EXPECT_GT(compared, 10);
  EXPECT_GT(glaring, 0);
  EXPECT_GT(hidden_by_obstructions, 0);  // the obstructions took some minutes
}

}  // namespace
}  // namespace glarecam::hazard
