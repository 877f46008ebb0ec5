#include "pipeline/result.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/stack_manifest.h"
#include "core/time.h"

namespace glarecam::pipeline {

namespace {

using nlohmann::json;

// Counts (pixels, points, regions): whole numbers far below 2^53.
constexpr long long kMaxCount = 1LL << 53;
// A solid angle is at most the whole sphere.
constexpr double kMaxSolidAngleSr = 4 * 3.14159265358979323846;

json pair(const std::array<double, 2>& values) { return json::array({values[0], values[1]}); }

// true / false, or none when there is no limit or the verdict cannot be known: a lower bound
// (saturated everywhere) below the limit may still exceed it, an upper bound (dark everywhere)
// above it may still stay below.
std::optional<bool> glareVerdict(const LuminancePeak& max,
                                 const std::optional<double>& limit_cd_m2) {
  if (!limit_cd_m2) return std::nullopt;
  const bool reaches = max.value_cd_m2 >= *limit_cd_m2;
  if (!reaches && max.method == PeakMethod::kLowerBound) return std::nullopt;
  if (reaches && max.method == PeakMethod::kUpperBound) return std::nullopt;
  return reaches;
}

std::optional<double> finite(double value) {
  return std::isfinite(value) ? std::optional(value) : std::nullopt;
}

ResultLevel resultLevel(const EllipseMeasurement& measurement) {
  return {.level_cd_m2 = measurement.level_cd_m2,
          .status = measurement.status,
          .ellipse = measurement.ellipse ? std::optional(resultEllipse(*measurement.ellipse))
                                         : std::nullopt};
}

// ---- writing ---------------------------------------------------------------------------------

json ellipseJson(const std::optional<ResultEllipse>& ellipse) {
  if (!ellipse) return nullptr;
  const ResultEllipse& e = *ellipse;
  return {
      {"vertical_deg", e.vertical_deg},
      {"horizontal_deg", e.horizontal_deg},
      {"major_deg", e.major_deg},
      {"minor_deg", e.minor_deg},
      {"orientation_deg", e.orientation_deg},
      {"center_px", pair(e.center_px)},
      {"center_direction_deg", pair(e.center_direction_deg)},
      {"semi_axes_px", pair(e.semi_axes_px)},
      {"solid_angle_sr", e.solid_angle_sr},
      {"fit_rms_px", e.fit_rms_px},
      {"fit_rms_deg", e.fit_rms_deg},
      {"shape_residual", e.shape_residual},
      {"ellipticity_ok", e.ellipticity_ok},
      {"truncated", e.truncated},
      {"regions", e.regions},
      {"contour_points", e.contour_points},
      {"region_pixels", e.region_pixels},
      {"smoothing_radius_px", e.smoothing_radius_px},
      {"uncertainty",
       {{"vertical_deg", e.vertical_uncertainty_deg},
        {"horizontal_deg", e.horizontal_uncertainty_deg},
        {"orientation_deg", jsonOrNull(e.orientation_uncertainty_deg)},
        {"solid_angle_sr", e.solid_angle_uncertainty_sr},
        {"unweighted_contour_points", e.unweighted_contour_points}}},
  };
}

json calibrationJson(const CalibrationIdentity& cal) {
  json parts = nullptr;
  if (cal.parts) {
    parts = json::object();
    for (const auto& [name, part] : *cal.parts)
      parts[name] = {{"measured_at", jsonOrNull(part.measured_at)},
                     {"method", jsonOrNull(part.method)}};
  }
  return {{"origin", cal.origin},
          {"noise_model", cal.noise_model_assumed ? "assumed" : "calibrated"},
          {"black", cal.dark_frame ? "dark_frame" : "black_level"},
          {"hot_pixels_masked", cal.hot_pixels},
          {"file", jsonOrNull(cal.file)},
          {"sha256", jsonOrNull(cal.sha256)},
          {"camera", cal.camera},
          {"parts", parts},
          {"id", cal.id},
          {"luminance_factor", cal.luminance_factor},
          {"luminance_factor_u", jsonOrNull(cal.luminance_factor_u)}};
}

json illuminanceJson(const ResultIlluminance& e) {
  return {{"status", e.referred() ? "referred" : "unreferred"},
          {"reference_lx", jsonOrNull(e.reference_lx)},
          {"source", e.source ? toJson(*e.source) : json(nullptr)},
          {"factor", e.referred() ? json(e.factor()) : json(nullptr)}};
}

json luminanceJson(const ResultLuminance& l) {
  return {{"max_cd_m2", l.max_cd_m2},
          {"measured_max_cd_m2", jsonOrNull(l.measured_max_cd_m2)},
          {"max_pixel", {l.max_pixel[0], l.max_pixel[1]}},
          {"max_position_px", pair(l.max_position_px)},
          {"max_method", toString(l.max_method)},
          {"max_relative_uncertainty", jsonOrNull(l.max_relative_uncertainty)},
          {"max_relative_uncertainty_combined", jsonOrNull(l.max_relative_uncertainty_combined)},
          {"max_is_lower_bound", l.isLowerBound()},
          {"max_is_upper_bound", l.isUpperBound()},
          {"valid_fraction", l.valid_fraction},
          {"saturated_pixels", l.saturated_pixels},
          {"dark_pixels", l.dark_pixels},
          {"masked_pixels", l.masked_pixels},
          {"median_relative_uncertainty", l.median_relative_uncertainty},
          {"frames_consistent", jsonOrNull(l.frames_consistent)}};
}

// ---- reading ---------------------------------------------------------------------------------

Result<std::array<double, 2>> readPair(const JsonReader& parent, std::string_view key) {
  JsonReader value;
  GLARECAM_ASSIGN(value, parent.arrayMember(key));
  if (value.size() != 2) return value.fail("must be a pair of numbers");
  std::array<double, 2> pair{};
  for (std::size_t i = 0; i < 2; ++i) GLARECAM_ASSIGN(pair[i], value.element(i).number());
  return pair;
}

Result<long long> readCount(const JsonReader& parent, std::string_view key) {
  return parent.integer(key, 0, kMaxCount);
}

Result<std::optional<ResultEllipse>> readEllipse(const JsonReader& parent) {
  std::optional<JsonReader> block;
  GLARECAM_ASSIGN(block, parent.optionalMember("ellipse"));
  if (!block) return std::optional<ResultEllipse>{};
  const JsonReader& r = *block;
  GLARECAM_CHECK(r.object());
  ResultEllipse e;
  GLARECAM_ASSIGN(e.vertical_deg, r.numberIn("vertical_deg", 0, kMaxAxisDeg, "°"));
  GLARECAM_ASSIGN(e.horizontal_deg, r.numberIn("horizontal_deg", 0, kMaxAxisDeg, "°"));
  GLARECAM_ASSIGN(e.major_deg, r.numberIn("major_deg", 0, kMaxAxisDeg, "°"));
  GLARECAM_ASSIGN(e.minor_deg, r.numberIn("minor_deg", 0, kMaxAxisDeg, "°"));
  GLARECAM_ASSIGN(e.orientation_deg,
                  r.numberIn("orientation_deg", -kMaxOrientationDeg, kMaxOrientationDeg, "°"));
  GLARECAM_ASSIGN(e.center_px, readPair(r, "center_px"));
  GLARECAM_ASSIGN(e.center_direction_deg, readPair(r, "center_direction_deg"));
  GLARECAM_ASSIGN(e.semi_axes_px, readPair(r, "semi_axes_px"));
  GLARECAM_ASSIGN(e.solid_angle_sr, r.numberIn("solid_angle_sr", 0, kMaxSolidAngleSr, " sr"));
  GLARECAM_ASSIGN(e.fit_rms_px, r.nonNegative("fit_rms_px"));
  GLARECAM_ASSIGN(e.fit_rms_deg, r.nonNegative("fit_rms_deg"));
  GLARECAM_ASSIGN(e.shape_residual, r.nonNegative("shape_residual"));
  GLARECAM_ASSIGN(e.ellipticity_ok, r.boolean("ellipticity_ok"));
  GLARECAM_ASSIGN(e.truncated, r.boolean("truncated"));
  GLARECAM_ASSIGN(e.regions, readCount(r, "regions"));
  GLARECAM_ASSIGN(e.contour_points, readCount(r, "contour_points"));
  GLARECAM_ASSIGN(e.region_pixels, readCount(r, "region_pixels"));
  GLARECAM_ASSIGN(e.smoothing_radius_px, readCount(r, "smoothing_radius_px"));
  JsonReader u;
  GLARECAM_ASSIGN(u, r.objectMember("uncertainty"));
  GLARECAM_ASSIGN(e.vertical_uncertainty_deg, u.nonNegative("vertical_deg"));
  GLARECAM_ASSIGN(e.horizontal_uncertainty_deg, u.nonNegative("horizontal_deg"));
  GLARECAM_ASSIGN(e.orientation_uncertainty_deg, u.optionalNonNegative("orientation_deg"));
  GLARECAM_ASSIGN(e.solid_angle_uncertainty_sr, u.nonNegative("solid_angle_sr"));
  GLARECAM_ASSIGN(e.unweighted_contour_points, readCount(u, "unweighted_contour_points"));
  return std::optional(e);
}

Result<EllipseStatus> readStatus(const JsonReader& parent) {
  std::string text;
  GLARECAM_ASSIGN(text, parent.text("status"));
  const auto status = ellipseStatusFromString(text);
  if (!status) return parent.fail("status", "\"" + text + "\" is not an ellipse status");
  return *status;
}

// The ellipse is there exactly when it was measured.
Status checkEllipseMatchesStatus(const JsonReader& parent, std::optional<EllipseStatus> status,
                                 const std::optional<ResultEllipse>& ellipse) {
  const bool measured = status == EllipseStatus::kMeasured;
  if (measured && !ellipse) return parent.fail("ellipse", "is missing though status is measured");
  if (!measured && ellipse) return parent.fail("ellipse", "is given though status is not measured");
  return {};
}

Result<ResultLevel> readLevel(const JsonReader& block, std::string_view level_key) {
  GLARECAM_CHECK(block.object());
  ResultLevel level;
  GLARECAM_ASSIGN(level.level_cd_m2, block.number(level_key));
  GLARECAM_ASSIGN(level.status, readStatus(block));
  GLARECAM_ASSIGN(level.ellipse, readEllipse(block));
  GLARECAM_CHECK(checkEllipseMatchesStatus(block, level.status, level.ellipse));
  return level;
}

Result<ResultLimit> readResultLimit(const JsonReader& document) {
  JsonReader block;
  GLARECAM_ASSIGN(block, document.objectMember("limit"));
  ResultLimit limit;
  GLARECAM_ASSIGN(limit.limit_cd_m2, block.optionalPositive("limit_cd_m2"));
  std::string mode;
  GLARECAM_ASSIGN(mode, block.word("mode", {"alpha_curve", "constant", "none"}));
  for (LimitMode known : {LimitMode::kAlphaCurve, LimitMode::kConstant, LimitMode::kNone}) {
    if (mode == toString(known)) limit.mode = known;
  }
  if ((limit.mode == LimitMode::kNone) == limit.limit_cd_m2.has_value())
    return block.fail("mode", "\"" + mode + "\" does not match limit_cd_m2");
  std::string status;
  GLARECAM_ASSIGN(status, block.text("status"));
  if (status != "no_limit") GLARECAM_ASSIGN(limit.status, readStatus(block));
  if (limit.status.has_value() != limit.limit_cd_m2.has_value())
    return block.fail("status", "\"" + status + "\" does not match limit_cd_m2");
  GLARECAM_ASSIGN(limit.ellipse, readEllipse(block));
  GLARECAM_CHECK(checkEllipseMatchesStatus(block, limit.status, limit.ellipse));
  return limit;
}

Result<ResultLuminance> readLuminance(const JsonReader& document) {
  JsonReader r;
  GLARECAM_ASSIGN(r, document.objectMember("luminance"));
  ResultLuminance l;
  // An upper bound of a dark image may be at or below zero (black subtracted from noise).
  GLARECAM_ASSIGN(l.max_cd_m2, r.number("max_cd_m2"));
  JsonReader pixel;
  GLARECAM_ASSIGN(pixel, r.arrayMember("max_pixel"));
  if (pixel.size() != 2) return pixel.fail("must be a pair of whole numbers");
  for (std::size_t i = 0; i < 2; ++i)
    GLARECAM_ASSIGN(l.max_pixel[i], pixel.element(i).integer(-kMaxCount, kMaxCount));
  GLARECAM_ASSIGN(l.max_position_px, readPair(r, "max_position_px"));
  std::string method;
  GLARECAM_ASSIGN(method, r.text("max_method"));
  const auto parsed = peakMethodFromString(method);
  if (!parsed) return r.fail("max_method", "\"" + method + "\" is not a peak method");
  l.max_method = *parsed;
  GLARECAM_ASSIGN(l.measured_max_cd_m2, r.optionalNumber("measured_max_cd_m2"));
  GLARECAM_ASSIGN(l.max_relative_uncertainty, r.optionalNonNegative("max_relative_uncertainty"));
  GLARECAM_ASSIGN(l.max_relative_uncertainty_combined,
                  r.optionalNonNegative("max_relative_uncertainty_combined"));
  bool lower = false, upper = false;
  GLARECAM_ASSIGN(lower, r.boolean("max_is_lower_bound"));
  GLARECAM_ASSIGN(upper, r.boolean("max_is_upper_bound"));
  if (lower != l.isLowerBound() || upper != l.isUpperBound())
    return r.fail("max_method", "\"" + method + "\" contradicts max_is_lower/upper_bound");
  GLARECAM_ASSIGN(l.valid_fraction, r.numberIn("valid_fraction", 0, 1));
  GLARECAM_ASSIGN(l.saturated_pixels, readCount(r, "saturated_pixels"));
  GLARECAM_ASSIGN(l.dark_pixels, readCount(r, "dark_pixels"));
  GLARECAM_ASSIGN(l.masked_pixels, readCount(r, "masked_pixels"));
  GLARECAM_ASSIGN(l.median_relative_uncertainty, r.nonNegative("median_relative_uncertainty"));
  GLARECAM_ASSIGN(l.frames_consistent, r.optionalBoolean("frames_consistent"));
  return l;
}

// The `illuminance` block; a result written before it existed is unreferred.
Result<ResultIlluminance> readIlluminance(const JsonReader& document) {
  std::optional<JsonReader> block;
  GLARECAM_ASSIGN(block, document.optionalObject("illuminance"));
  ResultIlluminance e;
  if (!block) return e;
  std::string status;
  GLARECAM_ASSIGN(status, block->word("status", {"referred", "unreferred"}));
  std::optional<JsonReader> source;
  GLARECAM_ASSIGN(source, block->optionalObject("source"));
  if (source) GLARECAM_ASSIGN(e.source, parseSourceIlluminance(*source));
  GLARECAM_ASSIGN(e.reference_lx, block->optionalPositive("reference_lx"));
  if (e.reference_lx)
    GLARECAM_CHECK(checkReferenceIlluminance(
        *e.reference_lx, block->file() + ": " + block->path() + ".reference_lx"));
  const bool referred = status == "referred";
  if (referred != e.source.has_value())
    return block->fail("source", referred ? "is missing for a referred result"
                                          : "must be null for an unreferred result");
  if (referred != e.reference_lx.has_value())
    return block->fail("reference_lx", referred ? "is missing for a referred result"
                                                : "must be null for an unreferred result");
  return e;
}

Result<ResultFrame> readFrame(const JsonReader& r) {
  GLARECAM_CHECK(r.object());
  ResultFrame frame;
  GLARECAM_ASSIGN(frame.file, r.text("file"));
  GLARECAM_ASSIGN(frame.median_ratio, r.optionalNonNegative("median_ratio"));
  GLARECAM_ASSIGN(frame.samples, readCount(r, "samples"));
  GLARECAM_ASSIGN(frame.agrees, r.optionalBoolean("agrees"));
  if (frame.agrees.has_value() != frame.median_ratio.has_value())
    return r.fail("agrees", "must be given exactly when median_ratio is");
  return frame;
}

// A block copied verbatim from the stack's manifest or calibration (a camera block, whatever
// another tool put in it): an object or null, kept as written.
Result<json> readCopiedBlock(const JsonReader& parent, std::string_view key) {
  std::optional<JsonReader> block;
  GLARECAM_ASSIGN(block, parent.optionalObject(key));
  if (!block) return json(nullptr);
  return block->value();
}

Result<CalibrationIdentity> readResultCalibration(const JsonReader& document) {
  JsonReader r;
  GLARECAM_ASSIGN(r, document.objectMember("calibration"));
  CalibrationIdentity cal;
  GLARECAM_ASSIGN(cal.origin, r.text("origin"));
  std::string noise, black;
  GLARECAM_ASSIGN(noise, r.word("noise_model", {"assumed", "calibrated"}));
  cal.noise_model_assumed = noise == "assumed";
  GLARECAM_ASSIGN(black, r.word("black", {"dark_frame", "black_level"}));
  cal.dark_frame = black == "dark_frame";
  GLARECAM_ASSIGN(cal.hot_pixels, r.boolean("hot_pixels_masked"));
  GLARECAM_ASSIGN(cal.file, r.optionalText("file"));
  GLARECAM_ASSIGN(cal.sha256, r.optionalText("sha256"));
  GLARECAM_ASSIGN(cal.camera, readCopiedBlock(r, "camera"));
  std::optional<JsonReader> parts;
  GLARECAM_ASSIGN(parts, r.optionalObject("parts"));
  if (parts) {
    cal.parts.emplace();
    for (const auto& [name, value] : parts->value().items()) {
      JsonReader part;
      GLARECAM_ASSIGN(part, parts->objectMember(name));
      CalibrationPart& entry = (*cal.parts)[name];
      GLARECAM_ASSIGN(entry.measured_at, part.optionalText("measured_at"));
      GLARECAM_ASSIGN(entry.method, part.optionalText("method"));
    }
  }
  GLARECAM_ASSIGN(cal.id, r.text("id"));
  GLARECAM_ASSIGN(cal.luminance_factor, r.positive("luminance_factor"));
  GLARECAM_ASSIGN(cal.luminance_factor_u, r.optionalNonNegative("luminance_factor_u"));
  return cal;
}

Result<ResultContour> readContour(const JsonReader& block) {
  GLARECAM_CHECK(block.object());
  ResultContour contour;
  std::string kind;
  GLARECAM_ASSIGN(kind, block.word("kind", {"ladder", "limit", "half_maximum"}));
  contour.kind = *contourKindFromString(kind);
  GLARECAM_ASSIGN(contour.level, readLevel(block, "level_cd_m2"));
  if (!(contour.level.level_cd_m2 > 0)) return block.fail("level_cd_m2", "must be positive");
  if (contour.kind == ContourKind::kLadder && !isLadderLevel(contour.level.level_cd_m2))
    return block.fail("level_cd_m2", fmt::format("{:g} cd/m² is not a level of the ladder (1, "
                                                 "2.15 or 4.64 × 10ⁿ from 10 000 cd/m²)",
                                                 contour.level.level_cd_m2));
  return contour;
}

// `contours`: null or absent (no ladder), or the rungs by ascending level, the limit's at the
// limit and the half maximum's at the FWHM's level, each at most once.
Result<std::optional<std::vector<ResultContour>>> readContours(const JsonReader& document,
                                                               const StackResult& result) {
  std::optional<JsonReader> list;
  GLARECAM_ASSIGN(list, document.optionalArray("contours"));
  if (!list) return std::optional<std::vector<ResultContour>>{};
  std::vector<ResultContour> contours;
  GLARECAM_ASSIGN(contours, readEach<ResultContour>(*list, readContour));
  int limits = 0, halves = 0;
  for (std::size_t i = 0; i < contours.size(); ++i) {
    const JsonReader element = list->element(i);
    const ResultContour& c = contours[i];
    if (i > 0 && c.level.level_cd_m2 < contours[i - 1].level.level_cd_m2)
      return element.fail("level_cd_m2", "is below the previous contour's: the ladder ascends");
    if (c.kind == ContourKind::kLimit) {
      ++limits;
      if (result.limit.limit_cd_m2 != c.level.level_cd_m2)
        return element.fail("level_cd_m2", "of the limit contour is not limit.limit_cd_m2");
    }
    if (c.kind == ContourKind::kHalfMaximum) {
      ++halves;
      if (c.level.level_cd_m2 != result.fwhm.level_cd_m2)
        return element.fail("level_cd_m2", "of the half-maximum contour is not fwhm.level_cd_m2");
    }
    if (limits > 1 || halves > 1)
      return element.fail("kind", fmt::format("a second \"{}\" contour", toString(c.kind)));
  }
  return std::optional(std::move(contours));
}

Result<ResultOutputs> readOutputs(const JsonReader& document) {
  JsonReader r;
  GLARECAM_ASSIGN(r, document.objectMember("outputs"));
  ResultOutputs outputs;
  GLARECAM_ASSIGN(outputs.luminance_exr, r.text("luminance_exr"));
  GLARECAM_ASSIGN(outputs.quality_exr, r.text("quality_exr"));
  GLARECAM_ASSIGN(outputs.luminance_png, r.text("luminance_png"));
  GLARECAM_ASSIGN(outputs.pruned_at, r.optionalText("pruned_at"));
  if (outputs.pruned_at && !parseIsoTime(*outputs.pruned_at))
    return r.fail("pruned_at", "is not an ISO 8601 time");
  return outputs;
}

}  // namespace

const char* toString(LimitMode mode) {
  switch (mode) {
    case LimitMode::kAlphaCurve:
      return "alpha_curve";
    case LimitMode::kConstant:
      return "constant";
    case LimitMode::kNone:
      return "none";
  }
  return "none";
}

ResultEllipse resultEllipse(const GlareEllipse& e) {
  return {
      .vertical_deg = e.vertical_deg,
      .horizontal_deg = e.horizontal_deg,
      .major_deg = e.major_deg,
      .minor_deg = e.minor_deg,
      .orientation_deg = e.orientation_deg,
      .center_px = {e.centre_px.x, e.centre_px.y},
      .center_direction_deg = {e.centre_direction.horizontal_deg, e.centre_direction.vertical_deg},
      .semi_axes_px = {e.semi_major_px, e.semi_minor_px},
      .solid_angle_sr = e.solid_angle_sr,
      .fit_rms_px = e.fit_rms_px,
      .fit_rms_deg = e.fit_rms_deg,
      .shape_residual = e.shape_residual_fraction,
      .ellipticity_ok = e.ellipticity_ok,
      .truncated = e.truncated,
      .regions = e.regions,
      .contour_points = static_cast<long long>(e.contour_points),
      .region_pixels = static_cast<long long>(e.region_pixels),
      .smoothing_radius_px = e.smoothing_radius_px,
      .vertical_uncertainty_deg = e.vertical_uncertainty_deg,
      .horizontal_uncertainty_deg = e.horizontal_uncertainty_deg,
      .orientation_uncertainty_deg = finite(e.orientation_uncertainty_deg),
      .solid_angle_uncertainty_sr = e.solid_angle_uncertainty_sr,
      .unweighted_contour_points = static_cast<long long>(e.unweighted_contour_points)};
}

std::string describe(const ResultIlluminance& illuminance) {
  if (!illuminance.referred()) return "unreferred";
  return fmt::format("referred to {:g} klx (source {})", *illuminance.reference_lx / 1000,
                     describe(*illuminance.source));
}

std::string newestPartDate(const CalibrationIdentity& calibration) {
  std::string newest;
  if (!calibration.parts) return newest;
  for (const auto& [name, part] : *calibration.parts) {
    // ISO 8601 in UTC ("2026-06-21T10:00:00Z"): the text orders as the time.
    if (part.measured_at && part.measured_at->size() >= 10)
      newest = std::max(newest, part.measured_at->substr(0, 10));
  }
  return newest;
}

std::string StackResult::cameraText(std::string_view key) const {
  if (!camera.is_object()) return {};
  const auto it = camera.find(key);
  return it != camera.end() && it->is_string() ? it->get<std::string>() : std::string();
}

const char* toString(Route route) { return route == Route::kBrdf ? "brdf" : "camera"; }

std::optional<Route> routeFromString(std::string_view text) {
  if (text == "camera") return Route::kCamera;
  if (text == "brdf") return Route::kBrdf;
  return std::nullopt;
}

StackResult makeResult(const ResultInputs& in) {
  const LuminanceStats& s = in.stats;
  StackResult result;
  result.stack = in.stack_id;
  result.route = in.route;
  result.brdf = in.brdf;
  result.alpha_deg = in.alpha_deg;
  if (!in.alpha_source.empty()) result.alpha_source = in.alpha_source;
  result.alpha_uncertainty_deg = in.alpha_uncertainty_deg;
  result.width = in.width;
  result.height = in.height;
  result.camera = in.camera;
  result.module = in.module;
  result.calibration = in.calibration;
  // Lmax's uncertainty: the merge's noise, and that combined in quadrature with K's, which scales
  // every luminance of the stack alike (none when the calibration states no u(K)).
  const CalibrationIdentity& cal = in.calibration;
  const double noise_u = s.max.relative_uncertainty;
  const double k_u = cal.luminance_factor_u && cal.luminance_factor > 0
                         ? *cal.luminance_factor_u / cal.luminance_factor
                         : std::numeric_limits<double>::quiet_NaN();
  ResultLuminance& l = result.luminance;
  l.max_cd_m2 = s.max.value_cd_m2;
  l.max_pixel = {std::lround(s.max.x_px), std::lround(s.max.y_px)};
  l.max_position_px = {s.max.x_px, s.max.y_px};
  l.max_method = s.max.method;
  l.max_relative_uncertainty = finite(noise_u);
  // u(E) scales every referred luminance alike too (fully correlated across the image).
  result.illuminance = in.illuminance;
  const double e_u = in.illuminance.referred() ? in.illuminance.source->relativeUncertainty()
                                               : std::numeric_limits<double>::quiet_NaN();
  if (std::isfinite(noise_u) && (std::isfinite(k_u) || std::isfinite(e_u)))
    l.max_relative_uncertainty_combined =
        std::hypot(noise_u, std::isfinite(k_u) ? k_u : 0.0, std::isfinite(e_u) ? e_u : 0.0);
  if (in.illuminance.referred()) l.measured_max_cd_m2 = s.max.value_cd_m2 / in.illuminance.factor();
  l.valid_fraction = s.valid_fraction;
  l.saturated_pixels = static_cast<long long>(s.saturated_pixels);
  l.dark_pixels = static_cast<long long>(s.dark_pixels);
  l.masked_pixels = static_cast<long long>(s.masked_pixels);
  l.median_relative_uncertainty = s.median_relative_uncertainty;
  bool disagreement = false, unchecked = in.frames.empty();
  for (const FrameCheck& f : in.frames) {
    const std::optional<double> ratio = finite(f.agreement.median_ratio);
    result.frames.push_back({.file = f.file,
                             .median_ratio = ratio,
                             .samples = static_cast<long long>(f.agreement.samples),
                             .agrees = ratio ? std::optional(f.agreement.agrees()) : std::nullopt});
    disagreement = disagreement || !f.agreement.agrees();
    unchecked = unchecked || !ratio;
  }
  if (disagreement || !unchecked) l.frames_consistent = !disagreement;
  const auto& limit = in.glare.limit;
  result.limit = {.limit_cd_m2 = in.limit_cd_m2,
                  .mode = in.constant_limit ? LimitMode::kConstant
                          : in.limit_cd_m2  ? LimitMode::kAlphaCurve
                                            : LimitMode::kNone,
                  .status = limit ? std::optional(limit->status) : std::nullopt,
                  .ellipse = limit ? resultLevel(*limit).ellipse : std::nullopt};
  result.fwhm = resultLevel(in.glare.fwhm);
  for (const EllipseMeasurement& m : in.glare.thresholds)
    result.thresholds.push_back(resultLevel(m));
  if (in.ladder) {
    result.contours.emplace();
    for (const ContourRung& rung : in.glare.ladder)
      result.contours->push_back({rung.kind, resultLevel(rung.measurement)});
  }
  result.glare = glareVerdict(s.max, in.limit_cd_m2);
  return result;
}

json toJson(const StackResult& r) {
  json thresholds = json::array();
  for (const ResultLevel& level : r.thresholds) {
    thresholds.push_back({{"threshold_cd_m2", level.level_cd_m2},
                          {"status", toString(level.status)},
                          {"ellipse", ellipseJson(level.ellipse)}});
  }
  json contours = nullptr;
  if (r.contours) {
    contours = json::array();
    for (const ResultContour& c : *r.contours) {
      contours.push_back({{"level_cd_m2", c.level.level_cd_m2},
                          {"kind", toString(c.kind)},
                          {"status", toString(c.level.status)},
                          {"ellipse", ellipseJson(c.level.ellipse)}});
    }
  }
  json frames = json::array();
  for (const ResultFrame& f : r.frames) {
    frames.push_back({{"file", f.file},
                      {"median_ratio", jsonOrNull(f.median_ratio)},
                      {"samples", f.samples},
                      {"agrees", jsonOrNull(f.agrees)}});
  }
  return {{"schema", kResultSchema},
          {"stack", r.stack},
          {"route", toString(r.route)},
          {"alpha_deg", jsonOrNull(r.alpha_deg)},
          {"alpha_source", jsonOrNull(r.alpha_source)},
          {"alpha_uncertainty_deg", jsonOrNull(r.alpha_uncertainty_deg)},
          {"image", {{"width", r.width}, {"height", r.height}}},
          {"camera", r.camera},
          {"module", jsonOrNull(r.module)},
          {"calibration", calibrationJson(r.calibration)},
          {"illuminance", illuminanceJson(r.illuminance)},
          {"luminance", luminanceJson(r.luminance)},
          {"frames", frames},
          {"limit",
           {{"limit_cd_m2", jsonOrNull(r.limit.limit_cd_m2)},
            {"mode", toString(r.limit.mode)},
            {"status", r.limit.status ? toString(*r.limit.status) : "no_limit"},
            {"ellipse", ellipseJson(r.limit.ellipse)}}},
          {"fwhm",
           {{"level_cd_m2", r.fwhm.level_cd_m2},
            {"status", toString(r.fwhm.status)},
            {"ellipse", ellipseJson(r.fwhm.ellipse)}}},
          {"thresholds", thresholds},
          {"contours", contours},
          {"glare", jsonOrNull(r.glare)},
          {"outputs",
           {{"luminance_exr", r.outputs.luminance_exr},
            {"quality_exr", r.outputs.quality_exr},
            {"luminance_png", r.outputs.luminance_png},
            {"pruned_at", jsonOrNull(r.outputs.pruned_at)}}},
          {"brdf", r.brdf},
          {"generator", toJson(r.generator)}};
}

Result<StackResult> resultFromJson(const json& document, const std::string& file) {
  const JsonReader r(document, file);
  GLARECAM_CHECK(r.schema(kResultSchema, "a result"));
  StackResult result;
  GLARECAM_ASSIGN(result.stack, r.text("stack"));
  GLARECAM_ASSIGN(result.alpha_deg, r.optionalNumberIn("alpha_deg", 0, kMaxStackAlphaDeg, "°"));
  // Written before the BRDF route: absent is the camera's.
  std::optional<std::string> route;
  GLARECAM_ASSIGN(route, r.optionalWord("route", {"camera", "brdf"}));
  result.route = route ? *routeFromString(*route) : Route::kCamera;
  GLARECAM_ASSIGN(result.alpha_source,
                  r.optionalWord("alpha_source", {"manifest", "given", "measurement"}));
  if (result.alpha_source.has_value() != result.alpha_deg.has_value())
    return r.fail("alpha_source", "must be given exactly when alpha_deg is");
  GLARECAM_ASSIGN(result.alpha_uncertainty_deg, r.optionalNonNegative("alpha_uncertainty_deg"));
  JsonReader image;
  GLARECAM_ASSIGN(image, r.objectMember("image"));
  GLARECAM_ASSIGN(result.width, image.integer("width", 1, kMaxImageSide));
  GLARECAM_ASSIGN(result.height, image.integer("height", 1, kMaxImageSide));
  GLARECAM_ASSIGN(result.camera, readCopiedBlock(r, "camera"));
  GLARECAM_ASSIGN(result.module, r.optionalText("module"));
  GLARECAM_ASSIGN(result.calibration, readResultCalibration(r));
  GLARECAM_ASSIGN(result.illuminance, readIlluminance(r));
  GLARECAM_ASSIGN(result.luminance, readLuminance(r));
  if (result.luminance.measured_max_cd_m2.has_value() != result.illuminance.referred())
    return r.fail("luminance.measured_max_cd_m2",
                  "must be given exactly when the result is referred (illuminance.status)");
  JsonReader frames;
  GLARECAM_ASSIGN(frames, r.arrayMember("frames"));
  GLARECAM_ASSIGN(result.frames, readEach<ResultFrame>(frames, readFrame));
  GLARECAM_ASSIGN(result.limit, readResultLimit(r));
  JsonReader fwhm;
  GLARECAM_ASSIGN(fwhm, r.member("fwhm"));
  GLARECAM_ASSIGN(result.fwhm, readLevel(fwhm, "level_cd_m2"));
  JsonReader thresholds;
  GLARECAM_ASSIGN(thresholds, r.arrayMember("thresholds"));
  GLARECAM_ASSIGN(result.thresholds, readEach<ResultLevel>(thresholds, [](const JsonReader& level) {
                    return readLevel(level, "threshold_cd_m2");
                  }));
  GLARECAM_ASSIGN(result.contours, readContours(r, result));
  GLARECAM_ASSIGN(result.glare, r.optionalBoolean("glare"));
  if (result.glare && !result.limit.limit_cd_m2)
    return r.fail("glare", "is a verdict without a limit");
  GLARECAM_ASSIGN(result.outputs, readOutputs(r));
  GLARECAM_ASSIGN(result.brdf, readCopiedBlock(r, "brdf"));
  if ((result.route == Route::kBrdf) != result.brdf.is_object())
    return r.fail("brdf", "must be an object exactly when the route is brdf");
  JsonReader generator;
  GLARECAM_ASSIGN(generator, r.member("generator"));
  GLARECAM_ASSIGN(result.generator, generatorFromJson(generator));
  return result;
}

Result<StackResult> readResult(const std::filesystem::path& path) {
  json document;
  GLARECAM_ASSIGN(document, readJsonFile(path));
  return resultFromJson(document, path.string());
}

bool hasResultSchema(const json& document) {
  return document.is_object() && document.value("schema", "") == kResultSchema;
}

namespace {

// A frame that reads this factor or more above or below the others is far off: its reading is
// said as the factor, and it may be one of a swapped pair.
constexpr double kFarOffFactor = 2;

bool farAbove(double ratio) { return ratio >= kFarOffFactor; }
bool farBelow(double ratio) { return ratio > 0 && ratio <= 1 / kFarOffFactor; }

}  // namespace

std::string formatFrameRatio(double median_ratio) {
  if (farAbove(median_ratio)) return fmt::format("{:.3g} times", median_ratio);
  if (farBelow(median_ratio)) return fmt::format("1/{:.3g} of", 1 / median_ratio);
  return fmt::format("{:+.0f} %", 100 * (median_ratio - 1));
}

std::vector<std::pair<std::size_t, std::size_t>> swappedFramePairs(
    const std::vector<double>& median_ratios) {
  constexpr double kReciprocal = 1.25;  // r and 1/r to within 25 %
  std::vector<std::pair<std::size_t, std::size_t>> pairs;
  for (std::size_t i = 0; i < median_ratios.size(); ++i) {
    for (std::size_t j = i + 1; j < median_ratios.size(); ++j) {
      const double a = median_ratios[i], b = median_ratios[j];
      const bool apart = (farAbove(a) && farBelow(b)) || (farAbove(b) && farBelow(a));  // NaN: no
      if (apart && a * b <= kReciprocal && a * b >= 1 / kReciprocal) pairs.emplace_back(i, j);
    }
  }
  return pairs;
}

}  // namespace glarecam::pipeline
