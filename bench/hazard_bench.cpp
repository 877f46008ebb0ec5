// hazard/year: `glarecam hazard`'s calculation for one array and one observer over a year at
// 60-s steps (525 600 steps, ellipse and circle), on one thread, beside sun/year_spa (the same
// year's sun directions alone: the floor every step pays). hazard/scene: 10 arrays × 20 observers,
// the size of a report on a housing estate. main() prints hazard ÷ sun (target ≤ 1.5) and what
// each extra array–observer pair adds, as a fraction of the sun pass (target ≤ 0.10).
// hazard/year_clear_sky: hazard/year under a clear sky's sun, the region from the profile's
// contour ladder at every step (target ≤ 1.3× hazard/year); hazard/year_obstructions: the same
// with 5 buildings around, whose shadows and what they hide are clipped (target ≤ 2×).
#include <benchmark/benchmark.h>

#include <array>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <optional>

#include "bench/benchmarks.h"
#include "hazard/hazard_calculation.h"
#include "hazard/obstruction.h"
#include "hazard/profile_table.h"
#include "hazard/scene.h"
#include "hazard/screening.h"
#include "sun/solar_track.h"

namespace glarecam::bench {
namespace {

constexpr int kYear = 2027;

// A profile of the demo module's size: 6° × 4° wherever it glares (0–80°); with `ladder`, a
// glarecam.glare-profile/2 referred to 100 klx whose contour ladder is a log-quadratic lobe with
// that limit ellipse (as a measured sweep's is).
hazard::ProfileTable benchProfile(bool ladder = false) {
  nlohmann::json rows = nlohmann::json::array();
  for (int alpha = 0; alpha <= 80; ++alpha) {
    rows.push_back({{"alpha_deg", alpha},
                    {"lmax_cd_m2", 1e6},
                    {"limit_cd_m2", 3e4},
                    {"vertical_deg", 6.0},
                    {"horizontal_deg", 4.0},
                    {"circular_beam", {{"beta_mrad", 85.5}}}});
  }
  nlohmann::json document{{"schema", pipeline::kGlareProfileSchemaV1},
                          {"module", "bench module"},
                          {"glare_ranges_deg", {{0.0, 80.0}}},
                          {"profile", rows}};
  if (ladder) {
    constexpr double kLmax = 1e6, kLimit = 3e4;
    nlohmann::json degrees = nlohmann::json::array();
    for (int alpha = 0; alpha <= 80; ++alpha) {
      nlohmann::json contours = nlohmann::json::array();
      for (const double level : {1e4, 2.15e4, 4.64e4, 1e5, 2.15e5, 4.64e5}) {
        const double scale = std::sqrt(std::log(kLmax / level) / std::log(kLmax / kLimit));
        contours.push_back({{"level_cd_m2", level},
                            {"kind", "ladder"},
                            {"vertical_deg", 6.0 * scale},
                            {"horizontal_deg", 4.0 * scale},
                            {"orientation_deg", 0.0},
                            {"solid_angle_sr", 7.3e-3 * scale * scale},
                            {"uncertainty",
                             {{"vertical_deg", 0.0},
                              {"horizontal_deg", 0.0},
                              {"orientation_deg", 0.0},
                              {"solid_angle_sr", 0.0}}}});
      }
      degrees.push_back({{"alpha_deg", alpha}, {"contours", contours}});
    }
    document["schema"] = pipeline::kGlareProfileSchema;
    document["illuminance"] = {{"status", "referred"}, {"reference_lx", 1e5}};
    document["ladder"] = degrees;
  }
  return *hazard::ProfileTable::fromJson(document, "bench-profile.json");
}

// Roofs like docs/examples/hazard-scene.json's (12 m wide, sloping 30° down to the north),
// 15 m apart along x, and windows north of them: every window sees glare in the year.
hazard::Scene benchScene(int arrays, int observers) {
  hazard::Scene scene;
  scene.path = "bench-scene.json";
  scene.site.location.latitude_deg = 47.37;
  scene.site.location.longitude_deg = 8.54;
  scene.site.location.altitude_m = 410;
  scene.site.utc_offset_h = 1;
  for (int a = 0; a < arrays; ++a) {
    const double x = 15.0 * a;
    scene.arrays.push_back(*hazard::makeArrayPolygon(
        "roof-" + std::to_string(a),
        {{x - 6, 0, 9}, {x + 6, 0, 9}, {x + 6, 5.2, 6}, {x - 6, 5.2, 6}}, "bench", "roof"));
  }
  for (int o = 0; o < observers; ++o)
    scene.observers.push_back(
        {.name = "window-" + std::to_string(o), .position_m = {7.0 * o, 30, 12}});
  return scene;
}

// Five buildings around the first roof and window: one south of the roof (its shadow falls on it
// in winter), two between the roof and the window (they hide parts of it), two beside them.
void addBuildings(hazard::Scene& scene) {
  const std::array<std::array<double, 5>, 5> kBuildings = {{
      // x0, y0, x1, y1, height_m
      {-5, -16, 5, -10, 12},
      {-10, 14, -3, 18, 10.5},
      {2, 16, 9, 20, 11.5},
      {-25, 0, -18, 8, 15},
      {18, 5, 26, 12, 11},
  }};
  for (std::size_t b = 0; b < kBuildings.size(); ++b) {
    const auto& [x0, y0, x1, y1, height] = kBuildings[b];
    scene.obstructions.push_back(*hazard::makeExtrudedObstruction(
        "house-" + std::to_string(b), {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}}, 0, height, "bench",
        "obstructions"));
  }
}

enum class BenchSun { kReference, kClearSky, kClearSkyObstructed };

// One year of the scene, or nullopt with the benchmark marked skipped with the reason. The caller
// keeps the result's storage alive: DoNotOptimize on it, not on a double (benchmark 1.7's "+m,r"
// constraint can hand a double back corrupted, google/benchmark#1340).
std::optional<hazard::HazardResult> computeYear(
    benchmark::State& state, const hazard::Scene& scene,
    const std::vector<const hazard::ProfileTable*>& profiles,
    const hazard::HazardOptions& options) {
  Result<hazard::HazardResult> result = hazard::computeHazard(scene, profiles, options);
  if (!result) {
    state.SkipWithError(result.error().message.c_str());
    return std::nullopt;
  }
  benchmark::DoNotOptimize(result->observers.data());
  return std::move(*result);
}

void runYear(benchmark::State& state, int arrays, int observers,
             BenchSun sun = BenchSun::kReference) {
  const hazard::ProfileTable profile = benchProfile(sun != BenchSun::kReference);
  hazard::Scene scene = benchScene(arrays, observers);
  if (sun == BenchSun::kClearSkyObstructed) addBuildings(scene);
  const std::vector<const hazard::ProfileTable*> profiles(scene.arrays.size(), &profile);
  hazard::HazardOptions options;
  options.year = kYear;
  options.threads = 1;
  if (sun != BenchSun::kReference) options.sun.kind = hazard::SunKind::kClearSky;
  double minutes = 0;
  for (auto _ : state) {
    const std::optional<hazard::HazardResult> result = computeYear(state, scene, profiles, options);
    if (!result) return;
    minutes = result->observers[0].models[0].minutes_per_year;
  }
  state.counters["steps"] = 365.0 * 1440;
  state.counters["pairs"] = arrays * observers;
  state.counters["min_per_year"] = minutes;  // observer 0, ellipse: proof that it glares
}

// The floor: the same year's sun directions, day by day as computeHazard asks for them.
void sunYear(benchmark::State& state) {
  const hazard::Scene scene = benchScene(1, 1);
  const auto start = std::chrono::time_point_cast<std::chrono::microseconds>(
                         std::chrono::sys_days{std::chrono::year{kYear} / 1 / 1}) -
                     std::chrono::hours(1);
  const std::chrono::microseconds step(60'000'000);
  std::vector<sun::SunDirection> day(1440);
  for (auto _ : state) {
    for (int d = 0; d < 365; ++d) {
      const Status status =
          sun::solarTrack(start + std::chrono::days(d) + step / 2, step, day, scene.site.location);
      if (!status) {
        state.SkipWithError(status.error().message.c_str());
        return;
      }
    }
    benchmark::DoNotOptimize(day.data());
  }
  state.counters["steps"] = 365.0 * 1440;
}

// hazard/pairs/*: 20 pairs of one roof, all glaring (windows north of it, as benchScene's) or
// none ever (windows along the roof's normal, where the sun, which never stands 60° high in the
// north at 47° N, would have to be: the day-level bound rejects every day), and none at all (the
// year's sun alone, the floor both pay). Steps are not kept, as in a screening.
enum class BenchPairs { kNone, kNever, kGlaring };
constexpr int kBenchPairs = 20;

void runPairs(benchmark::State& state, BenchPairs pairs) {
  const hazard::ProfileTable profile = benchProfile();
  hazard::Scene scene = benchScene(1, 0);
  const hazard::ArrayPolygon& roof = scene.arrays[0];
  for (int o = 0; pairs != BenchPairs::kNone && o < kBenchPairs; ++o) {
    const hazard::Vec3 position = pairs == BenchPairs::kGlaring
                                      ? hazard::Vec3{-9.5 + o, 30, 12}
                                      : roof.centroid_m + (15.0 + o) * roof.normal;
    scene.observers.push_back({.name = "window-" + std::to_string(o), .position_m = position});
  }
  const std::vector<const hazard::ProfileTable*> profiles(scene.arrays.size(), &profile);
  hazard::HazardOptions options;
  options.year = kYear;
  options.threads = 1;
  options.keep_steps = false;
  double minutes = 0;
  for (auto _ : state) {
    const std::optional<hazard::HazardResult> result = computeYear(state, scene, profiles, options);
    if (!result) return;
    minutes = 0;
    for (const hazard::ObserverHazard& observer : result->observers)
      minutes += observer.models[0].minutes_per_year;
  }
  state.counters["pairs"] = pairs == BenchPairs::kNone ? 0 : kBenchPairs;
  state.counters["min_per_year"] = minutes;  // all windows, ellipse: > 0 only when glaring
}

// hazard/city/R_roofs: a scripts/make-city district of R roofs and 4 R receptors screened over a
// year at 60-s steps on every core, 100 m around each receptor (`glarecam hazard --screen`'s
// calculation, without reading and writing files). Three sizes: the time per candidate pair
// should not grow with the district.
void runCity(benchmark::State& state, int roofs) {
  const std::filesystem::path scene_path =
      std::filesystem::temp_directory_path() /
      ("glarecam-bench-city-" + std::to_string(roofs) + ".geojson");
  const std::string command = "python3 " GLARECAM_SOURCE_DIR "/scripts/make-city --roofs " +
                              std::to_string(roofs) + " --receptors " + std::to_string(4 * roofs) +
                              " --out " + scene_path.string() + " >/dev/null 2>&1";
  if (std::system(command.c_str()) != 0) {
    state.SkipWithError("scripts/make-city failed (python3 missing?)");
    return;
  }
  const Result<hazard::Scene> scene = hazard::readScene(scene_path);
  std::filesystem::remove(scene_path);
  if (!scene) {
    state.SkipWithError(scene.error().message.c_str());
    return;
  }
  const hazard::ProfileTable profile = benchProfile();
  const std::vector<const hazard::ProfileTable*> profiles(scene->arrays.size(), &profile);
  hazard::ScreenOptions options;
  options.hazard.year = kYear;
  options.hazard.max_distance_m = hazard::kDefaultMaxDistanceM;
  std::size_t candidates = 0, glaring = 0;
  std::int64_t pair_days = 0;
  for (auto _ : state) {
    const Result<hazard::ScreenResult> result = hazard::screenHazard(*scene, profiles, options);
    if (!result) {
      state.SkipWithError(result.error().message.c_str());
      return;
    }
    benchmark::DoNotOptimize(result->points.data());
    candidates = result->counts.candidate_pairs;
    pair_days = 0;
    glaring = 0;
    for (const hazard::ScreenedPoint& point : result->points) {
      pair_days += point.pair_days;
      glaring += point.models[0].arrays.size();
    }
  }
  state.counters["receptor_points"] = static_cast<double>(scene->observers.size());
  state.counters["candidate_pairs"] = static_cast<double>(candidates);
  state.counters["pair_days"] = static_cast<double>(pair_days);
  state.counters["glaring_pairs"] = static_cast<double>(glaring);
  state.counters["s_per_1000_pairs"] = benchmark::Counter(
      static_cast<double>(candidates) / 1000.0,
      benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

}  // namespace

std::vector<std::string> registerHazardBenchmarks() {
  benchmark::RegisterBenchmark(kSunYearSpa, sunYear)->Unit(benchmark::kMillisecond)->UseRealTime();
  benchmark::RegisterBenchmark(kHazardYear, [](benchmark::State& s) { runYear(s, 1, 1); })
      ->Unit(benchmark::kMillisecond)
      ->UseRealTime();
  benchmark::RegisterBenchmark(kHazardScene, [](benchmark::State& s) { runYear(s, 10, 20); })
      ->Unit(benchmark::kMillisecond)
      ->UseRealTime()
      ->Iterations(1);
  benchmark::RegisterBenchmark(kHazardYearClearSky,
                               [](benchmark::State& s) { runYear(s, 1, 1, BenchSun::kClearSky); })
      ->Unit(benchmark::kMillisecond)
      ->UseRealTime();
  benchmark::RegisterBenchmark(
      kHazardYearObstructions,
      [](benchmark::State& s) { runYear(s, 1, 1, BenchSun::kClearSkyObstructed); })
      ->Unit(benchmark::kMillisecond)
      ->UseRealTime();
  const std::pair<const char*, BenchPairs> kPairs[] = {{kHazardPairsNone, BenchPairs::kNone},
                                                       {kHazardPairsNever, BenchPairs::kNever},
                                                       {kHazardPairsGlaring, BenchPairs::kGlaring}};
  std::vector<std::string> names = {kSunYearSpa, kHazardYear, kHazardScene, kHazardYearClearSky,
                                    kHazardYearObstructions};
  for (const auto& [name, pairs] : kPairs) {
    benchmark::RegisterBenchmark(name, [pairs](benchmark::State& s) { runPairs(s, pairs); })
        ->Unit(benchmark::kMillisecond)
        ->UseRealTime();
    names.emplace_back(name);
  }
  for (const int roofs : kHazardCityRoofs) {
    const std::string name = std::string(kHazardCity) + "/" + std::to_string(roofs) + "_roofs";
    benchmark::RegisterBenchmark(name.c_str(), [roofs](benchmark::State& s) { runCity(s, roofs); })
        ->Unit(benchmark::kSecond)
        ->UseRealTime()
        ->Iterations(1);
    names.push_back(name);
  }
  return names;
}

}  // namespace glarecam::bench
