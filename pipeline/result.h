// The result document of one processed stack (schema glarecam.result/1, docs/process.md).
// Built from plain values: identity, calibration origin, luminance statistics, the limit and
// FWHM ellipses (null where there is none, with a status saying why) and the glare verdict.
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "calibration/frame_consistency.h"
#include "pipeline/glare_analysis.h"
#include "pipeline/luminance_stats.h"

namespace glarecam::pipeline {

inline constexpr std::string_view kResultSchema = "glarecam.result/1";

struct FrameCheck {
  std::string file;
  calibration::FrameAgreement agreement;
};

struct ResultInputs {
  std::string stack_id;
  std::optional<double> alpha_deg;
  int width = 0, height = 0;
  std::string calibration_origin;  // "inline", a path
  bool noise_model_assumed = false;
  LuminanceStats stats;
  std::vector<FrameCheck> frames;
  std::optional<double> limit_cd_m2;
  bool constant_limit = false;  // --threshold rather than the α curve
  GlareAnalysis glare;
};

nlohmann::json ellipseJson(const EllipseMeasurement& measurement);

nlohmann::json makeResult(const ResultInputs& inputs);

}  // namespace glarecam::pipeline
