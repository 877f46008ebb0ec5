#include "hazard/hazard_calculation.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <numbers>
#include <string>
#include <tuple>

#include "core/angles.h"
#include "core/parallel.h"
#include "core/time.h"
#include "hazard/glare_region.h"
#include "hazard/obstruction.h"
#include "hazard/plane_region.h"
#include "sun/solar_track.h"

namespace glarecam::hazard {
namespace {

constexpr int kSecondsPerDay = 86400;
constexpr int kMaxStepS = 3600;
// SPA's years (sun/solar_position.h), less one at each end so that a local year's UTC instants
// stay inside it whatever the offset.
constexpr int kFirstYear = -1999, kLastYear = 5999;
constexpr double kNeverReject = -2;  // a cosine below every cosine
// Days handed to the workers between two progress reports.
constexpr int kDaysPerChunkPerThread = 8;

enum class RegionState { kNone, kGlare, kUnknown, kBeyond };

struct ModelRegion {
  RegionState state = RegionState::kNone;
  bool has_axes = false;
  RegionHalfAxes axes;
};

// One array in one step: shared by every observer. What the cheap rejection needs (lit, c) is
// set for every array; the rest (α, the frame, each model's region) when a pair first needs it.
struct ArrayStep {
  bool lit = false;  // the sun in front of it
  Vec3 sun;
  double cos_alpha = 0;
  Vec3 c;  // the sun's mirror image
  bool resolved = false;
  double alpha_deg = 0;
  RegionFrame frame;
  std::array<ModelRegion, kMaxModels> regions{};
  // With obstructions: the part of the array the sun lights, found when a pair first needs it.
  bool lit_resolved = false;
  PlaneRegion lit_part;
};

// One observer and one array: what never changes over the year. `view` is the part of the
// array the observer can see glare from: all of it, or what its field of view and the
// obstructions leave.
struct Pair {
  PolygonView view;
  bool clipped = false;                         // view is less than the whole array
  std::array<double, kMaxModels> reject_cos{};  // c·d below this: the region cannot reach it
};

// Per array and model: whether some glaring α has no spread there (then every lit step must be
// resolved to count it, not only those the rejection lets through).
using UnknownSpreads = std::array<bool, kMaxModels>;

struct Tally {
  int glare_steps = 0;
  std::optional<std::pair<int, int>> first_last;
  std::int64_t beyond = 0, unknown = 0;
};

struct DayOutput {
  std::vector<std::array<Tally, kMaxModels>> tallies;  // per observer, per model
  std::vector<GlareEvent> events;
};

struct Context {
  const Scene& scene;
  const std::vector<const ProfileTable*>& profiles;
  const HazardOptions& options;
  std::vector<std::vector<Pair>> pairs;         // [observer][array]
  std::vector<UnknownSpreads> unknown_spreads;  // [array]
  int steps_per_day = 0;
  int first_day = 0;
  std::chrono::sys_time<std::chrono::microseconds> year_start_utc;
};

ModelRegion modelRegion(const GlareModel& model, const SpreadAt& spread,
                        const ProfileTable& profile) {
  ModelRegion region;
  if (spread.status == SpreadStatus::kNoGlare) return region;
  if (spread.status == SpreadStatus::kBeyondMethod) {
    region.state = RegionState::kBeyond;
    const std::optional<SpreadAt>& last = profile.lastDefined();
    const std::optional<RegionAxesDeg> axes =
        last ? regionAxes(model, *last) : regionAxes(model, SpreadAt{});
    if (axes) {
      region.has_axes = true;
      region.axes = halfAxesRad(axes->vertical_deg, axes->horizontal_deg);
    }
    return region;
  }
  const std::optional<RegionAxesDeg> axes = regionAxes(model, spread);
  if (!axes) {
    region.state = RegionState::kUnknown;
    return region;
  }
  region.state = RegionState::kGlare;
  region.has_axes = true;
  region.axes = halfAxesRad(axes->vertical_deg, axes->horizontal_deg);
  return region;
}

ArrayStep arrayStep(const Context& context, std::size_t a, Vec3 sun) {
  ArrayStep step;
  const ArrayPolygon& array = context.scene.arrays[a];
  step.cos_alpha = dot(array.normal, sun);
  if (step.cos_alpha <= 0) return step;
  step.lit = true;
  step.sun = sun;
  step.c = sun - 2 * step.cos_alpha * array.normal;
  return step;
}

void resolve(const Context& context, std::size_t a, ArrayStep& step) {
  if (step.resolved) return;
  step.resolved = true;
  const ArrayPolygon& array = context.scene.arrays[a];
  step.alpha_deg = degrees(std::acos(std::min(step.cos_alpha, 1.0)));
  step.frame = regionFrame(array.normal, step.sun, array.up_slope);
  const ProfileTable& profile = *context.profiles[a];
  const SpreadAt spread = profile.at(step.alpha_deg);
  const std::size_t models = std::min(context.options.models.size(), kMaxModels);
  for (std::size_t m = 0; m < models; ++m)
    step.regions[m] = modelRegion(context.options.models[m], spread, profile);
}

// Per model: some glaring α with no spread for it. A spread is the same over [k, k + 1) (it
// comes from rows k and k + 1), so each whole degree the glare ranges touch is checked once.
UnknownSpreads unknownSpreads(const std::vector<GlareModel>& models, const ProfileTable& profile) {
  UnknownSpreads unknown{};
  for (int k = 0; k <= pipeline::kProfileAlphaMaxDeg; ++k) {
    const double to = std::min(k + 1.0, static_cast<double>(pipeline::kProfileAlphaMaxDeg));
    if (!profile.glaresWithin(k, to)) continue;
    const SpreadAt spread = profile.spreadAt(std::min(k + 0.5, to));
    for (std::size_t m = 0; m < std::min(models.size(), kMaxModels); ++m)
      unknown[m] = unknown[m] || !regionAxes(models[m], spread);
  }
  return unknown;
}

// The part of the array a receptor's field of view holds: the horizontal directions within
// field_of_view_deg of one of its azimuths. Each azimuth's wedge is the intersection (half-angle
// ≤ 90°) or the union (> 90°) of two vertical half-spaces through the receptor, whose traces on
// the array's plane are half-planes.
PlaneRegion fieldOfViewRegion(const ArrayPolygon& array, const Observer& observer) {
  const double extent = array.radius_m * 1.01 + 1e-3;
  std::vector<PlaneRing> wedges;
  for (const double azimuth_deg : observer.view_azimuths_deg) {
    // Compass azimuth φ to the mathematical angle θ = 90° − φ in (east, north).
    const double theta = radians(90 - azimuth_deg), half = radians(observer.field_of_view_deg);
    std::array<PlaneRegion, 2> sides;
    for (int k = 0; k < 2; ++k) {
      const double normal_angle =
          k == 0 ? theta + half - std::numbers::pi / 2 : theta - half + std::numbers::pi / 2;
      const Vec3 m{std::cos(normal_angle), std::sin(normal_angle), 0};
      sides[static_cast<std::size_t>(k)] =
          halfPlane(dot(m, array.axis_u), dot(m, array.axis_w),
                    dot(m, array.centroid_m - observer.position_m), extent);
    }
    const PlaneRegion wedge =
        observer.field_of_view_deg <= 90 ? intersect(sides[0], sides[1]) : unite([&] {
          std::vector<PlaneRing> rings = sides[0].rings;
          rings.insert(rings.end(), sides[1].rings.begin(), sides[1].rings.end());
          return rings;
        }());
    wedges.insert(wedges.end(), wedge.rings.begin(), wedge.rings.end());
  }
  return intersect(arrayRegion(array), unite(wedges));
}

// The part of the array an observer can see glare from (Pair::view).
Pair makePair(const Scene& scene, const ArrayPolygon& array, const Observer& observer) {
  Pair pair;
  if (observer.view_azimuths_deg.empty() && scene.obstructions.empty()) {
    pair.view = viewFrom(array, observer.position_m);
    return pair;
  }
  PlaneRegion region = observer.view_azimuths_deg.empty() || observer.field_of_view_deg >= 180
                           ? arrayRegion(array)
                           : fieldOfViewRegion(array, observer);
  if (seesFront(array, observer.position_m))
    region = subtract(region, hiddenRings(array, scene.obstructions, observer.position_m));
  pair.clipped = true;
  pair.view = viewFrom(array, observer.position_m, std::move(region));
  return pair;
}

// Whether the region reaches the part of the array the observer sees and the sun lights, and q
// there when it does. The sun's shadows are found only for a region that reaches the part seen
// (q over a part is never below q over the whole).
std::optional<double> regionMeets(const Context& context, std::size_t a, ArrayStep& step,
                                  const ModelRegion& region, const Pair& pair) {
  const ArrayPolygon& array = context.scene.arrays[a];
  const double q = minNormalisedDistance(step.frame, region.axes, array, pair.view);
  if (q > 1) return std::nullopt;
  if (context.scene.obstructions.empty()) return q;
  if (!step.lit_resolved) {
    step.lit_resolved = true;
    step.lit_part =
        subtract(arrayRegion(array), sunShadowRings(array, context.scene.obstructions, step.sun));
  }
  const PolygonView lit_view =
      viewFrom(array, pair.view.observer_m, intersect(pair.view.region, step.lit_part));
  const double lit_q = minNormalisedDistance(step.frame, region.axes, array, lit_view);
  if (lit_q <= 1) return lit_q;
  return std::nullopt;
}

// Day `index` of the run, day first_day + index of the year.
Result<DayOutput> computeDay(const Context& context, int index,
                             std::vector<ObserverHazard>& observers) {
  const int day = context.first_day + index;
  const Scene& scene = context.scene;
  const HazardOptions& options = context.options;
  const int steps = context.steps_per_day;
  const std::size_t models = options.models.size();
  const auto step = std::chrono::microseconds(std::int64_t{options.step_s} * 1'000'000);
  const auto first_utc = context.year_start_utc + std::chrono::days(day) + step / 2;
  std::vector<sun::SunDirection> track;
  GLARECAM_ASSIGN(track, sun::solarTrack(first_utc, step, static_cast<std::size_t>(steps),
                                         scene.site.location));

  DayOutput output;
  output.tallies.resize(scene.observers.size());
  // open[o][m][a]: the event being built, if any.
  std::vector<std::vector<std::vector<std::optional<GlareEvent>>>> open(
      scene.observers.size(),
      std::vector<std::vector<std::optional<GlareEvent>>>(
          models, std::vector<std::optional<GlareEvent>>(scene.arrays.size())));
  auto close = [&](std::size_t o, std::size_t m, std::size_t a) {
    if (open[o][m][a]) {
      output.events.push_back(*open[o][m][a]);
      open[o][m][a].reset();
    }
  };
  auto closeObserver = [&](std::size_t o) {
    for (std::size_t m = 0; m < models; ++m)
      for (std::size_t a = 0; a < scene.arrays.size(); ++a) close(o, m, a);
  };

  std::vector<ArrayStep> array_steps(scene.arrays.size());
  const std::int64_t day_first_step = std::int64_t{day} * steps;
  for (int k = 0; k < steps; ++k) {
    const std::size_t cell = static_cast<std::size_t>(std::int64_t{index} * steps + k);
    const Vec3 sun{track[static_cast<std::size_t>(k)].east,
                   track[static_cast<std::size_t>(k)].north, track[static_cast<std::size_t>(k)].up};
    if (sun.z <= 0) {  // apparent elevation ≤ 0°
      for (std::size_t o = 0; o < scene.observers.size(); ++o) {
        observers[o].steps[cell] = kSunDownBit;
        closeObserver(o);
      }
      continue;
    }
    for (std::size_t a = 0; a < scene.arrays.size(); ++a)
      array_steps[a] = arrayStep(context, a, sun);
    const double local_h = (k + 0.5) * options.step_s / 3600.0;
    for (std::size_t o = 0; o < scene.observers.size(); ++o) {
      const Observer& observer = scene.observers[o];
      if (local_h < observer.from_h || local_h >= observer.to_h) {
        observers[o].steps[cell] = kOutsideHoursBit;
        closeObserver(o);
        continue;
      }
      std::uint8_t mask = 0;
      for (std::size_t m = 0; m < models; ++m) {
        bool glare = false, beyond = false, unknown = false;
        for (std::size_t a = 0; a < scene.arrays.size(); ++a) {
          ArrayStep& array_step = array_steps[a];
          const Pair& pair = context.pairs[o][a];
          std::optional<double> q;
          // The cheap rejection first: c too far from the array for any region of the profile.
          const bool reachable =
              array_step.lit && pair.view.in_front &&
              (dot(array_step.c, pair.view.centre_direction) >= pair.reject_cos[m] ||
               context.unknown_spreads[a][m]);
          if (reachable) {
            resolve(context, a, array_step);
            const ModelRegion& region = array_step.regions[m];
            switch (region.state) {
              case RegionState::kNone:
                break;
              case RegionState::kUnknown:
                unknown = true;
                break;
              case RegionState::kBeyond:
                beyond = beyond || !region.has_axes ||
                         regionMeets(context, a, array_step, region, pair).has_value();
                break;
              case RegionState::kGlare:
                q = regionMeets(context, a, array_step, region, pair);
                break;
            }
          }
          if (!q) {
            close(o, m, a);
            continue;
          }
          glare = true;
          std::optional<double> luminance;
          const LuminancesAt luminances = context.profiles[a]->luminancesAt(array_step.alpha_deg);
          if (luminances.lmax_cd_m2 && luminances.limit_cd_m2) {
            luminance = *luminances.lmax_cd_m2 *
                        std::pow(*luminances.limit_cd_m2 / *luminances.lmax_cd_m2, *q);
          }
          std::optional<GlareEvent>& event = open[o][m][a];
          if (!event) {
            event = GlareEvent{.observer = o,
                               .array = a,
                               .model = m,
                               .first_step = day_first_step + k,
                               .end_step = day_first_step + k + 1,
                               .alpha_min_deg = array_step.alpha_deg,
                               .alpha_max_deg = array_step.alpha_deg,
                               .peak_luminance_cd_m2 = luminance};
          } else {
            event->end_step = day_first_step + k + 1;
            event->alpha_min_deg = std::min(event->alpha_min_deg, array_step.alpha_deg);
            event->alpha_max_deg = std::max(event->alpha_max_deg, array_step.alpha_deg);
            if (luminance &&
                (!event->peak_luminance_cd_m2 || *luminance > *event->peak_luminance_cd_m2))
              event->peak_luminance_cd_m2 = luminance;
          }
        }
        Tally& tally = output.tallies[o][m];
        if (glare) {
          mask = static_cast<std::uint8_t>(mask | (1u << m));
          ++tally.glare_steps;
          if (!tally.first_last) tally.first_last = std::pair{k, k};
          tally.first_last->second = k;
        }
        tally.beyond += beyond ? 1 : 0;
        tally.unknown += unknown ? 1 : 0;
      }
      observers[o].steps[cell] = mask;
    }
  }
  for (std::size_t o = 0; o < scene.observers.size(); ++o) closeObserver(o);
  return output;
}

// Joins events that a day boundary split (one ends where the next, of the same observer, model
// and array, begins).
std::vector<GlareEvent> joinEvents(std::vector<GlareEvent> events) {
  std::sort(events.begin(), events.end(), [](const GlareEvent& x, const GlareEvent& y) {
    return std::tie(x.observer, x.model, x.array, x.first_step) <
           std::tie(y.observer, y.model, y.array, y.first_step);
  });
  std::vector<GlareEvent> joined;
  for (const GlareEvent& event : events) {
    if (!joined.empty()) {
      GlareEvent& last = joined.back();
      if (last.observer == event.observer && last.model == event.model &&
          last.array == event.array && last.end_step == event.first_step) {
        last.end_step = event.end_step;
        last.alpha_min_deg = std::min(last.alpha_min_deg, event.alpha_min_deg);
        last.alpha_max_deg = std::max(last.alpha_max_deg, event.alpha_max_deg);
        if (event.peak_luminance_cd_m2 &&
            (!last.peak_luminance_cd_m2 ||
             *event.peak_luminance_cd_m2 > *last.peak_luminance_cd_m2))
          last.peak_luminance_cd_m2 = event.peak_luminance_cd_m2;
        continue;
      }
    }
    joined.push_back(event);
  }
  return joined;
}

}  // namespace

std::optional<std::string> HazardOptions::yearWarning() const {
  if (year >= kLikelyFirstYear && year <= kLikelyLastYear) return std::nullopt;
  constexpr int kCentury = 2000;  // "27": a two-digit year of this century
  const std::string typo = year >= 0 && year < 100
                               ? " (did you mean " + std::to_string(kCentury + year) + "?)"
                               : std::string();
  return "--year " + std::to_string(year) + " is outside " + std::to_string(kLikelyFirstYear) +
         "\u2013" + std::to_string(kLikelyLastYear) + typo + "; computed for the year " +
         std::to_string(year) + " as given";
}

Status HazardOptions::validate() const {
  if (year < kFirstYear || year > kLastYear) {
    return badInput("--year " + std::to_string(year) + " is outside the sun's range [" +
                    std::to_string(kFirstYear) + ", " + std::to_string(kLastYear) + "]");
  }
  if (step_s < 1 || step_s > kMaxStepS || kSecondsPerDay % step_s != 0) {
    return badInput("--step-s " + std::to_string(step_s) +
                    " is not a whole number of seconds in [1, 3600] that divides a day");
  }
  if (threads > kMaxThreads) {
    return badInput("--threads " + std::to_string(threads) + " is more than " +
                    std::to_string(kMaxThreads));
  }
  if (models.empty()) return badInput("--models: no model given");
  if (models.size() > kMaxModels)
    return badInput("--models: at most " + std::to_string(kMaxModels) + " models at once");
  if (first_day < 0 || day_count < 0 || first_day + day_count > daysInYear(year) ||
      first_day >= daysInYear(year))
    return badInput("hazard: days " + std::to_string(first_day) + " + " +
                    std::to_string(day_count) + " are outside the year " + std::to_string(year));
  return {};
}

Result<HazardResult> computeHazard(const Scene& scene,
                                   const std::vector<const ProfileTable*>& profiles,
                                   const HazardOptions& options, const HazardProgress& progress) {
  GLARECAM_CHECK(options.validate());
  if (profiles.size() != scene.arrays.size() ||
      std::any_of(profiles.begin(), profiles.end(), [](const ProfileTable* p) { return !p; }))
    return badInput("hazard: every array needs a glare profile");
  GLARECAM_CHECK(sun::validate(scene.site.location));

  HazardResult result;
  result.year = options.year;
  result.first_day = options.first_day;
  result.days =
      options.day_count > 0 ? options.day_count : daysInYear(options.year) - options.first_day;
  result.step_s = options.step_s;
  result.steps_per_day = kSecondsPerDay / options.step_s;

  const auto local_midnight = std::chrono::sys_days{std::chrono::year{options.year} / 1 / 1};
  Context context{
      .scene = scene,
      .profiles = profiles,
      .options = options,
      .pairs = {},
      .unknown_spreads = {},
      .steps_per_day = result.steps_per_day,
      .first_day = result.first_day,
      .year_start_utc = std::chrono::time_point_cast<std::chrono::microseconds>(local_midnight) -
                        std::chrono::microseconds(std::llround(scene.site.utc_offset_h * 3600e6))};
  for (std::size_t a = 0; a < scene.arrays.size(); ++a)
    context.unknown_spreads.push_back(unknownSpreads(options.models, *profiles[a]));
  for (const Observer& observer : scene.observers) {
    std::vector<Pair> row;
    for (std::size_t a = 0; a < scene.arrays.size(); ++a) {
      Pair pair = makePair(scene, scene.arrays[a], observer);
      for (std::size_t m = 0; m < options.models.size(); ++m) {
        const double reach = radians(maxFullAxisDeg(options.models[m], *profiles[a]) / 2) +
                             pair.view.angular_radius_rad;
        pair.reject_cos[m] = reach >= std::numbers::pi ? kNeverReject : std::cos(reach);
      }
      row.push_back(std::move(pair));
    }
    context.pairs.push_back(std::move(row));
  }

  result.observers.resize(scene.observers.size());
  for (ObserverHazard& observer : result.observers) {
    observer.steps.assign(static_cast<std::size_t>(result.days) * result.steps_per_day, 0);
    observer.models.resize(options.models.size());
  }
  std::vector<DayOutput> days(static_cast<std::size_t>(result.days));
  std::vector<std::optional<Error>> errors(static_cast<std::size_t>(result.days));
  const unsigned threads = options.threads == 0 ? availableThreads() : options.threads;
  const int chunk = static_cast<int>(std::min(threads, kMaxThreads)) * kDaysPerChunkPerThread;
  for (int first = 0; first < result.days; first += chunk) {
    const int count = std::min(chunk, result.days - first);
    parallelRows(count, threads, [&](int begin, int end) {
      for (int i = begin; i < end; ++i) {
        const int day = first + i;
        Result<DayOutput> output = computeDay(context, day, result.observers);
        if (output)
          days[static_cast<std::size_t>(day)] = std::move(*output);
        else
          errors[static_cast<std::size_t>(day)] = output.error();
      }
    });
    for (int day = first; day < first + count; ++day) {
      if (errors[static_cast<std::size_t>(day)])
        return std::unexpected(*errors[static_cast<std::size_t>(day)]);
    }
    if (progress) progress(first + count, result.days);
  }

  const double minutes_per_step = options.step_s / 60.0;
  std::vector<GlareEvent> events;
  for (std::size_t o = 0; o < scene.observers.size(); ++o) {
    for (std::size_t m = 0; m < options.models.size(); ++m) {
      ModelSummary& summary = result.observers[o].models[m];
      summary.minutes_per_day.assign(static_cast<std::size_t>(result.days), 0.0);
      summary.first_last_step.assign(static_cast<std::size_t>(result.days), std::nullopt);
      std::int64_t year_steps = 0;
      for (int day = 0; day < result.days; ++day) {
        const Tally& tally = days[static_cast<std::size_t>(day)].tallies[o][m];
        summary.minutes_per_day[static_cast<std::size_t>(day)] =
            tally.glare_steps * minutes_per_step;
        summary.first_last_step[static_cast<std::size_t>(day)] = tally.first_last;
        year_steps += tally.glare_steps;
        summary.days_with_glare += tally.glare_steps > 0 ? 1 : 0;
        summary.max_minutes_per_day =
            std::max(summary.max_minutes_per_day, tally.glare_steps * minutes_per_step);
        summary.steps_beyond_method += tally.beyond;
        summary.steps_unknown_spread += tally.unknown;
      }
      summary.minutes_per_year = static_cast<double>(year_steps) * minutes_per_step;
      summary.hours_per_year = summary.minutes_per_year / 60.0;
      for (const Criterion& criterion : options.criteria)
        summary.verdicts.push_back(
            assess(criterion, summary.max_minutes_per_day, summary.hours_per_year));
    }
  }
  for (DayOutput& day : days) events.insert(events.end(), day.events.begin(), day.events.end());
  result.events = joinEvents(std::move(events));
  return result;
}

}  // namespace glarecam::hazard
