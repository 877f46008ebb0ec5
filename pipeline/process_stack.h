// `glarecam process`: one recorded stack -> calibrated luminance image and result.
// Reads the stack (stack_io.h), merges it (hdr_merge.h), summarises it, and writes into the
// output directory (default STACK/result/): luminance.exr (float cd/m², channel Y),
// quality.exr (relative uncertainty, valid frame count, bound flags), luminance.png (false
// colour with the glare ellipses drawn over it) and result.json (glarecam.result/1, with the
// limit, FWHM and threshold ellipses of glare_analysis.h), each file atomically, result.json last.
// A stack with a source illuminance E (its manifest's `source`, or given) is referred to the
// reference E_ref before the analysis: every luminance written, luminance.exr included, is
// L · E_ref / E (docs/method.md "Reference illuminance"); one without is processed at face value
// and marked unreferred.
#pragma once

#include <filesystem>
#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "calibration/calibration_file.h"
#include "calibration/camera_model.h"
#include "calibration/hdr_merge.h"
#include "core/error.h"
#include "core/progress.h"
#include "core/source_illuminance.h"
#include "pipeline/result.h"

namespace glarecam::pipeline {

struct ProcessOptions {
  std::optional<std::filesystem::path> calibration_file;  // overrides the stack's calibration
  std::optional<std::filesystem::path> output_directory;  // default: STACK/result
  // A constant glare limit instead of the α curve (the method's 30 000 cd/m² mode).
  std::optional<double> threshold_cd_m2;
  std::vector<double> thresholds_cd_m2;  // extra ellipses, one per level (threshold sweep)
  // The contour ladder (glare_analysis.h) in result.json's `contours` and the picture; off:
  // `--no-ladder`, `contours` null.
  bool ladder = true;
  // α for a stack whose manifest records none (another tool's, a rig without an inclinometer),
  // recorded in result.json as given by the user; one that contradicts the manifest's is refused.
  std::optional<double> alpha_deg = std::nullopt;
  // The source illuminance E for the stack (--source-illuminance, origin given): replaces the
  // manifest's `source`, with a warning when that records another value. Without either the
  // result is unreferred.
  std::optional<SourceIlluminance> source_illuminance = std::nullopt;
  // The estimate for a stack that records no source and is given none (`--source-illuminance
  // clear-sky`: sun::clearSkySourceOfStack), origin clear_sky; its error (no sun recorded) is
  // the process's.
  std::function<Result<SourceIlluminance>(const StackManifest&)> estimate_source = nullptr;
  // E_ref: the luminance image is referred to it (L · E_ref / E) before the glare analysis.
  double reference_illuminance_lx = kDefaultReferenceIlluminanceLx;
  unsigned threads = 0;  // 0: all cores
  bool show_progress = true;
  // The images at full float32 precision, losslessly (larger); by default luminance.exr keeps 24
  // bits a value (relative 1.5e-5) and quality.exr stores the uncertainty as half
  // (docs/process.md).
  bool float32 = false;
  // Whose and how old a calibration may be (a serial mismatch refuses, old parts warn).
  calibration::CalibrationUseOptions calibration_use;
  // Thresholds positive and finite, at most kMaxThresholds; the illuminances in range.
  Status validate() const;
};

// The result document `process` writes into its output directory (glarecam.result/1).
inline constexpr const char* kResultFileName = "result.json";

inline constexpr std::size_t kMaxThresholds = 32;

struct ProcessSummary {
  std::filesystem::path output_directory;
  StackResult result;
  std::string briefReport() const;  // one line for logs
};

// The files of an analysed luminance image, as `process` writes them into `directory` (made when
// missing): luminance.exr, quality.exr, luminance.png (false colour with `glare`'s ellipses,
// captioned from `result`) and result.json last, each atomically. `glarecam brdf` writes its
// pictures through it too.
Status writeResultFiles(const std::filesystem::path& directory,
                        const calibration::MergedImage& merged,
                        const calibration::CameraModel& camera, const GlareAnalysis& glare,
                        const LuminancePeak& peak, const StackResult& result, bool float32,
                        Progress& progress);
// The steps writeResultFiles() advances a Progress by.
inline constexpr int kResultFileSteps = 4;

Result<ProcessSummary> processStack(const std::filesystem::path& stack_directory,
                                    const ProcessOptions& options = {});

}  // namespace glarecam::pipeline
