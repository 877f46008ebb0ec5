#include "calibration/calibration_parts.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <span>
#include <utility>

#include "core/atomic_file.h"
#include "core/image_io.h"

namespace glarecam::calibration {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

fs::path directoryOf(const fs::path& file) {
  return file.parent_path().empty() ? fs::path(".") : file.parent_path();
}

// What every part has before its procedure: its options validated, the stacks and the values
// measured before read, the part's directory made.
struct Started {
  CalibrationInputs inputs;
  PriorCalibration prior;
};

template <typename PartOptions>
Result<Started> start(const PartOptions& options) {
  GLARECAM_CHECK(options.validate());
  const PartInputs& part = options.inputs;
  Started started;
  GLARECAM_ASSIGN(started.inputs, readCalibrationInputs(part.stacks, part.show_progress));
  GLARECAM_ASSIGN(started.prior, readPriorCalibration(part.calibrations, started.inputs));
  GLARECAM_CHECK(ensureDirectory(directoryOf(part.out)));
  return started;
}

// What a procedure hands to the shared end: its part's name, method and values.
struct Measurement {
  std::string part, method;
  json values;
  std::vector<std::string> warnings;
};

// The shared end: the warnings logged, the part written.
Result<PartReport> finish(const PartInputs& part, const CalibrationInputs& inputs,
                          Measurement measurement) {
  for (const std::string& warning : measurement.warnings)
    spdlog::warn("calibrate {}: {}", measurement.part, warning);
  PartReport report{.part = measurement.part,
                    .method = measurement.method,
                    .document = partDocument(inputs, measurement.part, measurement.method,
                                             std::move(measurement.values)),
                    .file = part.out,
                    .warnings = std::move(measurement.warnings)};
  GLARECAM_CHECK(writeCalibrationDocument(part.out, report.document));
  return report;
}

// The black level and saturation known before, and the region (default the central quarter) of
// a procedure measuring in a region.
struct LevelsInRegion {
  SensorLevels levels;
  Roi roi;
};

Result<LevelsInRegion> levelsInRegion(const std::optional<Roi>& roi,
                                      const CalibrationInputs& inputs,
                                      const PriorCalibration& prior, const std::string& procedure) {
  const RawFrame& first = inputs.frames.front().frame;
  const Roi region = roi.value_or(centralRoi(first.width(), first.height()));
  GLARECAM_CHECK(checkRoi(region, first.width(), first.height(), "--roi"));
  SensorLevels levels;
  GLARECAM_ASSIGN(levels, sensorLevels(prior, inputs, procedure));
  return LevelsInRegion{.levels = levels, .roi = region};
}

// The f-number K is stated at: the calibration's reference, else the frames' own.
std::optional<double> referenceFNumber(const PriorCalibration& prior,
                                       const CalibrationInputs& inputs) {
  return prior.reference_f_number ? prior.reference_f_number : inputs.frames.front().spec.f_number;
}

Result<std::optional<FloatImage>> priorFlat(const Calibration& calibration) {
  if (!calibration.flat_field) return std::optional<FloatImage>{};
  FloatImage flat;
  GLARECAM_ASSIGN(flat, readExr(*calibration.flat_field));
  return std::optional(std::move(flat));
}

// One board view a stack: its best exposed frame, as a float image.
std::vector<BoardView> boardViews(std::span<const InputFrame> frames, double saturation_dn) {
  std::vector<BoardView> views;
  for (std::size_t first = 0, end = 0; first < frames.size(); first = end) {
    end = first;
    while (end < frames.size() && frames[end].stack == frames[first].stack) ++end;
    const InputFrame& best =
        frames[first + bestExposedFrame(frames.subspan(first, end - first), saturation_dn)];
    FloatImage image(best.frame.width(), best.frame.height());
    std::copy(best.frame.data(), best.frame.data() + image.pixelCount(), image.data());
    views.push_back({.name = best.name, .image = std::move(image)});
  }
  return views;
}

}  // namespace

Status PartInputs::validate() const {
  if (out.empty()) return badInput("--out FILE is required: where the calibration part goes");
  if (out.filename().empty())
    return badInput(fmt::format("--out {}: expected a file name", out.string()));
  return {};
}

Status DarkPartOptions::validate() const { return inputs.validate(); }
Status FlatPartOptions::validate() const { return inputs.validate(); }
Status NoisePartOptions::validate() const { return inputs.validate(); }

Status LinearityPartOptions::validate() const {
  GLARECAM_CHECK(inputs.validate());
  return checkLinearityTolerance(tolerance_percent / 100);
}

Status LuminancePartOptions::validate() const {
  GLARECAM_CHECK(inputs.validate());
  return reference.validate();
}

Status IntrinsicsPartOptions::validate() const {
  GLARECAM_CHECK(inputs.validate());
  return board.validate();
}

namespace {

std::vector<std::string> darkWarnings(const DarkCalibration& dark) {
  if (auto warning = darkFrameNoiseWarning(dark)) return {std::move(*warning)};
  return {};
}

}  // namespace

