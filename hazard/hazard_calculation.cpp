#include "hazard/hazard_calculation.h"

#include <fmt/format.h>

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
#include "hazard/candidate_pairs.h"
#include "hazard/glare_region.h"
#include "hazard/obstruction.h"
#include "hazard/plane_region.h"
#include "pipeline/glare_ellipse.h"
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
  // Of the region, when known without integrating it (the ladder's contour, a circular cone);
  // else found from the axes when a step glares.
  std::optional<double> solid_angle_sr;
  // The luminance seen at the lobe's peak and at the region's edge: L = peak (edge / peak)^q.
  std::optional<double> peak_cd_m2, edge_cd_m2;
};

// One array in one step: shared by every observer. What the cheap rejection needs (lit, c) is
// set for every array; the rest (α, the frame, each model's region) when a pair first needs it.
struct ArrayStep {
  bool lit = false;  // the sun in front of it
  Vec3 sun;
  double source_lx = 0;  // E(t), when the sun is not the reference
  double cos_alpha = 0;
  Vec3 c;  // the sun's mirror image
  bool resolved = false;
  double alpha_deg = 0;
  RegionFrame frame;
  std::array<ModelRegion, kMaxModels> regions{};
  // With obstructions: the part of the array the sun lights, found when a pair first needs it.
  bool lit_resolved = false;
  bool shaded = false;  // some shadow falls on the array (else lit_part is all of it, unused)
  PlaneRegion lit_part;
};

// One observer and one array: what never changes over the year. `view` is the part of the
// array the observer can see glare from: all of it, or what its field of view and the
// obstructions leave.
struct Pair {
  std::size_t array = 0;  // index into scene.arrays
  PolygonView view;
  bool clipped = false;                         // view is less than the whole array
  double solid_angle_sr = 0;                    // of the part seen, from the observer
  std::array<double, kMaxModels> reject_cos{};  // c·d below this: the region cannot reach it
  // The day-level bound (candidate_pairs.h): the largest reach over the models (π: never
  // rejected) and the angle from the mirrored pole to the array's centre.
  double reach_rad = std::numbers::pi;
  double mirrored_pole_rad = 0;
};

// An obstruction that can shade an array, and the sine of the highest sun that it can.
struct Caster {
  double max_sin_elevation = 0;
  const Obstruction* obstruction = nullptr;
  // Seen from the array's centroid, horizontally: the obstruction's direction (radians from
  // east, counter-clockwise) and the half-width within which a sun's azimuth must lie for a
  // shadow ray from some point of the array to meet its bounding sphere (π: any).
  double direction_rad = 0, half_width_rad = std::numbers::pi;
};

Caster makeCaster(const Obstruction& obstruction, const ArrayPolygon& array,
                  double max_elevation_rad) {
  Caster caster{.max_sin_elevation = std::sin(max_elevation_rad), .obstruction = &obstruction};
  const double dx = obstruction.centre_m.x - array.centroid_m.x,
               dy = obstruction.centre_m.y - array.centroid_m.y;
  const double distance_m = std::hypot(dx, dy), reach_m = obstruction.radius_m + array.radius_m;
  caster.direction_rad = std::atan2(dy, dx);
  if (distance_m > reach_m) caster.half_width_rad = std::asin(reach_m / distance_m);
  return caster;
}

// Whether the sun (horizontal direction `sun_rad`, radians from east) stands where the caster
// can throw a shadow on the array.
bool towardSun(const Caster& caster, double sun_rad) {
  if (caster.half_width_rad >= std::numbers::pi) return true;
  const double off = std::remainder(sun_rad - caster.direction_rad, 2 * std::numbers::pi);
  return std::abs(off) <= caster.half_width_rad;
}

// Per array and model: whether some glaring α has no spread there (then every lit step must be
// resolved to count it, not only those the rejection lets through).
using UnknownSpreads = std::array<bool, kMaxModels>;

