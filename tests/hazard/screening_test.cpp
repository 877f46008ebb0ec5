// Screening a district (hazard/screening.h, hazard/candidate_pairs.h): shards merge into
// exactly one run's outputs, in any order; the day-level bound never drops a day that glares
// (checked by brute force); the screening's numbers equal the full calculation's.
#include "hazard/screening.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <random>
#include <sstream>

#include "core/angles.h"
#include "hazard/candidate_pairs.h"
#include "hazard/hazard_run.h"
#include "hazard/scene.h"
#include "sun/solar_track.h"
#include "tests/hazard/hazard_fixtures.h"

namespace glarecam::hazard {
namespace {

using nlohmann::json;
using testing::constantProfileJson;
using testing::squareVertices;
using testing::unitToward;

std::string fileText(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

class ScreeningTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           ("screening_test_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
    std::ofstream(dir_ / "profile.json") << constantProfileJson(4, 8).dump();
    // A small district: roofs facing every way at several tilts, windows around them, a route
    // and a building in between. Deterministic (a fixed seed).
    std::mt19937 random(7);
    std::uniform_real_distribution<double> coordinate(-60, 60), unit(0, 1);
    json arrays = json::array(), observers = json::array();
    for (int i = 0; i < 10; ++i) {
      const double azimuth_deg = 36.0 * i, tilt_deg = 10 + 5.0 * (i % 6);
      const Vec3 normal = unitToward(90 - tilt_deg, azimuth_deg);
      const Vec3 centre{coordinate(random), coordinate(random), 6 + 4 * unit(random)};
      json vertices = json::array();
      for (const Vec3& v : squareVertices(centre, normal, 4 + 2 * unit(random)))
        vertices.push_back({v.x, v.y, v.z});
      arrays.push_back({{"name", "roof-" + std::to_string(i)}, {"vertices_m", vertices}});
    }
    for (int i = 0; i < 36; ++i) {
      json observer = {
          {"name", "window-" + std::to_string(i)},
          {"position_m", {coordinate(random), coordinate(random), 2 + 10 * unit(random)}}};
      if (i % 3 == 0) observer["facing_azimuth_deg"] = 30.0 * (i % 12);
      observers.push_back(observer);
    }
    const json scene = {
        {"schema", kSceneSchema},
        {"site",
         {{"latitude_deg", 47.37},
          {"longitude_deg", 8.54},
          {"elevation_m", 410},
          {"utc_offset_h", 1.0}}},
        {"arrays", arrays},
        {"observers", observers},
        {"routes",
         {{{"name", "road"}, {"points_m", {{-70, -10, 1.1}, {70, 15, 1.1}}}, {"spacing_m", 20}}}},
        {"obstructions",
         {{{"name", "house"},
           {"footprint_m", {{-5, -5}, {5, -5}, {5, 5}, {-5, 5}}},
           {"base_m", 0},
           {"height_m", 8}}}}};
    std::ofstream(dir_ / "scene.json") << scene.dump(1);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  HazardRunOptions runOptions(const std::string& out) const {
    HazardRunOptions options;
    options.scene = dir_ / "scene.json";
    options.profile = dir_ / "profile.json";
    options.out = dir_ / out;
    options.hazard.year = 2026;
    // Ten-minute steps: a whole year (a screening's unit) of this district in a second or two;
    // the merge's equality does not depend on the step.
    options.hazard.step_s = 600;
    options.hazard.max_distance_m = 50;
    options.hazard.sun = SunBrightness{};  // the reference sun: the constant profile has no ladder
    options.show_progress = false;
    options.screen = true;
    return options;
  }

  std::filesystem::path dir_;
};

constexpr const char* kOutputs[] = {"screen.json", "receptors.csv", "hazard.geojson"};

TEST_F(ScreeningTest, ShardsMergeIntoExactlyOneRunInAnyOrder) {
  ASSERT_TRUE(runHazard(runOptions("single")).has_value());
  const json screen = json::parse(fileText(dir_ / "single" / "screen.json"));
  // The district is not trivial: some pairs are beyond the distance, some see a back, some glare.
  EXPECT_LT(screen["counts"]["candidate_pairs"].get<int>(),
            screen["counts"]["pairs_within_distance"].get<int>());
  EXPECT_LT(screen["counts"]["pairs_within_distance"].get<int>(), 10 * 36);
  EXPECT_GT(screen["counts"]["glaring_pairs"].get<int>(), 0);
  for (const unsigned count : {1u, 3u, 7u}) {
    std::vector<std::filesystem::path> shards;
    for (unsigned index = 0; index < count; ++index) {
      HazardRunOptions options =
          runOptions("shards" + std::to_string(count) + "/" + std::to_string(index));
      options.shard = ShardSpec{index, count};
      ASSERT_TRUE(runHazard(options).has_value());
      shards.push_back(options.out);
    }
    // Order-independent: reversed, and rotated.
    std::reverse(shards.begin(), shards.end());
    std::rotate(shards.begin(), shards.begin() + count / 2, shards.end());
    const std::string merged = "merged" + std::to_string(count);
    const Result<HazardRunSummary> merge =
        runHazardMerge({.shards = shards, .out = dir_ / merged, .scene = std::nullopt});
    ASSERT_TRUE(merge.has_value()) << merge.error().message;
    for (const char* file : kOutputs)
      EXPECT_EQ(fileText(dir_ / "single" / file), fileText(dir_ / merged / file))
          << file << " differs after merging " << count << " shards";
  }
}

TEST_F(ScreeningTest, ShardsAreBalancedAndCoverEveryPointOnce) {
  std::vector<std::size_t> seen;
  for (unsigned index = 0; index < 3; ++index) {
    HazardRunOptions options = runOptions("s" + std::to_string(index));
    options.shard = ShardSpec{index, 3};
    ASSERT_TRUE(runHazard(options).has_value());
    const Result<ShardFile> shard = readShard(options.out / "shard.json");
    ASSERT_TRUE(shard.has_value());
    EXPECT_FALSE(shard->result.points.empty()) << "shard " << index << " got no point";
    for (const ScreenedPoint& point : shard->result.points) seen.push_back(point.observer);
  }
  std::sort(seen.begin(), seen.end());
  EXPECT_TRUE(std::adjacent_find(seen.begin(), seen.end()) == seen.end());
  const Result<Scene> scene = readScene(dir_ / "scene.json");
  ASSERT_TRUE(scene.has_value());
  EXPECT_EQ(seen.size(), scene->observers.size());  // 36 windows and the road's points
}

TEST_F(ScreeningTest, MergeRefusesMissingRepeatedAndForeignShards) {
  std::vector<std::filesystem::path> shards;
  for (unsigned index = 0; index < 3; ++index) {
    HazardRunOptions options = runOptions("s" + std::to_string(index));
    options.shard = ShardSpec{index, 3};
    ASSERT_TRUE(runHazard(options).has_value());
    shards.push_back(options.out);
  }
  const auto mergeOf = [&](std::vector<std::filesystem::path> given) {
    return runHazardMerge({.shards = std::move(given), .out = dir_ / "m", .scene = std::nullopt});
  };
  Result<HazardRunSummary> merged = mergeOf({shards[0], shards[2]});
  ASSERT_FALSE(merged.has_value());
  EXPECT_NE(merged.error().message.find("shard 1/3 is missing"), std::string::npos)
      << merged.error().message;
  merged = mergeOf({shards[0], shards[1], shards[1], shards[2]});
  ASSERT_FALSE(merged.has_value());
  EXPECT_NE(merged.error().message.find("given twice"), std::string::npos);
  // A shard of other options (another year) is another screening.
  HazardRunOptions other = runOptions("other");
  other.hazard.year = 2027;
  other.shard = ShardSpec{1, 3};
  ASSERT_TRUE(runHazard(other).has_value());
  merged = mergeOf({shards[0], other.out, shards[2]});
  ASSERT_FALSE(merged.has_value());
  EXPECT_NE(merged.error().message.find("the options (year: 2027 against 2026) differ"),
            std::string::npos)
      << merged.error().message;
  EXPECT_EQ(merged.error().code, ErrorCode::kBadInput);
  // A shard of another profile (same scene, same options, refitted profile) is another screening.
  std::ofstream(dir_ / "profile-b.json") << constantProfileJson(4, 9).dump();
  HazardRunOptions refitted = runOptions("refitted");
  refitted.profile = dir_ / "profile-b.json";
  refitted.shard = ShardSpec{1, 3};
  ASSERT_TRUE(runHazard(refitted).has_value());
  merged = mergeOf({shards[0], refitted.out, shards[2]});
  ASSERT_FALSE(merged.has_value());
  EXPECT_NE(merged.error().message.find("the options (profiles_sha256: "), std::string::npos);
  // A damaged shard: an array index beyond the scene's is refused, not written through.
  {
    json damaged = json::parse(fileText(shards[1] / "shard.json"));
    damaged["points"][0]["models"][0]["arrays"] = {999999};
    std::filesystem::create_directories(dir_ / "damaged");
    std::ofstream(dir_ / "damaged" / "shard.json") << damaged.dump();
  }
  merged = mergeOf({shards[0], dir_ / "damaged", shards[2]});
  ASSERT_FALSE(merged.has_value());
  EXPECT_EQ(merged.error().code, ErrorCode::kBadInput);
  EXPECT_NE(merged.error().message.find("damaged"), std::string::npos) << merged.error().message;
  // A screening without a distance is refused before anything is read.
  HazardRunOptions unlimited = runOptions("unlimited");
  unlimited.hazard.max_distance_m = kUnlimitedDistanceM;
  const Result<HazardRunSummary> refused = runHazard(unlimited);
  ASSERT_FALSE(refused.has_value());
  EXPECT_NE(refused.error().message.find("--max-distance"), std::string::npos);
  // No shard at all, and a directory without one.
  merged = mergeOf({dir_ / "nowhere"});
  ASSERT_FALSE(merged.has_value());
  EXPECT_NE(merged.error().message.find("no shard.json"), std::string::npos);
  EXPECT_FALSE(mergeOf({}).has_value());
  EXPECT_FALSE(std::filesystem::exists(dir_ / "m" / "screen.json"));
}

TEST_F(ScreeningTest, EqualsTheFullCalculationPointByPoint) {
  ASSERT_TRUE(runHazard(runOptions("single")).has_value());
  Result<Scene> scene = readScene(dir_ / "scene.json");
  ASSERT_TRUE(scene.has_value());
  Result<ProfileTable> profile = ProfileTable::read(dir_ / "profile.json");
  ASSERT_TRUE(profile.has_value());
  const std::vector<const ProfileTable*> profiles(scene->arrays.size(), &*profile);
  HazardOptions options = runOptions("x").hazard;
  // Every pair within the distance, all steps kept: the ordinary calculation.
  const Result<HazardResult> full = computeHazard(*scene, profiles, options);
  ASSERT_TRUE(full.has_value());
  // Batches of 5 points: results must not depend on which points share a batch.
  ScreenOptions screen{.hazard = options, .shard = std::nullopt, .batch_points = 5};
  const Result<ScreenResult> screened = screenHazard(*scene, profiles, screen);
  ASSERT_TRUE(screened.has_value());
  ASSERT_EQ(screened->points.size(), scene->observers.size());
  int glaring = 0;
  for (std::size_t o = 0; o < scene->observers.size(); ++o) {
    for (std::size_t m = 0; m < options.models.size(); ++m) {
      const ModelSummary& expected = full->observers[o].models[m];
      const ScreenedModel& got = screened->points[o].models[m];
      EXPECT_EQ(got.minutes_per_year, expected.minutes_per_year) << scene->observers[o].name;
      EXPECT_EQ(got.days_with_glare, expected.days_with_glare);
      EXPECT_EQ(got.max_minutes_per_day, expected.max_minutes_per_day);
      EXPECT_EQ(got.steps_beyond_method, expected.steps_beyond_method);
      glaring += got.minutes_per_year > 0 ? 1 : 0;
    }
  }
  EXPECT_GT(glaring, 0);
}

// The bound checked by brute force: on every day it rejects a pair, at every step with the sun
// up, no point of the array (a 5 × 5 grid over it) lies within the largest region of
// the profile around the sun's mirror image. The bound must also reject most pair-days here, or
// it would prove nothing.
TEST_F(ScreeningTest, ADayTheBoundRejectsHasNoGlareByBruteForce) {
  Result<Scene> scene = readScene(dir_ / "scene.json");
  ASSERT_TRUE(scene.has_value());
  const double largest_half_axis_rad = radians(8.0 / 2);  // the constant profile's 4° × 8°
  const Vec3 pole = celestialPole(scene->site.location.latitude_deg);
  const int year = 2026, step_s = 600, steps = 86400 / step_s;
  const auto year_start =
      std::chrono::sys_days{std::chrono::year{year} / 1 / 1} - std::chrono::hours(1);
  int rejected = 0, kept = 0;
  for (int day = 0; day < 365; day += 9) {
    const auto first = std::chrono::time_point_cast<std::chrono::microseconds>(
                           year_start + std::chrono::days(day)) +
                       std::chrono::seconds(step_s / 2);
    const auto track = sun::solarTrack(first, std::chrono::seconds(step_s),
                                       static_cast<std::size_t>(steps), scene->site.location);
    ASSERT_TRUE(track.has_value());
    PoleAngleRange range{.min_rad = std::numbers::pi, .max_rad = -1};
    std::vector<Vec3> suns;
    for (const sun::SunDirection& s : *track) {
      const Vec3 sun{s.east, s.north, s.up};
      if (sun.z <= 0) continue;
      suns.push_back(sun);
      range.min_rad = std::min(range.min_rad, angleBetweenRad(sun, pole));
      range.max_rad = std::max(range.max_rad, angleBetweenRad(sun, pole));
    }
    for (const Observer& observer : scene->observers) {
      for (const ArrayPolygon& array : scene->arrays) {
        if (!seesFront(array, observer.position_m)) continue;
        const Vec3 to_centre = array.centroid_m - observer.position_m;
        const double angular_radius = std::asin(std::min(1.0, array.radius_m / norm(to_centre)));
        const double phi = mirroredPoleAngleRad(array, pole, normalised(to_centre));
        if (dayMayReach(phi, largest_half_axis_rad + angular_radius, range)) {
          ++kept;
          continue;
        }
        ++rejected;
        for (const Vec3& sun : suns) {
          const Vec3 c = sun - 2 * dot(array.normal, sun) * array.normal;
          for (int i = 0; i <= 4; ++i) {
            for (int j = 0; j <= 4; ++j) {
              const Vec3 p = array.centroid_m + (array.radius_m * (i / 2.0 - 1)) * array.axis_u +
                             (array.radius_m * (j / 2.0 - 1)) * array.axis_w;
              if (!containsPlanePoint(array, p)) continue;
              ASSERT_GT(angleBetweenRad(c, normalised(p - observer.position_m)),
                        largest_half_axis_rad)
                  << observer.name << " sees " << array.name << " glare on day " << day
                  << " that the bound rejected";
            }
          }
        }
      }
    }
  }
  EXPECT_GT(rejected, 3 * kept) << "the bound rejects too little to be tested";
}

TEST_F(ScreeningTest, AnOrdinaryRunSaysWhatTheDistanceLeavesOut) {
  // The method docs' roof, a window near it and one 149 m away (it sees the roof's front).
  std::ofstream(dir_ / "far.json") << R"({"schema": "glarecam.hazard-scene/1",
    "site": {"latitude_deg": 47.37, "longitude_deg": 8.54, "elevation_m": 410, "utc_offset_h": 1},
    "arrays": [{"name": "roof-north", "vertices_m": [[-6,0,9],[6,0,9],[6,5.2,6],[-6,5.2,6]]}],
    "observers": [{"name": "near", "position_m": [0, 15, 12]},
                  {"name": "far", "position_m": [0, 150, 40]}]})";
  HazardRunOptions options = runOptions("ordinary");
  options.scene = dir_ / "far.json";
  options.screen = false;
  options.hazard.max_distance_m = kDefaultMaxDistanceM;
  const Result<HazardRunSummary> run = runHazard(options);
  ASSERT_TRUE(run.has_value()) << run.error().message;
  const auto warned = std::find_if(
      run->warnings.begin(), run->warnings.end(),
      [](const std::string& w) { return w.find("--max-distance 100 m") != std::string::npos; });
  ASSERT_NE(warned, run->warnings.end()) << ::testing::PrintToString(run->warnings);
  EXPECT_NE(warned->find("not computed against it"), std::string::npos) << *warned;
  EXPECT_NE(warned->find("1 receptor point sees"), std::string::npos) << *warned;
  EXPECT_NE(warned->find("\"far\" is 149 m"), std::string::npos) << *warned;
  // Unlimited: nothing is left out, nothing is said.
  options.hazard.max_distance_m = kUnlimitedDistanceM;
  const Result<HazardRunSummary> all = runHazard(options);
  ASSERT_TRUE(all.has_value());
  for (const std::string& warning : all->warnings)
    EXPECT_EQ(warning.find("--max-distance"), std::string::npos) << warning;
}

TEST(Screening, ShardSpecsAreCheckedWithTheirOption) {
  EXPECT_EQ(parseShard("0/1", "--shard")->count, 1u);
  EXPECT_EQ(parseShard("6/7", "--shard")->index, 6u);
  for (const char* bad : {"", "1", "7/7", "1/0", "-1/3", "a/3", "1/3x", "1//3", "/3", "1/"}) {
    const Result<ShardSpec> shard = parseShard(bad, "--shard");
    ASSERT_FALSE(shard.has_value()) << bad;
    EXPECT_EQ(shard.error().code, ErrorCode::kBadInput);
    EXPECT_NE(shard.error().message.find("--shard"), std::string::npos);
  }
}

TEST(Screening, DistanceToAnArrayIsToItsPolygon) {
  const ArrayPolygon array = testing::squareArray("a", {0, 0, 0}, {0, 0, 1}, 2);
  EXPECT_DOUBLE_EQ(distanceToArrayM(array, {0.5, 0.5, 3}), 3);  // over the inside
  EXPECT_DOUBLE_EQ(distanceToArrayM(array, {4, 0, 0}), 3);      // beside an edge
  EXPECT_DOUBLE_EQ(distanceToArrayM(array, {4, 5, 0}), 5);      // beyond a corner (3, 4)
}

}  // namespace
}  // namespace glarecam::hazard