Result<DarkPart> calibrateDarkPart(const DarkPartOptions& options) {
  Started started;
  GLARECAM_ASSIGN(started, start(options));
  const CalibrationInputs& inputs = started.inputs;
  DarkPart part;
  GLARECAM_ASSIGN(part.measured, calibrateDark(inputs.frames));
  const DarkCalibration& dark = part.measured;
  const fs::path dark_file = companionFile(options.inputs.out, "-dark.exr");
  const fs::path hot_file = companionFile(options.inputs.out, "-hot-pixels.png");
  GLARECAM_CHECK(writeExr(dark_file, dark.dark_frame_dn));
  RawFrame hot(dark.hot_pixels.width(), dark.hot_pixels.height());
  std::copy(dark.hot_pixels.data(), dark.hot_pixels.data() + hot.pixelCount(), hot.data());
  GLARECAM_CHECK(writePngGray(hot_file, hot, 8));
  GLARECAM_ASSIGN(
      part.report,
      finish(
          options.inputs, inputs,
          {.part = "dark",
           .method = fmt::format("{} dark frames at {} exposures, lens capped; black level = "
                                 "median of the per-pixel mean at the shortest",
                                 inputs.frames.size(), dark.levels.size()),
           .values = darkValues(dark, dark_file.filename().string(), hot_file.filename().string()),
           .warnings = darkWarnings(dark)}));
  return part;
}

Result<FlatPart> calibrateFlatPart(const FlatPartOptions& options) {
  Started started;
  GLARECAM_ASSIGN(started, start(options));
  const CalibrationInputs& inputs = started.inputs;
  SensorLevels levels;
  GLARECAM_ASSIGN(levels, sensorLevels(started.prior, inputs, "flat"));
  const RawFrame& first = inputs.frames.front().frame;
  const double cx = started.prior.principal_x_px.value_or((first.width() - 1) / 2.0);
  const double cy = started.prior.principal_y_px.value_or((first.height() - 1) / 2.0);
  FlatPart part;
  GLARECAM_ASSIGN(part.measured, calibrateFlat(inputs.frames, levels, cx, cy));
  const FlatCalibration& flat = part.measured;
  const fs::path flat_file = companionFile(options.inputs.out, "-flat.exr");
  GLARECAM_CHECK(writeExr(flat_file, flat.flat_field));
  GLARECAM_ASSIGN(
      part.report,
      finish(options.inputs, inputs,
             {.part = "flat",
              .method = fmt::format("{} frames of a uniform source, mean above black {:.0f} DN, "
                                    "normalised over {}x{} px at the principal point",
                                    flat.frames, flat.mean_signal_dn, kFlatNormalisationWindowPx,
                                    kFlatNormalisationWindowPx),
              .values = flatValues(flat, flat_file.filename().string()),
              .warnings = {}}));
  return part;
}

Result<LinearityPart> calibrateLinearityPart(const LinearityPartOptions& options) {
  Started started;
  GLARECAM_ASSIGN(started, start(options));
  LevelsInRegion known;
  GLARECAM_ASSIGN(known, levelsInRegion(options.roi, started.inputs, started.prior, "linearity"));
  LinearityPart part;
  GLARECAM_ASSIGN(part.measured,
                  calibrateLinearity(started.inputs.frames, known.levels.black_level_dn, known.roi,
                                     options.tolerance_percent / 100));
  const LinearityCalibration& linearity = part.measured;
  Measurement measurement{
      .part = "linearity",
      .method = fmt::format("ramp of {} exposures of a steady source, line through the origin "
                            "fitted on {:g}-{:g} % of the largest signal, tolerance {:g} %",
                            linearity.points.size(), 100 * kLinearFitLowFraction,
                            100 * kLinearFitHighFraction, options.tolerance_percent),
      .values = linearityValues(linearity),
      .warnings = {}};
  if (!linearity.bend_found) {
    measurement.warnings.push_back(fmt::format(
        "the ramp stayed within {:g} % up to its last point: saturation_dn {:.0f} is a lower "
        "bound; extend the ramp to longer exposures",
        options.tolerance_percent, linearity.saturation_dn));
  }
  GLARECAM_ASSIGN(part.report, finish(options.inputs, started.inputs, std::move(measurement)));
  return part;
}

Result<NoisePart> calibrateNoisePart(const NoisePartOptions& options) {
  Started started;
  GLARECAM_ASSIGN(started, start(options));
  LevelsInRegion known;
  GLARECAM_ASSIGN(known, levelsInRegion(options.roi, started.inputs, started.prior, "noise"));
  NoisePart part;
  GLARECAM_ASSIGN(part.measured, calibrateNoise(started.inputs.frames, known.levels, known.roi));
  GLARECAM_ASSIGN(
      part.report,
      finish(options.inputs, started.inputs,
             {.part = "noise",
              .method = fmt::format("photon transfer: {} pairs of a uniform source, var(a-b)/2 "
                                    "against the mean, weighted line fit",
                                    part.measured.points.size()),
              .values = noiseValues(part.measured),
              .warnings = {}}));
  return part;
}

