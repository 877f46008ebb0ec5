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

// What a result's numbers rest on: the calibration's identity and its absolute scale K.
struct CalibrationIdentity {
  std::string origin;  // "inline", the manifest's path as written, or --calibration
  std::optional<std::string> file = std::nullopt;    // the file read, absolute (absent: inline)
  std::optional<std::string> sha256 = std::nullopt;  // of that file's bytes
  nlohmann::json camera = nullptr;  // the calibration's camera block (model, serial), or null
  nlohmann::json parts = nullptr;   // {name: {measured_at, method}}, or null
  // The calibration's values as used, in a short stable form: the first 16 hex digits of the
  // SHA-256 of the block's JSON with sorted keys. Equal for a file and its inline copy; what a
  // sweep compares to refuse mixing calibrations.
  std::string id = {};
  double luminance_factor = 0;                              // K
  std::optional<double> luminance_factor_u = std::nullopt;  // u(K), when the calibration has it
  bool noise_model_assumed = false;
  bool dark_frame = false;  // black subtracted pixel by pixel (else the black level)
  bool hot_pixels = false;  // the calibration's hot pixels masked out of the merge
};

struct ResultInputs {
  std::string stack_id;
  std::optional<double> alpha_deg;
  std::string alpha_source;  // "manifest", "given" (process --alpha), or empty: no α
  // The manifest's geometry.alpha_uncertainty_deg (inclinometer and clock), when α is its.
  std::optional<double> alpha_uncertainty_deg;
  nlohmann::json camera = nullptr;  // the manifest's camera block (backend, model, serial), or null
  std::optional<std::string> module;  // the manifest's module, when it names one
  int width = 0, height = 0;
  CalibrationIdentity calibration;
  LuminanceStats stats;
  std::vector<FrameCheck> frames;
  std::optional<double> limit_cd_m2;
  bool constant_limit = false;  // --threshold rather than the α curve
  GlareAnalysis glare;
};

nlohmann::json ellipseJson(const EllipseMeasurement& measurement);

nlohmann::json makeResult(const ResultInputs& inputs);

}  // namespace glarecam::pipeline
