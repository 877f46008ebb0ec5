// Measuring one part of a camera's calibration end to end, as `glarecam calibrate PART` does
// (docs/calibration.md): read the stacks (calibration_inputs.h) and what earlier parts measured
// (prior_calibration.h), run the part's procedure (dark_calibration.h, flat_calibration.h, ...),
// write its images beside the part's file and the part as a glarecam.calibration/1 document with
// its provenance. Each part takes its Options (validate()) and returns what it measured with the
// part as written; warnings are logged (and returned). `calibrate merge` combines the parts into
// one file (mergeCalibrationParts).
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "calibration/calibration_file.h"
#include "calibration/calibration_inputs.h"
#include "calibration/dark_calibration.h"
#include "calibration/flat_calibration.h"
#include "calibration/frame_statistics.h"
#include "calibration/intrinsics_calibration.h"
#include "calibration/linearity_calibration.h"
#include "calibration/luminance_calibration.h"
#include "calibration/noise_calibration.h"
#include "calibration/prior_calibration.h"
#include "core/error.h"

namespace glarecam::calibration {

// What every part starts from.
struct PartInputs {
  std::vector<std::string> stacks;        // glarecam.stack/1 directories, as the provenance names
  std::vector<std::string> calibrations;  // earlier parts, merged in order (prior_calibration.h)
  std::filesystem::path out;              // the part's file; its images go beside it
  bool show_progress = false;             // while reading the stacks, on stderr
  Status validate() const;  // `out` names a file (the stacks are checked as they are read)
};

// The part as written.
struct PartReport {
  std::string part;              // "dark", "flat", ...
  std::string method;            // how, in one line
  CalibrationDocument document;  // as written to `file`
  std::filesystem::path file;
  std::vector<std::string> warnings;  // logged as well
};

template <typename Measured>
struct MeasuredPart {
  Measured measured;
  PartReport report;
};

// Dark frames (lens capped) -> black level, dark frame (<out>-dark.exr), hot-pixel map
// (<out>-hot-pixels.png). Needs no earlier part.
struct DarkPartOptions {
  PartInputs inputs;
  Status validate() const;
};
using DarkPart = MeasuredPart<DarkCalibration>;
Result<DarkPart> calibrateDarkPart(const DarkPartOptions& options);

// Frames of a uniform source -> flat field (<out>-flat.exr), normalised at the intrinsics'
// principal point when known, else the image centre. Needs the black level.
struct FlatPartOptions {
  PartInputs inputs;
  Status validate() const;
};
using FlatPart = MeasuredPart<FlatCalibration>;
Result<FlatPart> calibrateFlatPart(const FlatPartOptions& options);

// A ramp of exposures -> deviation from linear, usable range, saturation_dn. Needs the black
// level; warns when the ramp never bends (saturation_dn is then a lower bound).
struct LinearityPartOptions {
  PartInputs inputs;
  std::optional<Roi> roi = std::nullopt;  // default: the central quarter
  double tolerance_percent = 100 * kDefaultLinearityTolerance;
  Status validate() const;
};
using LinearityPart = MeasuredPart<LinearityCalibration>;
Result<LinearityPart> calibrateLinearityPart(const LinearityPartOptions& options);

// Pairs of flat frames at several exposures -> read noise and DN per electron. Needs the black
// level.
struct NoisePartOptions {
  PartInputs inputs;
  std::optional<Roi> roi = std::nullopt;  // default: the central quarter
  Status validate() const;
};
using NoisePart = MeasuredPart<NoiseCalibration>;
Result<NoisePart> calibrateNoisePart(const NoisePartOptions& options);

// A stack of a reference surface the meter measured -> K with its uncertainty. Needs the black
// level; uses the flat field and noise model when known (warns when not).
struct LuminancePartOptions {
  PartInputs inputs;
  std::optional<Roi> roi = std::nullopt;  // the region the meter saw; default: the central quarter
  LuminanceReference reference;
  Status validate() const;
};
using LuminancePart = MeasuredPart<LuminanceCalibration>;
Result<LuminancePart> calibrateLuminancePart(const LuminancePartOptions& options);

// Checkerboard views, one stack each (its best exposed frame) -> intrinsics and distortion.
struct IntrinsicsPartOptions {
  PartInputs inputs;
  BoardSpec board;
  bool fit_k3 = false;
  Status validate() const;
};
using IntrinsicsPart = MeasuredPart<IntrinsicsCalibration>;
Result<IntrinsicsPart> calibrateIntrinsicsPart(const IntrinsicsPartOptions& options);

// The K measurement of the luminance part, which the drift check (luminance_drift.h) repeats on
// a field stack's reference patch: the frames merged with K = 1 with the prior's levels, noise
// model, reference f-number and flat field, over `roi` (default: the central quarter). The
// frames are moved out of `inputs` into the merge.
Result<LuminanceCalibration> measureLuminance(CalibrationInputs& inputs,
                                              const PriorCalibration& prior,
                                              const std::optional<Roi>& roi,
                                              const LuminanceReference& reference);

struct MergePartsOptions {
  std::vector<std::filesystem::path> files;  // glarecam.calibration/1 files; later ones win
  std::filesystem::path out;  // the combined file; the images it references are copied beside it
  Status validate() const;    // `out` given, two or more files
};

struct MergedCalibration {
  CalibrationDocument document;  // as written to `file`
  std::filesystem::path file;
  // Each replaced value or part, and what a stack's calibration still lacks; logged as well.
  std::vector<std::string> warnings;
};

Result<MergedCalibration> mergeCalibrationParts(const MergePartsOptions& options);

}  // namespace glarecam::calibration
