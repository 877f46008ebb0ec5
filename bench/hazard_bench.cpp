// hazard/year: `glarecam hazard`'s calculation for one array and one observer over a year at
// 60-s steps (525 600 steps, ellipse and circle), on one thread, beside sun/year_spa (the same
// year's sun directions alone: the floor every step pays). hazard/scene: 10 arrays × 20 observers,
// the size of a report on a housing estate. main() prints hazard ÷ sun (target ≤ 1.5) and what
// each extra array–observer pair adds, as a fraction of the sun pass (target ≤ 0.10).
#include <benchmark/benchmark.h>

#include <chrono>
#include <cmath>

#include "bench/benchmarks.h"
#include "hazard/hazard_calculation.h"
#include "hazard/profile_table.h"
#include "hazard/scene.h"
#include "sun/solar_track.h"

namespace glarecam::bench {
namespace {

constexpr int kYear = 2027;

// A profile of the demo module's size: 6° × 4° wherever it glares (0–80°).
hazard::ProfileTable benchProfile() {
  nlohmann::json rows = nlohmann::json::array();
  for (int alpha = 0; alpha <= 80; ++alpha) {
    rows.push_back({{"alpha_deg", alpha},
                    {"lmax_cd_m2", 1e6},
                    {"limit_cd_m2", 3e4},
                    {"vertical_deg", 6.0},
                    {"horizontal_deg", 4.0},
                    {"circular_beam", {{"beta_mrad", 85.5}}}});
  }
  const nlohmann::json document{{"schema", pipeline::kGlareProfileSchemaV1},
                                {"module", "bench module"},
                                {"glare_ranges_deg", {{0.0, 80.0}}},
                                {"profile", rows}};
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

void runYear(benchmark::State& state, int arrays, int observers) {
  const hazard::ProfileTable profile = benchProfile();
  const hazard::Scene scene = benchScene(arrays, observers);
  const std::vector<const hazard::ProfileTable*> profiles(scene.arrays.size(), &profile);
  hazard::HazardOptions options;
  options.year = kYear;
  options.threads = 1;
  double minutes = 0;
  for (auto _ : state) {
    const Result<hazard::HazardResult> result = hazard::computeHazard(scene, profiles, options);
    if (!result) {
      state.SkipWithError(result.error().message.c_str());
      return;
    }
    // DoNotOptimize on the result's storage, not on a double: benchmark 1.7's "+m,r" constraint
    // can hand a double back corrupted (google/benchmark#1340).
    benchmark::DoNotOptimize(result->observers.data());
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
  return {kSunYearSpa, kHazardYear, kHazardScene};
}

}  // namespace glarecam::bench
