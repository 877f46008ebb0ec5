// sun/glarecam_spa: glarecam's NREL SPA (sun/solar_position.h) for one day at one-minute
// steps (1440 positions, what planning a day's captures at α targets needs) at SPA's test site,
// beside sun/libnova: libnova 0.16's apparent solar coordinates, horizontal conversion and
// refraction for the same instants. libnova is the peer glarecam did not choose: it is 0.066° off
// in azimuth on SPA's documented test case (docs/rig.md), SPA is within 0.0003°; the ratio
// spa ÷ libnova is the price of that accuracy.
#include <benchmark/benchmark.h>
#include <libnova/libnova.h>

#include <chrono>
#include <cmath>

#include "bench/benchmarks.h"
#include "sun/solar_position.h"

namespace glarecam::bench {
namespace {

constexpr int kPositionsPerDay = 24 * 60;
// SPA's test case: Golden, Colorado (Reda & Andreas, NREL/TP-560-34302).
constexpr double kLatitudeDeg = 39.742476;
constexpr double kLongitudeDeg = -105.1786;
constexpr double kPressureHpa = 820;
constexpr double kTemperatureC = 11;
constexpr double kJulianDayOfUnixEpoch = 2440587.5;
constexpr double kSecondsPerDay = 86400;

using std::chrono::microseconds;
using std::chrono::sys_days;

const auto kDayStart =
    std::chrono::time_point_cast<microseconds>(sys_days{std::chrono::year{2026} / 6 / 21});

void glarecamSpa(benchmark::State& state) {
  sun::SiteLocation site;
  site.latitude_deg = kLatitudeDeg;
  site.longitude_deg = kLongitudeDeg;
  site.pressure_hpa = kPressureHpa;
  site.temperature_c = kTemperatureC;
  double sum = 0;
  for (auto _ : state) {
    for (int minute = 0; minute < kPositionsPerDay; ++minute) {
      const auto position = sun::solarPosition(kDayStart + std::chrono::minutes(minute), site);
      sum += position ? position->azimuth_deg : 0;
    }
  }
  benchmark::DoNotOptimize(sum);
  state.SetItemsProcessed(state.iterations() * kPositionsPerDay);
}

void libnovaPositions(benchmark::State& state) {
  const double day_start_jd =
      kJulianDayOfUnixEpoch +
      std::chrono::duration<double>(kDayStart.time_since_epoch()).count() / kSecondsPerDay;
  ln_lnlat_posn observer{kLongitudeDeg, kLatitudeDeg};
  double sum = 0;
  for (auto _ : state) {
    for (int minute = 0; minute < kPositionsPerDay; ++minute) {
      const double jd = day_start_jd + minute / (24.0 * 60.0);
      ln_equ_posn equatorial;
      ln_get_solar_equ_coords(jd, &equatorial);
      ln_hrz_posn horizontal;
      ln_get_hrz_from_equ(&equatorial, &observer, jd, &horizontal);
      sum += horizontal.az + ln_get_refraction_adj(horizontal.alt, kPressureHpa, kTemperatureC);
    }
  }
  benchmark::DoNotOptimize(sum);
  state.SetItemsProcessed(state.iterations() * kPositionsPerDay);
}

}  // namespace

std::vector<std::string> registerSunBenchmarks() {
  benchmark::RegisterBenchmark(kSunGlarecamSpa, glarecamSpa)->Unit(benchmark::kMillisecond);
  benchmark::RegisterBenchmark(kSunLibnova, libnovaPositions)->Unit(benchmark::kMillisecond);
  return {kSunGlarecamSpa, kSunLibnova};
}

}  // namespace glarecam::bench
