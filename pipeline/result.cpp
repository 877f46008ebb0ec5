#include "pipeline/result.h"

#include <cmath>

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

}  // namespace

nlohmann::json makeResult(const ResultInputs& in) {
  using nlohmann::json;
  const LuminanceStats& s = in.stats;
  json result;
  result["schema"] = kResultSchema;
  result["stack"] = in.stack_id;
  result["alpha_deg"] = in.alpha_deg ? json(*in.alpha_deg) : json(nullptr);
  result["image"] = {{"width", in.width}, {"height", in.height}};
  result["calibration"] = {{"origin", in.calibration_origin},
                           {"noise_model", in.noise_model_assumed ? "assumed" : "calibrated"}};
  result["luminance"] = {{"max_cd_m2", s.max.value_cd_m2},
                         {"max_pixel", {std::lround(s.max.x_px), std::lround(s.max.y_px)}},
                         {"max_position_px", {s.max.x_px, s.max.y_px}},
                         {"max_method", toString(s.max.method)},
                         {"max_is_lower_bound", s.max.method == PeakMethod::kLowerBound},
                         {"max_is_upper_bound", s.max.method == PeakMethod::kUpperBound},
                         {"valid_fraction", s.valid_fraction},
                         {"saturated_pixels", s.saturated_pixels},
                         {"dark_pixels", s.dark_pixels},
                         {"median_relative_uncertainty", s.median_relative_uncertainty}};
  result["limit"] = {{"limit_cd_m2", in.limit_cd_m2 ? json(*in.limit_cd_m2) : json(nullptr)},
                     {"mode", "alpha_curve"}};
  result["glare"] = glareVerdict(s.max, in.limit_cd_m2);
  result["outputs"] = {{"luminance_exr", "luminance.exr"},
                       {"quality_exr", "quality.exr"},
                       {"luminance_png", "luminance.png"}};
  result["generator"] = {{"name", "glarecam"}, {"version", kVersion}};
  return result;
}

}  // namespace glarecam::pipeline
