#include "pipeline/result.h"

#include <cmath>
#include <limits>

#include "core/version.h"

namespace glarecam::pipeline {

namespace {

// true / false, or null when there is no limit or the verdict cannot be known: a lower bound
// (saturated everywhere) below the limit may still exceed it, an upper bound (dark everywhere)
// above it may still stay below.
nlohmann::json glareVerdict(const LuminancePeak& max, const std::optional<double>& limit_cd_m2) {
  if (!limit_cd_m2) return nullptr;
  const bool reaches = max.value_cd_m2 >= *limit_cd_m2;
  if (!reaches && max.method == PeakMethod::kLowerBound) return nullptr;
  if (reaches && max.method == PeakMethod::kUpperBound) return nullptr;
  return reaches;
}

nlohmann::json pair(double a, double b) { return nlohmann::json::array({a, b}); }

}  // namespace

nlohmann::json ellipseJson(const EllipseMeasurement& measurement) {
  if (!measurement.ellipse) return nullptr;
  const GlareEllipse& e = *measurement.ellipse;
  return {
      {"vertical_deg", e.vertical_deg},
      {"horizontal_deg", e.horizontal_deg},
      {"major_deg", e.major_deg},
      {"minor_deg", e.minor_deg},
      {"orientation_deg", e.orientation_deg},
      {"center_px", pair(e.centre_px.x, e.centre_px.y)},
      {"center_direction_deg",
       pair(e.centre_direction.horizontal_deg, e.centre_direction.vertical_deg)},
      {"semi_axes_px", pair(e.semi_major_px, e.semi_minor_px)},
      {"solid_angle_sr", e.solid_angle_sr},
      {"fit_rms_px", e.fit_rms_px},
      {"fit_rms_deg", e.fit_rms_deg},
      {"shape_residual", e.shape_residual_fraction},
      {"ellipticity_ok", e.ellipticity_ok},
      {"truncated", e.truncated},
      {"regions", e.regions},
      {"contour_points", e.contour_points},
      {"region_pixels", e.region_pixels},
      {"smoothing_radius_px", e.smoothing_radius_px},
      {"uncertainty",
       {{"vertical_deg", e.vertical_uncertainty_deg},
        {"horizontal_deg", e.horizontal_uncertainty_deg},
        {"orientation_deg", std::isfinite(e.orientation_uncertainty_deg)
                                ? nlohmann::json(e.orientation_uncertainty_deg)
                                : nlohmann::json(nullptr)},
        {"solid_angle_sr", e.solid_angle_uncertainty_sr},
        {"unweighted_contour_points", e.unweighted_contour_points}}},
  };
}

nlohmann::json makeResult(const ResultInputs& in) {
  using nlohmann::json;
  const LuminanceStats& s = in.stats;
  json result;
  result["schema"] = kResultSchema;
  result["stack"] = in.stack_id;
  result["alpha_deg"] = in.alpha_deg ? json(*in.alpha_deg) : json(nullptr);
  result["alpha_source"] = in.alpha_source.empty() ? json(nullptr) : json(in.alpha_source);
  result["alpha_uncertainty_deg"] =
      in.alpha_uncertainty_deg ? json(*in.alpha_uncertainty_deg) : json(nullptr);
  result["image"] = {{"width", in.width}, {"height", in.height}};
  result["camera"] = in.camera;
  result["module"] = in.module ? nlohmann::json(*in.module) : nlohmann::json(nullptr);
  const CalibrationIdentity& cal = in.calibration;
  const auto optional = [](const auto& value) { return value ? json(*value) : json(nullptr); };
  result["calibration"] = {{"origin", cal.origin},
                           {"noise_model", cal.noise_model_assumed ? "assumed" : "calibrated"},
                           {"black", cal.dark_frame ? "dark_frame" : "black_level"},
                           {"hot_pixels_masked", cal.hot_pixels},
                           {"file", optional(cal.file)},
                           {"sha256", optional(cal.sha256)},
                           {"camera", cal.camera},
                           {"parts", cal.parts},
                           {"id", cal.id},
                           {"luminance_factor", cal.luminance_factor},
                           {"luminance_factor_u", optional(cal.luminance_factor_u)}};
  // Lmax's uncertainty: the merge's noise, and that combined in quadrature with K's, which scales
  // every luminance of the stack alike (null when the calibration states no u(K)).
  const double noise_u = s.max.relative_uncertainty;
  const double k_u = cal.luminance_factor_u && cal.luminance_factor > 0
                         ? *cal.luminance_factor_u / cal.luminance_factor
                         : std::numeric_limits<double>::quiet_NaN();
  result["luminance"] = {
      {"max_cd_m2", s.max.value_cd_m2},
      {"max_pixel", {std::lround(s.max.x_px), std::lround(s.max.y_px)}},
      {"max_position_px", {s.max.x_px, s.max.y_px}},
      {"max_method", toString(s.max.method)},
      {"max_relative_uncertainty", std::isfinite(s.max.relative_uncertainty)
                                       ? json(s.max.relative_uncertainty)
                                       : json(nullptr)},
      {"max_relative_uncertainty_combined", std::isfinite(noise_u) && std::isfinite(k_u)
                                                ? json(std::hypot(noise_u, k_u))
                                                : json(nullptr)},
      {"max_is_lower_bound", s.max.method == PeakMethod::kLowerBound},
      {"max_is_upper_bound", s.max.method == PeakMethod::kUpperBound},
      {"valid_fraction", s.valid_fraction},
      {"saturated_pixels", s.saturated_pixels},
      {"dark_pixels", s.dark_pixels},
      {"masked_pixels", s.masked_pixels},
      {"median_relative_uncertainty", s.median_relative_uncertainty}};
  const auto& limit = in.glare.limit;
  // true: every frame checked and agreeing; false: one disagrees; null: some frame had too few
  // well-exposed pixels to be checked (and none disagrees).
  result["frames"] = json::array();
  bool disagreement = false, unchecked = in.frames.empty();
  for (const FrameCheck& f : in.frames) {
    const double ratio = f.agreement.median_ratio;
    result["frames"].push_back(
        {{"file", f.file},
         {"median_ratio", std::isfinite(ratio) ? json(ratio) : json(nullptr)},
         {"samples", f.agreement.samples},
         {"agrees", std::isfinite(ratio) ? json(f.agreement.agrees()) : json(nullptr)}});
    disagreement = disagreement || !f.agreement.agrees();
    unchecked = unchecked || !std::isfinite(ratio);
  }
  result["luminance"]["frames_consistent"] =
      disagreement ? json(false) : (unchecked ? json(nullptr) : json(true));
  result["limit"] = {
      {"limit_cd_m2", in.limit_cd_m2 ? json(*in.limit_cd_m2) : json(nullptr)},
      {"mode", in.constant_limit ? "constant" : (in.limit_cd_m2 ? "alpha_curve" : "none")},
      {"status", limit ? toString(limit->status) : "no_limit"},
      {"ellipse", limit ? ellipseJson(*limit) : json(nullptr)}};
  result["fwhm"] = {{"level_cd_m2", in.glare.fwhm.level_cd_m2},
                    {"status", toString(in.glare.fwhm.status)},
                    {"ellipse", ellipseJson(in.glare.fwhm)}};
  result["thresholds"] = json::array();
  for (const EllipseMeasurement& m : in.glare.thresholds) {
    result["thresholds"].push_back({{"threshold_cd_m2", m.level_cd_m2},
                                    {"status", toString(m.status)},
                                    {"ellipse", ellipseJson(m)}});
  }
  result["glare"] = glareVerdict(s.max, in.limit_cd_m2);
  result["outputs"] = {{"luminance_exr", "luminance.exr"},
                       {"quality_exr", "quality.exr"},
                       {"luminance_png", "luminance.png"}};
  result["generator"] = {{"name", "glarecam"}, {"version", kVersion}};
  return result;
}

}  // namespace glarecam::pipeline