Result<LuminanceCalibration> measureLuminance(CalibrationInputs& inputs,
                                              const PriorCalibration& prior,
                                              const std::optional<Roi>& roi,
                                              const LuminanceReference& reference) {
  LevelsInRegion known;
  GLARECAM_ASSIGN(known, levelsInRegion(roi, inputs, prior, "luminance"));
  Calibration calibration;
  GLARECAM_ASSIGN(calibration, mergeCalibration(prior, known.levels));
  if (!calibration.reference_f_number)
    calibration.reference_f_number = referenceFNumber(prior, inputs);
  std::optional<FloatImage> flat;
  GLARECAM_ASSIGN(flat, priorFlat(calibration));
  if (!flat)
    spdlog::warn("calibrate luminance: no flat field known: K is for the region's vignetting");
  if (!calibration.noise)
    spdlog::warn("calibrate luminance: no noise model known: the merge assumes a typical one");
  return calibrateLuminance(std::move(inputs.frames), calibration, flat ? &*flat : nullptr,
                            known.roi, reference);
}

Result<LuminancePart> calibrateLuminancePart(const LuminancePartOptions& options) {
  Started started;
  GLARECAM_ASSIGN(started, start(options));
  const std::optional<double> f_number = referenceFNumber(started.prior, started.inputs);
  LuminancePart part;
  GLARECAM_ASSIGN(part.measured,
                  measureLuminance(started.inputs, started.prior, options.roi, options.reference));
  const LuminanceCalibration& luminance = part.measured;
  GLARECAM_ASSIGN(part.report,
                  finish(options.inputs, started.inputs,
                         {.part = "luminance",
                          .method = fmt::format(
                              "reference surface of {:.6g} cd/m² ({} meter reading(s), "
                              "±{:g} %) over ROI {}, stack merged with K = 1",
                              luminance.reference_cd_m2, options.reference.readings_cd_m2.size(),
                              options.reference.meter_accuracy_percent, roiText(luminance.roi)),
                          .values = luminanceValues(luminance, f_number),
                          .warnings = {}}));
  return part;
}

Result<IntrinsicsPart> calibrateIntrinsicsPart(const IntrinsicsPartOptions& options) {
  Started started;
  GLARECAM_ASSIGN(started, start(options));
  const double saturation_dn = started.prior.saturation_dn.value_or(formatMaxDn(started.inputs));
  IntrinsicsPart part;
  GLARECAM_ASSIGN(part.measured,
                  calibrateIntrinsics(boardViews(started.inputs.frames, saturation_dn),
                                      options.board, {.fit_k3 = options.fit_k3}));
  const IntrinsicsCalibration& intrinsics = part.measured;
  const BoardSpec& board = options.board;
  GLARECAM_ASSIGN(
      part.report,
      finish(
          options.inputs, started.inputs,
          {.part = "intrinsics",
           .method = fmt::format(
               "{}x{} checkerboard, {:g} mm squares, {} views, OpenCV "
               "calibrateCamera{}; RMS reprojection {:.3f} px",
               board.inner_columns, board.inner_rows, board.square_mm, intrinsics.views_used.size(),
               options.fit_k3 ? "" : " (k3 fixed at 0)", intrinsics.rms_reprojection_px),
           .values = intrinsicsValues(intrinsics, board),
           .warnings = intrinsics.warnings}));
  return part;
}

Status MergePartsOptions::validate() const {
  if (out.empty()) return badInput("--out FILE is required");
  if (files.size() < 2) return badInput("calibrate merge: give two or more files");
  return {};
}

Result<MergedCalibration> mergeCalibrationParts(const MergePartsOptions& options) {
  GLARECAM_CHECK(options.validate());
  std::vector<CalibrationDocument> documents;
  for (const fs::path& file : options.files) {
    CalibrationDocument document;
    GLARECAM_ASSIGN(document, readCalibrationDocument(file));
    documents.push_back(std::move(document));
  }
  MergedCalibration merged{.document = {}, .file = options.out, .warnings = {}};
  GLARECAM_ASSIGN(merged.document,
                  mergeCalibrationDocuments(documents, options.files, merged.warnings));
  for (const std::string& warning : merged.warnings) spdlog::warn("calibrate merge: {}", warning);
  const fs::path directory = directoryOf(options.out);
  GLARECAM_CHECK(ensureDirectory(directory));
  GLARECAM_CHECK(attachFiles(merged.document, directory));
  GLARECAM_CHECK(writeCalibrationDocument(options.out, merged.document));
  if (const auto block = calibrationBlock(merged.document, options.out.string()); !block) {
    spdlog::warn("calibrate merge: {}", block.error().message);
    merged.warnings.push_back(block.error().message);
  }
  return merged;
}

}  // namespace glarecam::calibration
