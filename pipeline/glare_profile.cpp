#include "pipeline/glare_profile.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <iterator>
#include <map>
#include <numbers>
#include <string>
#include <vector>

#include "core/json.h"
#include "pipeline/glare_ellipse.h"

namespace glarecam::pipeline {

namespace {

using nlohmann::json;

constexpr double kMradPerRad = 1000.0;

std::optional<double> axisAt(const AxisFit& axis, double alpha_deg) {
  if (!axis.logistic) return std::nullopt;
  const double axis_deg = axis.logistic->curve(alpha_deg);
  if (!isPhysicalAxisDeg(axis_deg)) return std::nullopt;  // an extrapolated fit run off
  return axis_deg;
}

// The method's verdict on the fits: the fitted Lmax at or above the limit (as in result.json).
bool glaresAt(const SweepFits& fits, const GlareLimit& limit, double alpha_deg) {
  const auto limit_cd_m2 = limit.at(alpha_deg);
  return limit_cd_m2 && fits.lmaxCdM2(alpha_deg) >= *limit_cd_m2;
}

bool outside(double alpha_deg, double lo_deg, double hi_deg) {
  return alpha_deg < lo_deg || alpha_deg > hi_deg;
}

}  // namespace

bool isPhysicalAxisDeg(double axis_deg) { return axis_deg > 0 && axis_deg <= kMaxFullAxisDeg; }

CircularBeamSpread circularBeamSpread(double vertical_deg, double horizontal_deg) {
  CircularBeamSpread beam;
  beam.solid_angle_sr = ellipseSolidAngleSr(vertical_deg / 2, horizontal_deg / 2);
  // A circular cone of half-angle θ spans 2π (1 - cos θ).
  const double half_angle_rad = std::acos(1.0 - beam.solid_angle_sr / (2 * std::numbers::pi));
  beam.beta_mrad = 2 * half_angle_rad * kMradPerRad;
  beam.slope_error_mrad = beam.beta_mrad / 2 - kSunHalfAngleMrad;
  return beam;
}

std::vector<ProfileRow> glareProfile(const SweepFits& fits, const GlareLimit& limit) {
  std::vector<ProfileRow> rows;
  for (int alpha = 0; alpha <= kProfileAlphaMaxDeg; alpha += kProfileStepDeg) {
    ProfileRow row;
    row.alpha_deg = alpha;
    row.lmax_cd_m2 = fits.lmaxCdM2(alpha);
    row.limit_cd_m2 = limit.at(alpha);
    row.glares = glaresAt(fits, limit, alpha);
    row.extrapolated = outside(alpha, fits.alpha_min_deg, fits.alpha_max_deg);
    if (row.glares) {
      row.vertical_deg = axisAt(fits.vertical, alpha);
      row.horizontal_deg = axisAt(fits.horizontal, alpha);
    }
    for (const AxisFit* axis : {&fits.vertical, &fits.horizontal}) {
      if (axis->logistic && row.glares)
        row.extrapolated |= outside(alpha, axis->alpha_min_deg, axis->alpha_max_deg);
    }
    if (row.vertical_deg && row.horizontal_deg && *row.vertical_deg > 0 && *row.horizontal_deg > 0)
      row.beam = circularBeamSpread(*row.vertical_deg, *row.horizontal_deg);
    rows.push_back(row);
  }
  return rows;
}

std::vector<AlphaRange> glareRanges(const SweepFits& fits, const GlareLimit& limit) {
  std::vector<AlphaRange> ranges;
  bool inside = false;
  const int steps = static_cast<int>(std::lround(kProfileAlphaMaxDeg / kGlareRangeResolutionDeg));
  for (int i = 0; i <= steps; ++i) {
    const double alpha = i / (1 / kGlareRangeResolutionDeg);  // 49.8, not 49.800000000000004
    const bool glares = glaresAt(fits, limit, alpha);
    if (glares && !inside) ranges.push_back({alpha, alpha});
    if (glares) ranges.back().to_deg = alpha;
    inside = glares;
  }
  return ranges;
}

namespace {

// An orientation in (-90°, 90°].
double wrapOrientationDeg(double deg) {
  while (deg > 90) deg -= 180;
  while (deg <= -90) deg += 180;
  return deg;
}

// a + (b - a) t for every number of a contour; the orientation the short way round (an axis'
// direction is modulo 180°). `level_cd_m2` and `kind` are the caller's.
ProfileContour lerpContour(const ProfileContour& a, const ProfileContour& b, double t) {
  const auto mix = [t](double x, double y) { return x + (y - x) * t; };
  ProfileContour c = a;
  c.vertical_deg = mix(a.vertical_deg, b.vertical_deg);
  c.horizontal_deg = mix(a.horizontal_deg, b.horizontal_deg);
  double to = b.orientation_deg;
  if (to - a.orientation_deg > 90) to -= 180;
  if (to - a.orientation_deg < -90) to += 180;
  c.orientation_deg = wrapOrientationDeg(mix(a.orientation_deg, to));
  c.solid_angle_sr = mix(a.solid_angle_sr, b.solid_angle_sr);
  c.vertical_uncertainty_deg = mix(a.vertical_uncertainty_deg, b.vertical_uncertainty_deg);
  c.horizontal_uncertainty_deg = mix(a.horizontal_uncertainty_deg, b.horizontal_uncertainty_deg);
  c.orientation_uncertainty_deg =
      a.orientation_uncertainty_deg && b.orientation_uncertainty_deg
          ? std::optional(mix(*a.orientation_uncertainty_deg, *b.orientation_uncertainty_deg))
          : std::nullopt;
  c.solid_angle_uncertainty_sr = mix(a.solid_angle_uncertainty_sr, b.solid_angle_uncertainty_sr);
  return c;
}

// A measured row of contours.csv as a profile contour.
ProfileContour contourOfRow(const ContourRow& row) {
  return {.level_cd_m2 = row.level_cd_m2,
          .kind = row.kind,
          .vertical_deg = *row.vertical_deg,
          .horizontal_deg = *row.horizontal_deg,
          .orientation_deg = *row.orientation_deg,
          .solid_angle_sr = *row.solid_angle_sr,
          .vertical_uncertainty_deg = *row.vertical_uncertainty_deg,
          .horizontal_uncertainty_deg = *row.horizontal_uncertainty_deg,
          .orientation_uncertainty_deg = row.orientation_uncertainty_deg,
          .solid_angle_uncertainty_sr = *row.solid_angle_uncertainty_sr};
}

// The measured rungs of the stacks at one α (fixed levels, then the half maximum as the last
// entry with key -1), each the mean over those stacks (the half maximum's level in ln L).
using StackRungs = std::map<double, ProfileContour>;
constexpr double kHalfMaximumKey = -1;

std::map<double, StackRungs> measuredRungsByAlpha(const ContourTable& contours) {
  std::map<double, std::map<double, std::vector<ProfileContour>>> collected;
  for (const ContourRow& row : contours.rows) {
    if (!row.measured() || row.kind == ContourKind::kLimit) continue;
    const double key = row.kind == ContourKind::kHalfMaximum ? kHalfMaximumKey : row.level_cd_m2;
    collected[row.alpha_deg][key].push_back(contourOfRow(row));
  }
  std::map<double, StackRungs> by_alpha;
  for (const auto& [alpha, levels] : collected) {
    for (const auto& [key, list] : levels) {
      // The running mean: the k-th contour mixed in with weight 1/k.
      ProfileContour mean = list.front();
      double ln_level = std::log(list.front().level_cd_m2);
      for (std::size_t k = 1; k < list.size(); ++k) {
        const double t = 1.0 / static_cast<double>(k + 1);
        mean = lerpContour(mean, list[k], t);
        ln_level += (std::log(list[k].level_cd_m2) - ln_level) * t;
      }
      mean.level_cd_m2 = key == kHalfMaximumKey ? std::exp(ln_level) : key;
      by_alpha[alpha][key] = mean;
    }
  }
  return by_alpha;
}

// The rungs at a whole degree between two measured α (t from the first), the levels both have.
std::vector<ProfileContour> rungsBetween(const StackRungs& a, const StackRungs& b, double t) {
  std::vector<ProfileContour> rungs;
  for (const auto& [key, first] : a) {
    const auto second = b.find(key);
    if (second == b.end()) continue;
    ProfileContour c = lerpContour(first, second->second, t);
    c.level_cd_m2 =
        key == kHalfMaximumKey
            ? std::exp(std::log(first.level_cd_m2) +
                       (std::log(second->second.level_cd_m2) - std::log(first.level_cd_m2)) * t)
            : key;
    rungs.push_back(c);
  }
  std::stable_sort(rungs.begin(), rungs.end(),
                   [](const auto& x, const auto& y) { return x.level_cd_m2 < y.level_cd_m2; });
  return rungs;
}

// The value at x of the parabola through (x[k], y[k]), k = 0, 1, 2.
double parabolaAt(const std::array<double, 3>& x, const std::array<double, 3>& y, double at) {
  double sum = 0;
  for (std::size_t k = 0; k < 3; ++k) {
    double basis = 1;
    for (std::size_t m = 0; m < 3; ++m)
      if (m != k) basis *= (at - x[m]) / (x[k] - x[m]);
    sum += basis * y[k];
  }
  return sum;
}

// The contour at `level` in one degree's ladder (linear in ln level between rungs), or none
// outside its rungs. Between rungs the linear interpolation's own error joins the standard
// uncertainties of the axes and the solid angle: estimated as the larger of its differences from
// the parabolas (in ln level) through the two rungs and the next rung above, and below: a lobe's
// axes are concave in ln level (a Gaussian's go as √ln(L/T)), its solid angle nearly linear, and
// either curve's bend changes along the ladder.
std::optional<ProfileContour> contourInRow(const ProfileLadderRow& row, double level) {
  const std::vector<ProfileContour>& rungs = row.contours;
  if (rungs.empty() || !(level >= rungs.front().level_cd_m2) ||
      !(level <= rungs.back().level_cd_m2))
    return std::nullopt;
  for (std::size_t i = 0; i < rungs.size(); ++i) {
    if (rungs[i].level_cd_m2 == level) return rungs[i];
    if (i + 1 == rungs.size() || rungs[i + 1].level_cd_m2 <= level) continue;
    const double t = std::log(level / rungs[i].level_cd_m2) /
                     std::log(rungs[i + 1].level_cd_m2 / rungs[i].level_cd_m2);
    ProfileContour c = lerpContour(rungs[i], rungs[i + 1], t);
    c.level_cd_m2 = level;
    c.kind = ContourKind::kLadder;
    // Each parabola through the two rungs and a third, the next above and the next below.
    std::vector<std::size_t> thirds;
    if (i + 2 < rungs.size()) thirds.push_back(i + 2);
    if (i > 0) thirds.push_back(i - 1);
    const auto widen = [&](double ProfileContour::*value, double ProfileContour::*sigma) {
      double error = 0;
      for (const std::size_t third : thirds) {
        const std::array<const ProfileContour*, 3> r{&rungs[i], &rungs[i + 1], &rungs[third]};
        const std::array<double, 3> x{std::log(r[0]->level_cd_m2), std::log(r[1]->level_cd_m2),
                                      std::log(r[2]->level_cd_m2)};
        const double curved =
            parabolaAt(x, {r[0]->*value, r[1]->*value, r[2]->*value}, std::log(level));
        error = std::max(error, std::abs(curved - c.*value));
      }
      c.*sigma = std::hypot(c.*sigma, error);
    };
    widen(&ProfileContour::vertical_deg, &ProfileContour::vertical_uncertainty_deg);
    widen(&ProfileContour::horizontal_deg, &ProfileContour::horizontal_uncertainty_deg);
    widen(&ProfileContour::solid_angle_sr, &ProfileContour::solid_angle_uncertainty_sr);
    return c;
  }
  return std::nullopt;
}

const ProfileLadderRow* ladderRowAt(const GlareProfile& profile, double alpha_deg) {
  const auto it = std::ranges::find_if(
      profile.ladder, [&](const ProfileLadderRow& row) { return row.alpha_deg == alpha_deg; });
  return it == profile.ladder.end() ? nullptr : &*it;
}

}  // namespace

std::vector<ProfileLadderRow> profileLadder(const ContourTable& contours) {
  const std::map<double, StackRungs> by_alpha = measuredRungsByAlpha(contours);
  std::vector<ProfileLadderRow> ladder;
  if (by_alpha.empty()) return ladder;
  const double first = std::max(0.0, std::ceil(by_alpha.begin()->first));
  const double last =
      std::min<double>(kProfileAlphaMaxDeg, std::floor(std::prev(by_alpha.end())->first));
  for (double alpha = first; alpha <= last; alpha += kProfileStepDeg) {
    auto above = by_alpha.lower_bound(alpha);  // the first measured α at or above
    ProfileLadderRow row{.alpha_deg = alpha};
    if (above->first == alpha) {
      row.contours = rungsBetween(above->second, above->second, 0);
    } else {
      const auto below = std::prev(above);
      row.contours = rungsBetween(below->second, above->second,
                                  (alpha - below->first) / (above->first - below->first));
    }
    ladder.push_back(std::move(row));
  }
  return ladder;
}

std::optional<ProfileContour> contourAt(const GlareProfile& profile, double alpha_deg,
                                        double level_cd_m2) {
  if (!std::isfinite(alpha_deg) || !(level_cd_m2 > 0) || !std::isfinite(level_cd_m2))
    return std::nullopt;
  const double lo = std::floor(alpha_deg), hi = std::ceil(alpha_deg);
  const ProfileLadderRow* below = ladderRowAt(profile, lo);
  const ProfileLadderRow* above = ladderRowAt(profile, hi);
  if (!below || !above) return std::nullopt;
  const auto a = contourInRow(*below, level_cd_m2);
  if (!a || lo == hi) return a;
  const auto b = contourInRow(*above, level_cd_m2);
  if (!b) return std::nullopt;
  ProfileContour c = lerpContour(*a, *b, alpha_deg - lo);
  c.level_cd_m2 = level_cd_m2;
  c.kind = a->kind == b->kind ? a->kind : ContourKind::kLadder;
  return c;
}

Result<std::optional<ProfileContour>> contourAt(const GlareProfile& profile, double alpha_deg,
                                                double level_cd_m2, double source_illuminance_lx) {
  if (profile.referred != true || !profile.reference_illuminance_lx)
    return badInput(fmt::format(
        "the glare profile of {} is {}: the contour under a source illuminance needs a profile "
        "referred to a reference illuminance (docs/method.md \"Reference illuminance and the "
        "contour ladder\")",
        profile.module,
        profile.referred ? "unreferred"
                         : "of glarecam.glare-profile/1, which "
                           "does not say what it refers to"));
  if (!(source_illuminance_lx > 0) || !std::isfinite(source_illuminance_lx))
    return badInput(fmt::format("source illuminance {:g} lx: must be a positive number",
                                source_illuminance_lx));
  return contourAt(profile, alpha_deg,
                   level_cd_m2 * *profile.reference_illuminance_lx / source_illuminance_lx);
}

GlareProfile makeGlareProfile(const ProfileIdentity& identity, const SweepTable& table,
                              const SweepFits& fits, const GlareLimit& limit,
                              const ContourTable* contours) {
  GlareProfile profile;
  profile.module = identity.module;
  profile.date = identity.date;
  profile.source = identity.source;
  // Stacks of the simulated camera make a simulated profile, never a measurement's.
  profile.simulated = isSimulated(table);
  profile.routes = tableRoutes(table);
  profile.cameras = tableCameras(table);
  profile.calibrations = tableCalibrations(table);
  std::vector<std::string> seen;
  for (const SweepRow& row : table.rows) {
    if (row.calibration_id.empty() || std::ranges::find(seen, row.calibration_id) != seen.end())
      continue;
    seen.push_back(row.calibration_id);
    profile.calibration_details.push_back(
        {.id = row.calibration_id,
         .date = row.calibration_date.empty() ? std::nullopt : std::optional(row.calibration_date),
         .luminance_factor = row.luminance_factor,
         .luminance_factor_u = row.luminance_factor_u});
  }
  profile.luminance_fit = fits.cosineIsBetter() ? "cos" : "biquadratic";
  profile.glare_ranges = glareRanges(fits, limit);
  profile.limit = limit;
  profile.rows = glareProfile(fits, limit);
  for (const SweepRow& row : table.rows) {
    profile.measured.push_back(
        {.alpha_deg = row.alpha_deg,
         .limit_cd_m2 = row.limit_cd_m2,
         .lmax_cd_m2 = row.lmax_cd_m2,
         .lmax_bound = row.lmax_bound.empty() ? std::nullopt : std::optional(row.lmax_bound),
         .vertical_deg = row.vertical_deg,
         .horizontal_deg = row.horizontal_deg});
  }
  profile.reference_illuminance_lx = tableReferenceIlluminance(table);
  profile.referred = profile.reference_illuminance_lx.has_value();
  if (profile.referred == true) profile.sources = sourceIlluminanceRange(table);
  if (contours) profile.ladder = profileLadder(*contours);
  profile.fits = fitsJson(fits);
  profile.generator = Generator{};
  return profile;
}

namespace {

json beamJson(const std::optional<CircularBeamSpread>& beam) {
  if (!beam) return nullptr;
  return {{"solid_angle_sr", beam->solid_angle_sr},
          {"beta_mrad", beam->beta_mrad},
          {"slope_error_mrad", beam->slope_error_mrad}};
}

json rowJson(const ProfileRow& row) {
  return {{"alpha_deg", row.alpha_deg},
          {"lmax_cd_m2", jsonOrNull(row.lmax_cd_m2)},
          {"limit_cd_m2", jsonOrNull(row.limit_cd_m2)},
          {"glares", row.glares},
          {"vertical_deg", jsonOrNull(row.vertical_deg)},
          {"horizontal_deg", jsonOrNull(row.horizontal_deg)},
          {"circular_beam", beamJson(row.beam)},
          {"extrapolated", row.extrapolated}};
}

json measuredJson(const MeasuredRow& row) {
  return {{"alpha_deg", row.alpha_deg},
          {"limit_cd_m2", jsonOrNull(row.limit_cd_m2)},
          {"lmax_cd_m2", row.lmax_cd_m2},
          {"lmax_bound", jsonOrNull(row.lmax_bound)},
          {"vertical_deg", jsonOrNull(row.vertical_deg)},
          {"horizontal_deg", jsonOrNull(row.horizontal_deg)}};
}

json ladderJson(const std::vector<ProfileLadderRow>& ladder) {
  json rows = json::array();
  for (const ProfileLadderRow& row : ladder) {
    json contours = json::array();
    for (const ProfileContour& c : row.contours) {
      contours.push_back({{"level_cd_m2", c.level_cd_m2},
                          {"kind", toString(c.kind)},
                          {"vertical_deg", c.vertical_deg},
                          {"horizontal_deg", c.horizontal_deg},
                          {"orientation_deg", c.orientation_deg},
                          {"solid_angle_sr", c.solid_angle_sr},
                          {"uncertainty",
                           {{"vertical_deg", c.vertical_uncertainty_deg},
                            {"horizontal_deg", c.horizontal_uncertainty_deg},
                            {"orientation_deg", jsonOrNull(c.orientation_uncertainty_deg)},
                            {"solid_angle_sr", c.solid_angle_uncertainty_sr}}}});
    }
    rows.push_back({{"alpha_deg", row.alpha_deg}, {"contours", contours}});
  }
  return rows;
}

// ---- reading ---------------------------------------------------------------------------------

Result<ProfileContour> readProfileContour(const JsonReader& r) {
  GLARECAM_CHECK(r.object());
  ProfileContour c;
  GLARECAM_ASSIGN(c.level_cd_m2, r.positive("level_cd_m2"));
  std::string kind;
  GLARECAM_ASSIGN(kind, r.word("kind", {"ladder", "half_maximum"}));
  c.kind = *contourKindFromString(kind);
  if (c.kind == ContourKind::kLadder && !isLadderLevel(c.level_cd_m2))
    return r.fail("level_cd_m2", fmt::format("{:g} cd/m² is not a level of the ladder (1, 2.15 or "
                                             "4.64 × 10ⁿ from 10 000 cd/m²)",
                                             c.level_cd_m2));
  GLARECAM_ASSIGN(c.vertical_deg, r.numberIn("vertical_deg", 0, kMaxFullAxisDeg, "°"));
  GLARECAM_ASSIGN(c.horizontal_deg, r.numberIn("horizontal_deg", 0, kMaxFullAxisDeg, "°"));
  GLARECAM_ASSIGN(c.orientation_deg, r.numberIn("orientation_deg", -90, 90, "°"));
  GLARECAM_ASSIGN(c.solid_angle_sr, r.numberIn("solid_angle_sr", 0, 4 * std::numbers::pi, " sr"));
  JsonReader u;
  GLARECAM_ASSIGN(u, r.objectMember("uncertainty"));
  GLARECAM_ASSIGN(c.vertical_uncertainty_deg, u.nonNegative("vertical_deg"));
  GLARECAM_ASSIGN(c.horizontal_uncertainty_deg, u.nonNegative("horizontal_deg"));
  GLARECAM_ASSIGN(c.orientation_uncertainty_deg, u.optionalNonNegative("orientation_deg"));
  GLARECAM_ASSIGN(c.solid_angle_uncertainty_sr, u.nonNegative("solid_angle_sr"));
  return c;
}

// Whole degrees 0–80, ascending, each once; each degree's contours by ascending level.
Result<std::vector<ProfileLadderRow>> readLadder(const JsonReader& list) {
  std::vector<ProfileLadderRow> ladder;
  for (std::size_t i = 0; i < list.size(); ++i) {
    const JsonReader element = list.element(i);
    GLARECAM_CHECK(element.object());
    ProfileLadderRow row;
    GLARECAM_ASSIGN(row.alpha_deg, element.numberIn("alpha_deg", 0, kProfileAlphaMaxDeg, "°"));
    if (row.alpha_deg != std::floor(row.alpha_deg))
      return element.fail("alpha_deg", "is not a whole degree");
    if (!ladder.empty() && !(row.alpha_deg > ladder.back().alpha_deg))
      return element.fail("alpha_deg", "is not above the previous row's: the ladder ascends in α");
    JsonReader contours;
    GLARECAM_ASSIGN(contours, element.arrayMember("contours"));
    GLARECAM_ASSIGN(row.contours, readEach<ProfileContour>(contours, readProfileContour));
    for (std::size_t k = 1; k < row.contours.size(); ++k) {
      if (!(row.contours[k].level_cd_m2 > row.contours[k - 1].level_cd_m2))
        return contours.element(k).fail("level_cd_m2",
                                        "is not above the previous contour's: levels ascend");
    }
    ladder.push_back(std::move(row));
  }
  return ladder;
}

// /2's `illuminance` (required there) and `ladder`.
Status readIlluminanceAndLadder(const JsonReader& r, const std::string& schema, GlareProfile& p) {
  const bool v2 = schema == kGlareProfileSchema;
  std::optional<JsonReader> illuminance;
  GLARECAM_ASSIGN(illuminance, r.optionalObject("illuminance"));
  if (v2 && !illuminance)
    return r.fail("illuminance", "is missing (a /2 profile says what it refers to)");
  if (illuminance) {
    std::string status;
    GLARECAM_ASSIGN(status, illuminance->word("status", {"referred", "unreferred", "unstated"}));
    if (status != "unstated") p.referred = status == "referred";
    GLARECAM_ASSIGN(p.reference_illuminance_lx, illuminance->optionalPositive("reference_lx"));
    if ((p.referred == true) != p.reference_illuminance_lx.has_value())
      return illuminance->fail("reference_lx", "must be given exactly when the status is referred");
    std::optional<std::string> sources;
    GLARECAM_ASSIGN(sources, illuminance->optionalText("sources"));
    p.sources = sources.value_or("");
  }
  std::optional<JsonReader> ladder;
  GLARECAM_ASSIGN(ladder, r.optionalArray("ladder"));
  if (v2 && !ladder) return r.fail("ladder", "is missing (a /2 profile has one, maybe empty)");
  if (ladder) GLARECAM_ASSIGN(p.ladder, readLadder(*ladder));
  return {};
}

// A circular beam's full angle, in mrad: at most a half turn.
constexpr double kMaxBetaMrad = std::numbers::pi * kMradPerRad;

// A list member (absent: empty) whose elements `read` turns into T.
template <typename T, typename Read>
Result<std::vector<T>> readList(const JsonReader& document, std::string_view key, Read read) {
  std::optional<JsonReader> list;
  GLARECAM_ASSIGN(list, document.optionalArray(key));
  if (!list) return std::vector<T>{};
  return readEach<T>(*list, read);
}

Result<std::vector<std::string>> readTexts(const JsonReader& document, std::string_view key) {
  return readList<std::string>(document, key, [](const JsonReader& r) { return r.text(); });
}

Result<ProfileCalibration> readCalibration(const JsonReader& r) {
  GLARECAM_CHECK(r.object());
  ProfileCalibration calibration;
  GLARECAM_ASSIGN(calibration.id, r.text("id"));
  GLARECAM_ASSIGN(calibration.date, r.optionalText("date"));
  GLARECAM_ASSIGN(calibration.luminance_factor, r.optionalPositive("luminance_factor"));
  GLARECAM_ASSIGN(calibration.luminance_factor_u, r.optionalNonNegative("luminance_factor_u"));
  return calibration;
}

Result<std::optional<double>> readAxis(const JsonReader& r, std::string_view key) {
  return r.optionalNumberIn(key, 0, kMaxFullAxisDeg, "°");
}

Result<MeasuredRow> readMeasured(const JsonReader& r) {
  GLARECAM_CHECK(r.object());
  MeasuredRow row;
  GLARECAM_ASSIGN(row.alpha_deg, r.numberIn("alpha_deg", 0, 90, "°"));
  GLARECAM_ASSIGN(row.limit_cd_m2, r.optionalPositive("limit_cd_m2"));
  GLARECAM_ASSIGN(row.lmax_cd_m2, r.nonNegative("lmax_cd_m2"));
  GLARECAM_ASSIGN(row.lmax_bound, r.optionalWord("lmax_bound", {"lower", "upper"}));
  GLARECAM_ASSIGN(row.vertical_deg, readAxis(r, "vertical_deg"));
  GLARECAM_ASSIGN(row.horizontal_deg, readAxis(r, "horizontal_deg"));
  return row;
}

Result<std::optional<CircularBeamSpread>> readBeam(const JsonReader& row) {
  std::optional<JsonReader> block;
  GLARECAM_ASSIGN(block, row.optionalObject("circular_beam"));
  if (!block) return std::optional<CircularBeamSpread>{};
  CircularBeamSpread beam;
  GLARECAM_ASSIGN(beam.beta_mrad, block->numberIn("beta_mrad", 0, kMaxBetaMrad, " mrad"));
  // Earlier profiles may give beta alone: the rest follows from it (circularBeamSpread()).
  const double half_angle_rad = beam.beta_mrad / 2 / kMradPerRad;
  std::optional<double> solid_angle_sr, slope_error_mrad;
  GLARECAM_ASSIGN(solid_angle_sr, block->optionalNonNegative("solid_angle_sr"));
  GLARECAM_ASSIGN(slope_error_mrad, block->optionalNumber("slope_error_mrad"));
  beam.solid_angle_sr =
      solid_angle_sr.value_or(2 * std::numbers::pi * (1 - std::cos(half_angle_rad)));
  beam.slope_error_mrad = slope_error_mrad.value_or(beam.beta_mrad / 2 - kSunHalfAngleMrad);
  return std::optional(beam);
}

Result<ProfileRow> readRow(const JsonReader& r) {
  ProfileRow row;
  GLARECAM_ASSIGN(row.alpha_deg, r.numberIn("alpha_deg", 0, kProfileAlphaMaxDeg, "°"));
  if (row.alpha_deg != std::floor(row.alpha_deg))
    return r.fail("alpha_deg", "is not a whole degree");
  // exp of a fitted ln L: positive, however far the fit extrapolates.
  GLARECAM_ASSIGN(row.lmax_cd_m2, r.optionalNonNegative("lmax_cd_m2"));
  GLARECAM_ASSIGN(row.limit_cd_m2, r.optionalPositive("limit_cd_m2"));
  std::optional<bool> glares, extrapolated;
  GLARECAM_ASSIGN(glares, r.optionalBoolean("glares"));
  GLARECAM_ASSIGN(extrapolated, r.optionalBoolean("extrapolated"));
  row.glares = glares.value_or(false);
  row.extrapolated = extrapolated.value_or(false);
  GLARECAM_ASSIGN(row.vertical_deg, readAxis(r, "vertical_deg"));
  GLARECAM_ASSIGN(row.horizontal_deg, readAxis(r, "horizontal_deg"));
  GLARECAM_ASSIGN(row.beam, readBeam(r));
  return row;
}

// One row per whole degree 0–80, each once, in order of α.
Result<std::vector<ProfileRow>> readRows(const JsonReader& document) {
  JsonReader list;
  GLARECAM_ASSIGN(list, document.arrayMember("profile"));
  std::vector<std::optional<ProfileRow>> by_alpha(kProfileAlphaMaxDeg + 1);
  for (std::size_t i = 0; i < list.size(); ++i) {
    const JsonReader element = list.element(i);
    GLARECAM_CHECK(element.object());
    ProfileRow row;
    GLARECAM_ASSIGN(row, readRow(element));
    auto& slot = by_alpha[static_cast<std::size_t>(row.alpha_deg)];
    if (slot) return element.fail("alpha_deg", "repeats an earlier row's α");
    slot = row;
  }
  std::vector<ProfileRow> rows;
  for (int alpha = 0; alpha <= kProfileAlphaMaxDeg; ++alpha) {
    if (!by_alpha[static_cast<std::size_t>(alpha)])
      return list.fail("has no row for α = " + std::to_string(alpha) + "°");
    rows.push_back(*by_alpha[static_cast<std::size_t>(alpha)]);
  }
  return rows;
}

Result<std::vector<AlphaRange>> readRanges(const JsonReader& document) {
  JsonReader list;
  GLARECAM_ASSIGN(list, document.arrayMember("glare_ranges_deg"));
  return readEach<AlphaRange>(list, [](const JsonReader& range) -> Result<AlphaRange> {
    GLARECAM_CHECK(range.array());
    if (range.size() != 2) return range.fail("is not [from, to] in degrees");
    AlphaRange alpha;
    GLARECAM_ASSIGN(alpha.from_deg, range.element(0).numberIn(0, 90, "°"));
    GLARECAM_ASSIGN(alpha.to_deg, range.element(1).numberIn(0, 90, "°"));
    if (alpha.from_deg > alpha.to_deg) return range.fail("runs backwards (from > to)");
    return alpha;
  });
}

Result<GlareLimit> readLimit(const JsonReader& document) {
  std::optional<JsonReader> block;
  GLARECAM_ASSIGN(block, document.optionalObject("limit"));
  if (!block) return GlareLimit{};
  std::string mode;
  GLARECAM_ASSIGN(mode, block->text("mode"));
  GlareLimit limit;
  GLARECAM_ASSIGN(limit.constant_cd_m2, block->optionalPositive("constant_cd_m2"));
  if (mode != GlareLimit{.constant_cd_m2 = limit.constant_cd_m2}.mode()) {
    return block->fail("mode", "\"" + mode +
                                   "\" does not match constant_cd_m2 (alpha_curve without one, "
                                   "constant with one)");
  }
  return limit;
}

}  // namespace

json toJson(const GlareProfile& p) {
  json rows = json::array();
  for (const ProfileRow& row : p.rows) rows.push_back(rowJson(row));
  json measured = json::array();
  for (const MeasuredRow& row : p.measured) measured.push_back(measuredJson(row));
  json ranges = json::array();
  for (const AlphaRange& r : p.glare_ranges) ranges.push_back({r.from_deg, r.to_deg});
  json details = json::array();
  for (const ProfileCalibration& c : p.calibration_details) {
    details.push_back({{"id", c.id},
                       {"date", jsonOrNull(c.date)},
                       {"luminance_factor", jsonOrNull(c.luminance_factor)},
                       {"luminance_factor_u", jsonOrNull(c.luminance_factor_u)}});
  }
  json document{
      {"schema", kGlareProfileSchema},
      {"module", p.module},
      {"simulated", p.simulated},
      {"cameras", p.cameras},
      {"calibrations", p.calibrations},
      {"calibration_details", details},
      {"glare_ranges_deg", ranges},
      {"limit", {{"mode", p.limit.mode()}, {"constant_cd_m2", jsonOrNull(p.limit.constant_cd_m2)}}},
      {"sun_half_angle_mrad", p.sun_half_angle_mrad},
      {"profile", rows},
      {"measured", measured},
      {"illuminance",
       {{"status", !p.referred   ? "unstated"
                   : *p.referred ? "referred"
                                 : "unreferred"},
        {"reference_lx", jsonOrNull(p.reference_illuminance_lx)},
        {"sources", p.sources.empty() ? nlohmann::json(nullptr) : nlohmann::json(p.sources)}}},
      {"ladder", ladderJson(p.ladder)},
      {"fits", p.fits}};
  // What earlier profiles lack is left out rather than written as a value they never had.
  if (p.date) document["date"] = *p.date;
  if (p.source) document["source"] = *p.source;
  if (p.luminance_fit) document["luminance_fit"] = *p.luminance_fit;
  if (!p.routes.empty()) document["routes"] = p.routes;
  if (p.generator) document["generator"] = toJson(*p.generator);
  return document;
}

Result<GlareProfile> glareProfileFromJson(const json& document, const std::string& file) {
  const JsonReader r(document, file);
  std::string schema;
  GLARECAM_ASSIGN(schema, r.schema(kGlareProfileSchema, "a glare profile", kGlareProfileSchemas));
  GlareProfile p;
  GLARECAM_ASSIGN(p.module, r.text("module"));
  GLARECAM_ASSIGN(p.date, r.optionalText("date"));
  GLARECAM_ASSIGN(p.source, r.optionalText("source"));
  std::optional<bool> simulated;
  GLARECAM_ASSIGN(simulated, r.optionalBoolean("simulated"));
  p.simulated = simulated.value_or(false);
  GLARECAM_ASSIGN(p.cameras, readTexts(r, "cameras"));
  GLARECAM_ASSIGN(p.routes, readTexts(r, "routes"));
  for (std::size_t i = 0; i < p.routes.size(); ++i) {
    if (p.routes[i] != "camera" && p.routes[i] != "brdf")
      return r.fail("routes", "[" + std::to_string(i) + "] \"" + p.routes[i] +
                                  "\" is not a route (camera or brdf)");
  }
  GLARECAM_ASSIGN(p.calibrations, readTexts(r, "calibrations"));
  GLARECAM_ASSIGN(p.calibration_details,
                  readList<ProfileCalibration>(r, "calibration_details", readCalibration));
  GLARECAM_ASSIGN(p.luminance_fit, r.optionalWord("luminance_fit", {"cos", "biquadratic"}));
  GLARECAM_ASSIGN(p.glare_ranges, readRanges(r));
  GLARECAM_ASSIGN(p.limit, readLimit(r));
  std::optional<double> sun_half_angle_mrad;
  GLARECAM_ASSIGN(sun_half_angle_mrad, r.optionalPositive("sun_half_angle_mrad"));
  p.sun_half_angle_mrad = sun_half_angle_mrad.value_or(kSunHalfAngleMrad);
  GLARECAM_ASSIGN(p.rows, readRows(r));
  GLARECAM_ASSIGN(p.measured, readList<MeasuredRow>(r, "measured", readMeasured));
  GLARECAM_CHECK(readIlluminanceAndLadder(r, schema, p));
  std::optional<JsonReader> fits;
  GLARECAM_ASSIGN(fits, r.optionalObject("fits"));
  if (fits) {
    p.fits = fits->value();
  }
  std::optional<JsonReader> generator;
  GLARECAM_ASSIGN(generator, r.optionalMember("generator"));
  if (generator) GLARECAM_ASSIGN(p.generator, generatorFromJson(*generator));
  return p;
}

Result<GlareProfile> readGlareProfile(const std::filesystem::path& path) {
  json document;
  GLARECAM_ASSIGN(document, readJsonFile(path));
  return glareProfileFromJson(document, path.string());
}

}  // namespace glarecam::pipeline
