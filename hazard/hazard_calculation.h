// Glare minutes at observers over a year (../shared/docs/hazard.md, "The model, per time step"
// and "Counting and criteria"): for every step of the year, for every array and observer and
// every model, whether the observer sees the array's glare region; then minutes per local day
// (inside the observer's hours), per year, the days with glare, each day's first and last glare,
// the events, the steps beyond the method and with an unknown spread, and the criteria's verdicts.
//
// Steps are step_s long and sampled at their middle, from local standard midnight of 1 January.
// The sun's directions of each day are computed once (sun/solar_track.h) and shared by every
// array, observer and model; per array and step the region's frame once, shared by observers.
// A pure function of its inputs; days run in parallel (options.threads) with identical results.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "core/error.h"
#include "hazard/criteria.h"
#include "hazard/glare_model.h"
#include "hazard/ocular_hazard.h"
#include "hazard/profile_table.h"
#include "hazard/scene.h"
#include "hazard/sun_brightness.h"

namespace glarecam::hazard {

// Models per run: each is one bit of a step's mask.
inline constexpr std::size_t kMaxModels = 6;
inline constexpr unsigned kMaxThreads = 1024;
// The distance within which `glarecam hazard` looks for glare by default: Germany's LAI
// guidance ("Hinweise zur Messung, Beurteilung und Minderung von Lichtimmissionen", Anhang 2)
// considers receptors within about 100 m of a PV array.
inline constexpr double kDefaultMaxDistanceM = 100;

struct HazardOptions {
  int year = 0;
  int step_s = 60;  // divides a day; [1, 3600]
  std::vector<GlareModel> models{{ModelKind::kEllipse}, {ModelKind::kCircle}};
  std::vector<Criterion> criteria = knownCriteria();
  unsigned threads = 0;  // 0: one per core; at most kMaxThreads
  // Part of the year only (tests, previews): days [first_day, first_day + day_count) of it,
  // counted from 0 = 1 January; day_count 0 runs to the year's end.
  int first_day = 0, day_count = 0;
  // The sun's brightness at each step (sun_brightness.h). Anything but kReference needs every
  // profile referred, with its contour ladder.
  SunBrightness sun;
  EyeParameters eye;  // for the ocular hazard of each glaring step
  // Receptor points farther than this from an array's polygon are never computed against it
  // (candidate_pairs.h; infinity: every pair). `glarecam hazard` gives kDefaultMaxDistanceM.
  double max_distance_m = std::numeric_limits<double>::infinity();
  // Keep every step's mask (ObserverHazard::steps, for the charts). Off, an observer's steps are
  // not stored and the days on which no array can glare there cost nothing (screening).
  bool keep_steps = true;

  Status validate() const;  // kBadInput naming the option
  // A warning for a year that is valid but unlikely meant (outside kLikelyYears: "27" for 2027, a
  // historical year), nullopt otherwise. The year is computed as given either way.
  std::optional<std::string> yearWarning() const;
};

// The years a glare assessment is likely made for: from when ΔT is measured (SPA's table starts
// its observed values in the 20th century) to well past a plant's life. Outside, --year is
// accepted (the sun's range is far wider) but warned about.
inline constexpr int kLikelyFirstYear = 1950, kLikelyLastYear = 2200;

// One step of one observer, as a bit mask: bit m set when model m glares there (union over the
// arrays); kOutsideHoursBit / kSunDownBit when the step does not count.
inline constexpr std::uint8_t kOutsideHoursBit = 1u << 6;
inline constexpr std::uint8_t kSunDownBit = 1u << 7;

// Where a glaring step is seen from, and what it does to the eye.
struct GlareSighting {
  std::int64_t step = 0;  // from the year's start
  double alpha_deg = 0;
  // The glare as seen from the receptor: the direction to where the region meets the array
  // (azimuth clockwise from north, elevation above the horizontal) and the distance to that
  // point of the array.
  double glare_azimuth_deg = 0, glare_elevation_deg = 0, distance_m = 0;
  double sun_azimuth_deg = 0, sun_elevation_deg = 0;  // apparent, topocentric
  std::optional<double> source_illuminance_lx;        // E(t), when the sun is not the reference
  std::optional<double> luminance_cd_m2;              // L = Lmax (L_edge / Lmax)^q
  std::optional<OcularExposure> ocular;               // of the spot seen (docs/ocular-hazard.md)
};

struct GlareEvent {
  std::size_t observer = 0, array = 0, model = 0;
  std::int64_t first_step = 0, end_step = 0;  // steps from the year's start, [first, end)
  double alpha_min_deg = 0, alpha_max_deg = 0;
  std::optional<double> peak_luminance_cd_m2;  // L = Lmax (L_limit / Lmax)^q, brightest step
  GlareSighting peak{};                        // the brightest step (the first without L)
  std::optional<OcularClass> worst_class{};    // the worst ocular class of its steps
};

struct ModelSummary {
  std::vector<double> minutes_per_day;  // one per local day computed
  double minutes_per_year = 0, hours_per_year = 0;
  int days_with_glare = 0;
  double max_minutes_per_day = 0;
  // Per day: the first and last glaring step of the day (step indices within the day).
  std::vector<std::optional<std::pair<int, int>>> first_last_step;
  std::int64_t steps_beyond_method = 0;  // α > 80° where the 80° region would reach the observer
  std::int64_t steps_unknown_spread = 0;  // α glares, the profile gives this model no spread
  std::vector<Verdict> verdicts;          // per options.criteria
  // Glaring minutes per ocular class (green, yellow, red), and those with no class (the
  // profile gives no luminance there).
  std::array<double, 3> ocular_minutes{};
  double unclassified_minutes = 0;
};

struct ObserverHazard {
  std::vector<ModelSummary> models;  // per options.models
  // days × steps_per_day masks, day-major from first_day; empty unless options.keep_steps
  std::vector<std::uint8_t> steps;
  std::size_t candidates = 0;  // arrays within max_distance_m whose front it sees
  std::int64_t pair_days = 0;  // (candidate, day) pairs the day-level bound let through
};

struct HazardResult {
  int year = 0, steps_per_day = 0, step_s = 0;
  int first_day = 0, days = 0;  // the days computed: [first_day, first_day + days) of the year
  std::vector<ObserverHazard> observers;  // per scene.observers
  std::vector<GlareEvent> events;         // by observer, model, array, then time
};

using HazardProgress = std::function<void(int days_done, int days)>;

// `profiles[i]` is arrays[i]'s profile. kBadInput for invalid options or a profile count that does
// not match the arrays.
Result<HazardResult> computeHazard(const Scene& scene,
                                   const std::vector<const ProfileTable*>& profiles,
                                   const HazardOptions& options,
                                   const HazardProgress& progress = {});

}  // namespace glarecam::hazard