struct Tally {
  int glare_steps = 0;
  std::array<int, 3> ocular_steps{};  // per OcularClass: the worst of the step's arrays
  int unclassified_steps = 0;
  std::optional<std::pair<int, int>> first_last;
  std::int64_t beyond = 0, unknown = 0;
};

struct DayOutput {
  std::vector<std::array<Tally, kMaxModels>> tallies;  // per observer, per model
  std::vector<int> active_pairs;                       // per observer: the bound let these through
  std::vector<GlareEvent> events;
};

struct Context {
  const Scene& scene;
  const std::vector<const ProfileTable*>& profiles;
  const HazardOptions& options;
  std::vector<std::vector<Pair>> pairs;         // [observer][candidate], by array
  std::vector<std::vector<Caster>> casters;     // [array], highest sun first
  Vec3 pole;                                    // the celestial pole, unit, ENU
  std::vector<UnknownSpreads> unknown_spreads;  // [array]
  int steps_per_day = 0;
  int first_day = 0;
  std::vector<double> reference_lx{};  // per array: E_ref of its profile (brightness only)
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

// The luminances seen at the region's peak and edge, under the reference sun.
void addReferenceLuminances(ModelRegion& region, const ProfileTable& profile, double alpha_deg) {
  if (!region.has_axes) return;
  const LuminancesAt luminances = profile.luminancesAt(alpha_deg);
  region.peak_cd_m2 = luminances.lmax_cd_m2;
  region.edge_cd_m2 = luminances.limit_cd_m2;
}

// The model's region at α under a source of illuminance E (sun_brightness.h): the referred
// contour at L_limit(α) · E_ref / E; a constant cone wherever that contour exists.
ModelRegion brightRegion(const GlareModel& model, const ProfileTable& profile, double alpha_deg,
                         double source_lx, double reference_lx) {
  ModelRegion region;
  if (!(source_lx > 0)) return region;  // no direct sun: no glare, nor any beyond the method
  if (alpha_deg > pipeline::kProfileAlphaMaxDeg) {
    region = modelRegion(model, profile.at(alpha_deg), profile);  // beyond the method
    return region;
  }
  const LuminancesAt luminances = profile.luminancesAt(alpha_deg);
  if (!luminances.limit_cd_m2 || !luminances.lmax_cd_m2) {
    region.state = RegionState::kUnknown;
    return region;
  }
  const double ratio = source_lx / reference_lx;
  const LadderRegion ladder = profile.regionAtLevel(alpha_deg, *luminances.limit_cd_m2 / ratio);
  switch (ladder.status) {
    case LadderRegion::Status::kNoGlare:
      return region;
    case LadderRegion::Status::kUnknown:
      region.state = RegionState::kUnknown;
      return region;
    case LadderRegion::Status::kRegion:
      break;
  }
  std::optional<RegionAxesDeg> axes;
  switch (model.kind) {
    case ModelKind::kEllipse:
      axes = RegionAxesDeg{ladder.vertical_deg, ladder.horizontal_deg};
      break;
    case ModelKind::kCircle: {
      // The circular cone of the contour's solid angle: Ω = 2π (1 − cos(β/2)).
      const double beta_deg = degrees(
          2 * std::acos(std::clamp(1 - ladder.solid_angle_sr / (2 * std::numbers::pi), -1.0, 1.0)));
      axes = RegionAxesDeg{beta_deg, beta_deg};
      break;
    }
    case ModelKind::kCone:
      axes = regionAxes(model, SpreadAt{});
      break;
  }
  // A region shrunk to nothing at the peak is no region.
  if (!axes || !(axes->vertical_deg >= kMinAxisDeg) || !(axes->horizontal_deg >= kMinAxisDeg))
    return region;
  region.state = RegionState::kGlare;
  region.has_axes = true;
  region.axes = halfAxesRad(axes->vertical_deg, axes->horizontal_deg);
  if (model.kind != ModelKind::kCone) region.solid_angle_sr = ladder.solid_angle_sr;
  region.peak_cd_m2 = *luminances.lmax_cd_m2 * ratio;
  region.edge_cd_m2 = *luminances.limit_cd_m2;
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
  const std::size_t models = std::min(context.options.models.size(), kMaxModels);
  if (context.options.sun.kind != SunKind::kReference) {
    for (std::size_t m = 0; m < models; ++m)
      step.regions[m] = brightRegion(context.options.models[m], profile, step.alpha_deg,
                                     step.source_lx, context.reference_lx[a]);
    return;
  }
  const SpreadAt spread = profile.at(step.alpha_deg);
  for (std::size_t m = 0; m < models; ++m) {
    step.regions[m] = modelRegion(context.options.models[m], spread, profile);
    addReferenceLuminances(step.regions[m], profile, step.alpha_deg);
  }
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

// The solid angle of `area_m2` of the array's plane about its centroid seen from a point: A cos θ
// / d² (the array small against its distance; ocular hazard only).
double solidAngleSeenSr(const ArrayPolygon& array, Vec3 point_m, double area_m2) {
  const Vec3 d = point_m - array.centroid_m;
  const double distance_m = norm(d);
  if (!(distance_m > 0)) return 0;
  return area_m2 * std::max(0.0, dot(array.normal, d)) / (distance_m * distance_m * distance_m);
}

// The obstructions that can stand between a point and the array: those within the box around
// both (every sight line lies in their convex hull).
std::vector<const Obstruction*> obstructionsBetween(const Scene& scene, const ArrayPolygon& array,
                                                    Vec3 point_m) {
  const Vec3 reach{array.radius_m, array.radius_m, array.radius_m};
  const Vec3 a_lo = array.centroid_m - reach, a_hi = array.centroid_m + reach;
  const Vec3 lo{std::min(a_lo.x, point_m.x), std::min(a_lo.y, point_m.y),
                std::min(a_lo.z, point_m.z)};
  const Vec3 hi{std::max(a_hi.x, point_m.x), std::max(a_hi.y, point_m.y),
                std::max(a_hi.z, point_m.z)};
  std::vector<const Obstruction*> between;
  for (const Obstruction& obstruction : scene.obstructions)
    if (mayMeetBox(obstruction, lo, hi)) between.push_back(&obstruction);
  return between;
}

// The part of the array an observer can see glare from (Pair::view).
Pair makePair(const Scene& scene, const ArrayPolygon& array, const Observer& observer) {
  Pair pair;
  const std::vector<const Obstruction*> between =
      obstructionsBetween(scene, array, observer.position_m);
  if (observer.view_azimuths_deg.empty() && between.empty()) {
    pair.view = viewFrom(array, observer.position_m);
    pair.solid_angle_sr = solidAngleSeenSr(array, observer.position_m, array.area_m2);
    return pair;
  }
  PlaneRegion region = observer.view_azimuths_deg.empty() || observer.field_of_view_deg >= 180
                           ? arrayRegion(array)
                           : fieldOfViewRegion(array, observer);
  if (seesFront(array, observer.position_m))
    region = subtract(region, hiddenRings(array, between, observer.position_m));
  pair.clipped = true;
  pair.view = viewFrom(array, observer.position_m, std::move(region));
  pair.solid_angle_sr = solidAngleSeenSr(array, observer.position_m, areaM2(pair.view.region));
  return pair;
}

// Whether an obstruction stands between a point and the sun: the ray toward the sun meets one of
// the faces of those that can shade from a sun this high.
bool sunBlocked(const std::vector<Caster>& casters, Vec3 point_m, Vec3 sun) {
  const double sun_rad = std::atan2(sun.y, sun.x);
  for (const Caster& caster : casters) {
    if (caster.max_sin_elevation < sun.z) break;
    if (!towardSun(caster, sun_rad)) continue;
    for (const ArrayPolygon& face : caster.obstruction->faces) {
      const double along = dot(face.normal, sun);
      if (along == 0) continue;
      const double t = dot(face.centroid_m - point_m, face.normal) / along;
      if (t > kSlabMarginM && containsPlanePoint(face, point_m + t * sun)) return true;
    }
  }
  return false;
}

// Whether the region reaches the part of the array the observer sees and the sun lights, and q
// there when it does. The sun's shadows are found only for a region that reaches the part seen
// (q over a part is never below q over the whole).
std::optional<double> regionMeets(const Context& context, std::size_t a, ArrayStep& step,
                                  const ModelRegion& region, const Pair& pair,
                                  Vec3* glare_direction = nullptr) {
  const ArrayPolygon& array = context.scene.arrays[a];
  Vec3 direction;
  const double q = minNormalisedDistance(step.frame, region.axes, array, pair.view, &direction);
  if (q > 1) return std::nullopt;
  if (glare_direction) *glare_direction = direction;
  const std::vector<Caster>& casters = context.casters[a];
  if (casters.empty() || casters.front().max_sin_elevation < step.sun.z) return q;
  // Where q is attained, seen along `direction`: when the sun lights that point, the minimum over
  // the lit part is the same q (the lit part seen is within the part seen), and no shadow need
  // be clipped.
  const double toward = dot(direction, array.normal);
  if (toward < 0) {
    const Vec3 seen_m =
        pair.view.observer_m +
        (dot(array.centroid_m - pair.view.observer_m, array.normal) / toward) * direction;
    if (!sunBlocked(casters, seen_m, step.sun)) return q;
  }
  if (!step.lit_resolved) {
    step.lit_resolved = true;
    // Only what can shade the array from this high a sun (maxShadingElevationRad).
    std::vector<const Obstruction*> shading;
    const double sun_rad = std::atan2(step.sun.y, step.sun.x);
    for (const Caster& caster : casters) {
      if (caster.max_sin_elevation < step.sun.z) break;
      if (towardSun(caster, sun_rad)) shading.push_back(caster.obstruction);
    }
    const std::vector<PlaneRing> shadows = sunShadowRings(array, shading, step.sun);
    step.shaded = !shadows.empty();
    if (step.shaded) step.lit_part = subtract(arrayRegion(array), shadows);
  }
  if (!step.shaded) return q;  // the whole array is lit: the part seen is the part that glares
  const PolygonView lit_view =
      viewFrom(array, pair.view.observer_m, intersect(pair.view.region, step.lit_part));
  const double lit_q =
      minNormalisedDistance(step.frame, region.axes, array, lit_view, glare_direction);
  if (lit_q <= 1) return lit_q;
  return std::nullopt;
}

// The solid angle of an ellipse of half-axes a, b (radians) in the azimuthal-equidistant plane:
// Ω = ∫ (1 − cos R(ψ)) dψ with R the ellipse's radius in direction ψ. Its series, with
// ∫ R² dψ = 2π ab and ∫ R⁴ dψ = π ab (a² + b²), is Ω = π ab (1 − (a² + b²)/24 + …); the next
// term is below 5e-6 of Ω for half-axes under 0.2 rad (11.5°). Wider regions take the integral
// (pipeline::ellipseSolidAngleSr, 2 × its cost: per glaring step, not per step).
constexpr double kSolidAngleSeriesLimitRad = 0.2;
double regionSolidAngleSr(const RegionHalfAxes& axes) {
  const double a = axes.vertical_rad, b = axes.horizontal_rad;
  if (std::max(a, b) < kSolidAngleSeriesLimitRad)
    return std::numbers::pi * a * b * (1 - (a * a + b * b) / 24);
  return pipeline::ellipseSolidAngleSr(degrees(std::max(a, b)), degrees(std::min(a, b)));
}

double compassAzimuthDeg(Vec3 d) {
  const double azimuth_deg = degrees(std::atan2(d.x, d.y));
  return azimuth_deg < 0 ? azimuth_deg + 360 : azimuth_deg;
}
double elevationDeg(Vec3 d) { return degrees(std::asin(std::clamp(d.z, -1.0, 1.0))); }

// What a glaring step looks like from the receptor (GlareSighting): where, how bright, and its
// ocular hazard. The spot the eye sees is the region where it is smaller than the part of the
// array seen (over its solid angle, at its mean luminance, the logarithmic mean of the peak and
// the edge for the log-quadratic lobe of hazard.md step 7, but never brighter than the brightest
// point seen), else the array (the luminance at the point seen, over the array's solid angle).
GlareSighting sighting(const Context& context, std::size_t a, const ArrayStep& step,
                       const ModelRegion& region, const Pair& pair, double q, Vec3 direction,
                       std::int64_t step_index) {
  const ArrayPolygon& array = context.scene.arrays[a];
  GlareSighting seen;
  seen.step = step_index;
  seen.alpha_deg = step.alpha_deg;
  seen.glare_azimuth_deg = compassAzimuthDeg(direction);
  seen.glare_elevation_deg = elevationDeg(direction);
  const double toward = dot(direction, array.normal);
  seen.distance_m = toward < 0 ? dot(array.centroid_m - pair.view.observer_m, array.normal) / toward
                               : norm(array.centroid_m - pair.view.observer_m);
  seen.sun_azimuth_deg = compassAzimuthDeg(step.sun);
  seen.sun_elevation_deg = elevationDeg(step.sun);
  if (context.options.sun.kind != SunKind::kReference) seen.source_illuminance_lx = step.source_lx;
  if (!region.peak_cd_m2 || !region.edge_cd_m2 || !(*region.peak_cd_m2 > 0) ||
      !(*region.edge_cd_m2 > 0))
    return seen;
  const double peak = *region.peak_cd_m2, edge = *region.edge_cd_m2;
  seen.luminance_cd_m2 = peak * std::pow(edge / peak, q);
  // The spot is no larger than the region or the part of the array seen, and no brighter than
  // the brightest point seen (L at q): a region that only grazes the array shows its edge's
  // luminance, not its mean.
  double spot_cd_m2 = *seen.luminance_cd_m2, spot_sr = pair.solid_angle_sr;
  const double region_sr = region.solid_angle_sr.value_or(regionSolidAngleSr(region.axes));
  if (region_sr > 0 && region_sr <= pair.solid_angle_sr) {
    spot_sr = region_sr;
    const double mean_cd_m2 =
        peak > edge * (1 + 1e-9) ? (peak - edge) / std::log(peak / edge) : peak;
    spot_cd_m2 = std::min(mean_cd_m2, *seen.luminance_cd_m2);
  }
  if (spot_sr > 0) {
    const Result<OcularExposure> exposure =
        ocularExposure(spot_cd_m2, std::min(spot_sr, 2 * std::numbers::pi), context.options.eye);
    if (exposure) seen.ocular = *exposure;
  }
  return seen;
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
  std::vector<Vec3> suns(track.size());
  PoleAngleRange pole_range{.min_rad = std::numbers::pi, .max_rad = -1};
  for (std::size_t k = 0; k < track.size(); ++k) {
    suns[k] = Vec3{track[k].east, track[k].north, track[k].up};
    if (suns[k].z <= 0) continue;
    const double theta = angleBetweenRad(suns[k], context.pole);
    pole_range.min_rad = std::min(pole_range.min_rad, theta);
    pole_range.max_rad = std::max(pole_range.max_rad, theta);
  }

  DayOutput output;
  output.tallies.resize(scene.observers.size());
  // Per observer, the candidates the day-level bound keeps (indices into context.pairs[o]).
  std::vector<std::vector<std::size_t>> active(scene.observers.size());
  std::vector<std::size_t> active_observers;
  for (std::size_t o = 0; o < scene.observers.size(); ++o) {
    const std::vector<Pair>& pairs = context.pairs[o];
    for (std::size_t i = 0; i < pairs.size(); ++i)
      if (dayMayReach(pairs[i].mirrored_pole_rad, pairs[i].reach_rad, pole_range))
        active[o].push_back(i);
    if (!active[o].empty()) active_observers.push_back(o);
  }
  output.active_pairs.resize(scene.observers.size());
  for (const std::size_t o : active_observers)
    output.active_pairs[o] = static_cast<int>(active[o].size());
  if (!options.keep_steps && active_observers.empty()) return output;

  // open[o][m][i]: the event being built for active candidate i, if any.
  std::vector<std::vector<std::vector<std::optional<GlareEvent>>>> open(scene.observers.size());
  for (const std::size_t o : active_observers)
    open[o].assign(models, std::vector<std::optional<GlareEvent>>(active[o].size()));
  auto close = [&](std::size_t o, std::size_t m, std::size_t i) {
    if (open[o][m][i]) {
      output.events.push_back(*open[o][m][i]);
      open[o][m][i].reset();
    }
  };
  auto closeObserver = [&](std::size_t o) {
    if (open[o].empty()) return;
    for (std::size_t m = 0; m < models; ++m)
      for (std::size_t i = 0; i < active[o].size(); ++i) close(o, m, i);
  };

  // Each array's step is made when a pair first needs it in the step.
  std::vector<ArrayStep> array_steps(scene.arrays.size());
  std::vector<int> array_step_made(scene.arrays.size(), -1);
  std::vector<std::size_t> all_observers;
  if (options.keep_steps) {
    all_observers.resize(scene.observers.size());
    for (std::size_t o = 0; o < all_observers.size(); ++o) all_observers[o] = o;
  }
  const std::vector<std::size_t>& visited = options.keep_steps ? all_observers : active_observers;
  const std::int64_t day_first_step = std::int64_t{day} * steps;
  for (int k = 0; k < steps; ++k) {
    const std::size_t cell = static_cast<std::size_t>(std::int64_t{index} * steps + k);
    const Vec3 sun = suns[static_cast<std::size_t>(k)];
    if (sun.z <= 0) {  // apparent elevation ≤ 0°
      for (const std::size_t o : visited) {
        if (options.keep_steps) observers[o].steps[cell] = kSunDownBit;
        closeObserver(o);
      }
      continue;
    }
    std::optional<double> source_lx;
    auto arrayStepAt = [&](std::size_t a) -> ArrayStep& {
      if (array_step_made[a] != k) {
        array_step_made[a] = k;
        if (!source_lx) {
          source_lx = options.sun.kind == SunKind::kReference
                          ? 0.0
                          : sourceIlluminanceLx(options.sun, first_utc + k * step,
                                                elevationDeg(sun), day + 1, scene.site);
        }
        array_steps[a] = arrayStep(context, a, sun);
        array_steps[a].source_lx = *source_lx;
      }
      return array_steps[a];
    };
    const double local_h = (k + 0.5) * options.step_s / 3600.0;
    for (const std::size_t o : visited) {
      const Observer& observer = scene.observers[o];
      if (local_h < observer.from_h || local_h >= observer.to_h) {
        if (options.keep_steps) observers[o].steps[cell] = kOutsideHoursBit;
        closeObserver(o);
        continue;
      }
      std::uint8_t mask = 0;
      for (std::size_t m = 0; m < models && !active[o].empty(); ++m) {
        bool glare = false, beyond = false, unknown = false;
        std::optional<OcularClass> step_class;
        bool unclassified = false;
        for (std::size_t i = 0; i < active[o].size(); ++i) {
          const Pair& pair = context.pairs[o][active[o][i]];
          const std::size_t a = pair.array;
          ArrayStep& array_step = arrayStepAt(a);
          std::optional<double> q;
          Vec3 direction;
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
                q = regionMeets(context, a, array_step, region, pair, &direction);
                break;
            }
          }
          if (!q) {
            close(o, m, i);
            continue;
          }
          glare = true;
          const GlareSighting seen = sighting(context, a, array_step, array_step.regions[m], pair,
                                              *q, direction, day_first_step + k);
          if (seen.ocular) {
            if (!step_class || seen.ocular->ocular_class > *step_class)
              step_class = seen.ocular->ocular_class;
          } else {
            unclassified = true;
          }
          const std::optional<double> luminance = seen.luminance_cd_m2;
          std::optional<GlareEvent>& event = open[o][m][i];
          if (!event) {
            event = GlareEvent{.observer = o,
                               .array = a,
                               .model = m,
                               .first_step = day_first_step + k,
                               .end_step = day_first_step + k + 1,
                               .alpha_min_deg = array_step.alpha_deg,
                               .alpha_max_deg = array_step.alpha_deg,
                               .peak_luminance_cd_m2 = luminance,
                               .peak = seen,
                               .worst_class = std::nullopt};
          } else {
            event->end_step = day_first_step + k + 1;
            event->alpha_min_deg = std::min(event->alpha_min_deg, array_step.alpha_deg);
            event->alpha_max_deg = std::max(event->alpha_max_deg, array_step.alpha_deg);
            if (luminance &&
                (!event->peak_luminance_cd_m2 || *luminance > *event->peak_luminance_cd_m2)) {
              event->peak_luminance_cd_m2 = luminance;
              event->peak = seen;
            }
          }
          if (seen.ocular &&
              (!event->worst_class || seen.ocular->ocular_class > *event->worst_class))
            event->worst_class = seen.ocular->ocular_class;
        }
        Tally& tally = output.tallies[o][m];
        if (glare) {
          mask = static_cast<std::uint8_t>(mask | (1u << m));
          if (step_class)
            ++tally.ocular_steps[static_cast<std::size_t>(*step_class)];
          else if (unclassified)
            ++tally.unclassified_steps;
          ++tally.glare_steps;
          if (!tally.first_last) tally.first_last = std::pair{k, k};
          tally.first_last->second = k;
        }
        tally.beyond += beyond ? 1 : 0;
        tally.unknown += unknown ? 1 : 0;
      }
      if (options.keep_steps) observers[o].steps[cell] = mask;
    }
  }
  for (const std::size_t o : active_observers) closeObserver(o);
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
             *event.peak_luminance_cd_m2 > *last.peak_luminance_cd_m2)) {
          last.peak_luminance_cd_m2 = event.peak_luminance_cd_m2;
          last.peak = event.peak;
        }
        if (event.worst_class && (!last.worst_class || *event.worst_class > *last.worst_class))
          last.worst_class = event.worst_class;
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
  if (!(max_distance_m > 0))
    return badInput(
        fmt::format("--max-distance {:g} is not a positive distance in metres", max_distance_m));
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
      .casters = {},
      .pole = {},
      .unknown_spreads = {},
      .steps_per_day = result.steps_per_day,
      .first_day = result.first_day,
      .year_start_utc = std::chrono::time_point_cast<std::chrono::microseconds>(local_midnight) -
                        std::chrono::microseconds(std::llround(scene.site.utc_offset_h * 3600e6))};
  for (std::size_t a = 0; a < scene.arrays.size(); ++a)
    context.unknown_spreads.push_back(unknownSpreads(options.models, *profiles[a]));
  // Under a sun of its own brightness each profile's contours scale with E_ref / E: every profile
  // must say what its luminances refer to, and carry the ladder. The largest region a profile can
  // make is its contour at the lowest level the year reaches, L_limit · E_ref / E_max.
  std::vector<double> max_axis_deg(scene.arrays.size(), 0);
  if (options.sun.kind != SunKind::kReference) {
    const double max_lx = maxSourceIlluminanceLx(options.sun, scene.site);
    for (std::size_t a = 0; a < scene.arrays.size(); ++a) {
      const ProfileTable& profile = *profiles[a];
      if (!profile.ladderReferenceLx()) {
        return badInput(
            (profile.path().empty() ? "the glare profile of " + profile.module()
                                    : profile.path().string()) +
            ": the profile has no contour ladder referred to a reference illuminance "
            "(glarecam.glare-profile/2 from a referred sweep), so the sun's brightness cannot "
            "scale it: make it again with `glarecam fit` from referred stacks, or give --sun "
            "reference");
      }
      context.reference_lx.push_back(*profile.ladderReferenceLx());
      for (int alpha = 0; alpha <= pipeline::kProfileAlphaMaxDeg; ++alpha) {
        const std::optional<double> limit = profile.luminancesAt(alpha).limit_cd_m2;
        if (!limit || !(max_lx > 0)) continue;
        // Between whole degrees a contour is linear in α, so its axes are largest at one.
        const LadderRegion largest =
            profile.regionAtLevel(alpha, *limit * context.reference_lx[a] / max_lx);
        if (largest.status == LadderRegion::Status::kRegion)
          max_axis_deg[a] =
              std::max({max_axis_deg[a], largest.vertical_deg, largest.horizontal_deg});
      }
      // The limit between whole degrees is log-linear: at most the larger of its ends' regions
      // differ by a degree's change; the ladder's lowest rung bounds them all.
      max_axis_deg[a] = std::min(std::max(max_axis_deg[a], profile.maxFullAxisDeg()),
                                 std::max(profile.maxLadderAxisDeg(), profile.maxFullAxisDeg()));
    }
  }
  context.pole = celestialPole(scene.site.location.latitude_deg);
  for (std::size_t a = 0; a < scene.arrays.size(); ++a) {
    std::vector<Caster> casters;
    for (const Obstruction& obstruction : scene.obstructions) {
      const double elevation_rad = maxShadingElevationRad(obstruction, scene.arrays[a]);
      if (elevation_rad > 0)
        casters.push_back(makeCaster(obstruction, scene.arrays[a], elevation_rad));
    }
    std::stable_sort(casters.begin(), casters.end(), [](const Caster& x, const Caster& y) {
      return x.max_sin_elevation > y.max_sin_elevation;
    });
    context.casters.push_back(std::move(casters));
  }
  const std::vector<std::vector<std::size_t>> candidates =
      candidateArrays(scene, options.max_distance_m);
  for (std::size_t o = 0; o < scene.observers.size(); ++o) {
    const Observer& observer = scene.observers[o];
    std::vector<Pair> row;
    for (const std::size_t a : candidates[o]) {
      Pair pair = makePair(scene, scene.arrays[a], observer);
      pair.array = a;
      pair.reach_rad = 0;
      for (std::size_t m = 0; m < options.models.size(); ++m) {
        const double full_axis_deg =
            options.sun.kind == SunKind::kReference || options.models[m].kind == ModelKind::kCone
                ? maxFullAxisDeg(options.models[m], *profiles[a])
                : max_axis_deg[a];
        const double reach = radians(full_axis_deg / 2) + pair.view.angular_radius_rad;
        pair.reject_cos[m] = reach >= std::numbers::pi ? kNeverReject : std::cos(reach);
        pair.reach_rad =
            context.unknown_spreads[a][m] ? std::numbers::pi : std::max(pair.reach_rad, reach);
      }
      pair.mirrored_pole_rad =
          mirroredPoleAngleRad(scene.arrays[a], context.pole, pair.view.centre_direction);
      row.push_back(std::move(pair));
    }
    context.pairs.push_back(std::move(row));
  }

  result.observers.resize(scene.observers.size());
  for (ObserverHazard& observer : result.observers) {
    if (options.keep_steps)
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
    result.observers[o].candidates = context.pairs[o].size();
    for (const DayOutput& day : days)
      result.observers[o].pair_days += day.active_pairs.empty() ? 0 : day.active_pairs[o];
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
        for (std::size_t c = 0; c < summary.ocular_minutes.size(); ++c)
          summary.ocular_minutes[c] += tally.ocular_steps[c] * minutes_per_step;
        summary.unclassified_minutes += tally.unclassified_steps * minutes_per_step;
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
