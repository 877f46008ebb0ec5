#include "pipeline/glare_profile.h"

#include <algorithm>
#include <cmath>
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

GlareProfile makeGlareProfile(const ProfileIdentity& identity, const SweepTable& table,
                              const SweepFits& fits, const GlareLimit& limit) {
  GlareProfile profile;
  profile.module = identity.module;
  profile.date = identity.date;
  profile.source = identity.source;
  // Stacks of the simulated camera make a simulated profile, never a measurement's.
  profile.simulated = isSimulated(table);
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

// ---- reading ---------------------------------------------------------------------------------

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
      {"fits", p.fits}};
  // What earlier profiles lack is left out rather than written as a value they never had.
  if (p.date) document["date"] = *p.date;
  if (p.source) document["source"] = *p.source;
  if (p.luminance_fit) document["luminance_fit"] = *p.luminance_fit;
  if (p.generator) document["generator"] = toJson(*p.generator);
  return document;
}

Result<GlareProfile> glareProfileFromJson(const json& document, const std::string& file) {
  const JsonReader r(document, file);
  GLARECAM_CHECK(r.schema(kGlareProfileSchema, "a glare profile", kGlareProfileSchemas));
  GlareProfile p;
  GLARECAM_ASSIGN(p.module, r.text("module"));
  GLARECAM_ASSIGN(p.date, r.optionalText("date"));
  GLARECAM_ASSIGN(p.source, r.optionalText("source"));
  std::optional<bool> simulated;
  GLARECAM_ASSIGN(simulated, r.optionalBoolean("simulated"));
  p.simulated = simulated.value_or(false);
  GLARECAM_ASSIGN(p.cameras, readTexts(r, "cameras"));
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
