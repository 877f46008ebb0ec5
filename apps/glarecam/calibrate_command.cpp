// glarecam calibrate dark|flat|linearity|noise|luminance|intrinsics|merge, and
// glarecam simulate-calibration: measured calibration parts as glarecam.calibration/1 files
// (docs/calibration.md). The procedures live in calibration/; this file parses options, reads
// the inputs, writes the part and its pictures.
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <memory>
#include <optional>
#include <string>
#include <thread>
#include <tuple>
#include <vector>

#include "apps/glarecam/commands.h"
#include "apps/glarecam/option_parsing.h"
#include "calibration/calibration_file.h"
#include "calibration/calibration_inputs.h"
#include "calibration/dark_calibration.h"
#include "calibration/flat_calibration.h"
#include "calibration/intrinsics_calibration.h"
#include "calibration/linearity_calibration.h"
#include "calibration/luminance_calibration.h"
#include "calibration/noise_calibration.h"
#include "calibration/prior_calibration.h"
#include "capture/bracketer.h"
#include "capture/camera_registry.h"
#include "capture/sim/calibration_targets.h"
#include "core/atomic_file.h"
#include "core/image_io.h"

namespace glarecam::apps {
namespace {

namespace fs = std::filesystem;
namespace cal = calibration;
using json = nlohmann::json;

// Frames one --camera capture may take (a photon transfer curve of 64 pairs, say).
constexpr std::size_t kMaxCapturedFrames = 256;

struct CalibrateArgs {
  std::vector<std::string> inputs;               // stacks (merge: calibration files)
  std::optional<std::string> camera, exposures;  // capture instead of reading stacks
  double gain_db = 0;
  int views = 1;                          // intrinsics: board poses to capture
  double view_interval_s = 10;            // ... this long apart (the operator moves the board)
  std::vector<std::string> calibrations;  // --calibration, merged in order
  std::optional<std::string> out, roi, log;
  bool json = false, no_progress = false, check = false, fit_k3 = false;
  std::vector<double> references_cd_m2;
  double meter_accuracy_percent = cal::kDefaultMeterAccuracyPercent;
  double tolerance_percent = 100 * cal::kDefaultLinearityTolerance;
  std::string board = "9x6";
  double square_mm = 25;
};

// What a procedure hands back: its part's name, method and values, and the files it wrote.
struct PartResult {
  std::string part, method;
  json values;
  std::vector<std::string> warnings;
};

// `inputs` is the procedure's to consume (luminance moves the frames into the merge).
using Procedure = std::function<Result<PartResult>(const CalibrateArgs&, cal::CalibrationInputs&,
                                                   const cal::PriorCalibration&)>;

cal::Roi roiOr(const std::optional<cal::Roi>& roi, const cal::CalibrationInputs& inputs) {
  const RawFrame& first = inputs.frames.front().frame;
  return roi.value_or(cal::centralRoi(first.width(), first.height()));
}

Result<std::optional<cal::Roi>> parsedRoi(const CalibrateArgs& args) {
  if (!args.roi) return std::optional<cal::Roi>{};
  cal::Roi roi;
  GLARECAM_ASSIGN(roi, cal::parseRoi(*args.roi, "--roi"));
  return std::optional(roi);
}

// The black level and saturation known before, and the region (--roi, else the central quarter)
// of a procedure measuring in a region.
struct LevelsInRegion {
  cal::SensorLevels levels;
  cal::Roi roi;
};

Result<LevelsInRegion> levelsInRegion(const CalibrateArgs& args,
                                      const cal::CalibrationInputs& inputs,
                                      const cal::PriorCalibration& prior,
                                      const std::string& procedure) {
  std::optional<cal::Roi> roi;
  GLARECAM_ASSIGN(roi, parsedRoi(args));
  const cal::Roi region = roiOr(roi, inputs);
  const RawFrame& first = inputs.frames.front().frame;
  GLARECAM_CHECK(cal::checkRoi(region, first.width(), first.height(), "--roi"));
  cal::SensorLevels levels;
  GLARECAM_ASSIGN(levels, cal::sensorLevels(prior, inputs, procedure));
  return LevelsInRegion{.levels = levels, .roi = region};
}

// ---- the procedures ---------------------------------------------------------------------------

Result<PartResult> runDark(const CalibrateArgs& args, const cal::CalibrationInputs& inputs,
                           const cal::PriorCalibration&) {
  cal::DarkCalibration dark;
  GLARECAM_ASSIGN(dark, cal::calibrateDark(inputs.frames));
  const fs::path out = *args.out;
  const fs::path dark_file = cal::companionFile(out, "-dark.exr");
  const fs::path hot_file = cal::companionFile(out, "-hot-pixels.png");
  GLARECAM_CHECK(writeExr(dark_file, dark.dark_frame_dn));
  RawFrame hot(dark.hot_pixels.width(), dark.hot_pixels.height());
  std::copy(dark.hot_pixels.data(), dark.hot_pixels.data() + hot.pixelCount(), hot.data());
  GLARECAM_CHECK(writePngGray(hot_file, hot, 8));
  return PartResult{
      .part = "dark",
      .method = fmt::format("{} dark frames at {} exposures, lens capped; black level = median "
                            "of the per-pixel mean at the shortest",
                            inputs.frames.size(), dark.levels.size()),
      .values = cal::darkValues(dark, dark_file.filename().string(), hot_file.filename().string()),
      .warnings = {}};
}

Result<PartResult> runFlat(const CalibrateArgs& args, const cal::CalibrationInputs& inputs,
                           const cal::PriorCalibration& prior) {
  cal::SensorLevels levels;
  GLARECAM_ASSIGN(levels, cal::sensorLevels(prior, inputs, "flat"));
  const RawFrame& first = inputs.frames.front().frame;
  const double cx = prior.principal_x_px.value_or((first.width() - 1) / 2.0);
  const double cy = prior.principal_y_px.value_or((first.height() - 1) / 2.0);
  cal::FlatCalibration flat;
  GLARECAM_ASSIGN(flat, cal::calibrateFlat(inputs.frames, levels, cx, cy));
  const fs::path flat_file = cal::companionFile(*args.out, "-flat.exr");
  GLARECAM_CHECK(writeExr(flat_file, flat.flat_field));
  return PartResult{
      .part = "flat",
      .method = fmt::format("{} frames of a uniform source, mean above black {:.0f} DN, "
                            "normalised over {}x{} px at the principal point",
                            flat.frames, flat.mean_signal_dn, cal::kFlatNormalisationWindowPx,
                            cal::kFlatNormalisationWindowPx),
      .values = cal::flatValues(flat, flat_file.filename().string()),
      .warnings = {}};
}

Result<PartResult> runLinearity(const CalibrateArgs& args, const cal::CalibrationInputs& inputs,
                                const cal::PriorCalibration& prior) {
  LevelsInRegion known;
  GLARECAM_ASSIGN(known, levelsInRegion(args, inputs, prior, "linearity"));
  cal::LinearityCalibration linearity;
  GLARECAM_ASSIGN(linearity, cal::calibrateLinearity(inputs.frames, known.levels.black_level_dn,
                                                     known.roi, args.tolerance_percent / 100));
  PartResult result{
      .part = "linearity",
      .method = fmt::format("ramp of {} exposures of a steady source, line through the origin "
                            "fitted on {:g}-{:g} % of the largest signal, tolerance {:g} %",
                            linearity.points.size(), 100 * cal::kLinearFitLowFraction,
                            100 * cal::kLinearFitHighFraction, args.tolerance_percent),
      .values = cal::linearityValues(linearity),
      .warnings = {}};
  if (!linearity.bend_found) {
    result.warnings.push_back(fmt::format(
        "the ramp stayed within {:g} % up to its last point: saturation_dn {:.0f} is a lower "
        "bound; extend the ramp to longer exposures",
        args.tolerance_percent, linearity.saturation_dn));
  }
  return result;
}

Result<PartResult> runNoise(const CalibrateArgs& args, const cal::CalibrationInputs& inputs,
                            const cal::PriorCalibration& prior) {
  LevelsInRegion known;
  GLARECAM_ASSIGN(known, levelsInRegion(args, inputs, prior, "noise"));
  cal::NoiseCalibration noise;
  GLARECAM_ASSIGN(noise, cal::calibrateNoise(inputs.frames, known.levels, known.roi));
  return PartResult{
      .part = "noise",
      .method = fmt::format("photon transfer: {} pairs of a uniform source, var(a-b)/2 against "
                            "the mean, weighted line fit",
                            noise.points.size()),
      .values = cal::noiseValues(noise),
      .warnings = {}};
}

Result<std::optional<FloatImage>> priorFlat(const Calibration& calibration) {
  if (!calibration.flat_field) return std::optional<FloatImage>{};
  FloatImage flat;
  GLARECAM_ASSIGN(flat, readExr(*calibration.flat_field));
  return std::optional(std::move(flat));
}

// The frames' common f-number: K is stated at it.
std::optional<double> framesFNumber(const cal::CalibrationInputs& inputs,
                                    const cal::PriorCalibration& prior) {
  return prior.reference_f_number ? prior.reference_f_number : inputs.frames.front().spec.f_number;
}

// The frames are moved out of `inputs` into the merge.
Result<cal::LuminanceCalibration> measureLuminance(const CalibrateArgs& args,
                                                   cal::CalibrationInputs& inputs,
                                                   const cal::PriorCalibration& prior) {
  LevelsInRegion known;
  GLARECAM_ASSIGN(known, levelsInRegion(args, inputs, prior, "luminance"));
  Calibration calibration;
  GLARECAM_ASSIGN(calibration, cal::mergeCalibration(prior, known.levels));
  if (!calibration.reference_f_number)
    calibration.reference_f_number = framesFNumber(inputs, prior);
  std::optional<FloatImage> flat;
  GLARECAM_ASSIGN(flat, priorFlat(calibration));
  if (!flat)
    spdlog::warn("calibrate luminance: no flat field known: K is for the region's vignetting");
  if (!calibration.noise)
    spdlog::warn("calibrate luminance: no noise model known: the merge assumes a typical one");
  return cal::calibrateLuminance(std::move(inputs.frames), calibration, flat ? &*flat : nullptr,
                                 known.roi,
                                 {.readings_cd_m2 = args.references_cd_m2,
                                  .meter_accuracy_percent = args.meter_accuracy_percent});
}

Result<PartResult> runLuminance(const CalibrateArgs& args, cal::CalibrationInputs& inputs,
                                const cal::PriorCalibration& prior) {
  const std::optional<double> f_number = framesFNumber(inputs, prior);
  cal::LuminanceCalibration luminance;
  GLARECAM_ASSIGN(luminance, measureLuminance(args, inputs, prior));
  return PartResult{
      .part = "luminance",
      .method = fmt::format("reference surface of {:.6g} cd/m² ({} meter reading(s), ±{:g} %) "
                            "over ROI {}, stack merged with K = 1",
                            luminance.reference_cd_m2, args.references_cd_m2.size(),
                            args.meter_accuracy_percent, cal::roiText(luminance.roi)),
      .values = cal::luminanceValues(luminance, f_number),
      .warnings = {}};
}

Result<cal::BoardSpec> parseBoard(const CalibrateArgs& args) {
  std::pair<int, int> size;
  GLARECAM_ASSIGN(size, parseSize(args.board, "--board"));
  return cal::BoardSpec{
      .inner_columns = size.first, .inner_rows = size.second, .square_mm = args.square_mm};
}

Result<PartResult> runIntrinsics(const CalibrateArgs& args, cal::CalibrationInputs& inputs,
                                 const cal::PriorCalibration& prior) {
  cal::BoardSpec board;
  GLARECAM_ASSIGN(board, parseBoard(args));
  const double saturation = prior.saturation_dn.value_or(cal::formatMaxDn(inputs));
  std::vector<cal::BoardView> views;
  const std::span<const cal::InputFrame> frames = inputs.frames;
  for (std::size_t first = 0, end = 0; first < frames.size(); first = end) {  // one view a stack
    end = first;
    while (end < frames.size() && frames[end].stack == frames[first].stack) ++end;
    const cal::InputFrame& best =
        frames[first + cal::bestExposedFrame(frames.subspan(first, end - first), saturation)];
    FloatImage image(best.frame.width(), best.frame.height());
    std::copy(best.frame.data(), best.frame.data() + image.pixelCount(), image.data());
    views.push_back({.name = best.name, .image = std::move(image)});
  }
  cal::IntrinsicsCalibration intrinsics;
  GLARECAM_ASSIGN(intrinsics, cal::calibrateIntrinsics(views, board, {.fit_k3 = args.fit_k3}));
  return PartResult{
      .part = "intrinsics",
      .method = fmt::format("{}x{} checkerboard, {:g} mm squares, {} views, OpenCV "
                            "calibrateCamera{}; RMS reprojection {:.3f} px",
                            board.inner_columns, board.inner_rows, board.square_mm,
                            intrinsics.views_used.size(), args.fit_k3 ? "" : " (k3 fixed at 0)",
                            intrinsics.rms_reprojection_px),
      .values = cal::intrinsicsValues(intrinsics, board),
      .warnings = intrinsics.warnings};
}

// ---- the shared flow ------------------------------------------------------------------------

void printPart(const cal::CalibrationDocument& document, const PartResult& part, bool as_json,
               const fs::path& out) {
  if (as_json) {
    std::printf("%s", jsonText(cal::toJson(document)).c_str());
    return;
  }
  std::printf("%s: %s\n", part.part.c_str(), part.method.c_str());
  for (const auto& [key, value] : part.values.items()) {
    if (value.is_object() || value.is_array()) continue;
    std::printf("  %s = %s\n", key.c_str(), value.dump().c_str());
  }
  std::printf("%s\n", out.c_str());
}

// --camera: captures the stacks (one per view), writes them beside --out as <out>-stacks/<id>
// (the part's provenance names them) and returns their paths.
Result<std::vector<std::string>> captureInputs(const CalibrateArgs& args) {
  if (!args.exposures)
    return badInput("--camera needs --exposures LIST (µs; repeat a value for several frames)");
  std::vector<double> exposures;
  GLARECAM_ASSIGN(exposures,
                  parseNumberList(*args.exposures, "--exposures", 1, kMaxCapturedFrames));
  if (args.views < 1) return badInput("--views must be at least 1");
  if (!(args.view_interval_s >= 0 && args.view_interval_s <= 3600))
    return badInput("--view-interval must be between 0 and 3600 s");
  std::unique_ptr<capture::Camera> camera;
  GLARECAM_ASSIGN(camera, capture::openCamera(*args.camera, {}));
  const fs::path directory = cal::companionFile(*args.out, "-stacks");
  std::vector<std::string> paths;
  for (int view = 0; view < args.views; ++view) {
    if (view > 0) {
      spdlog::info("calibrate: view {} of {} in {:g} s: move the board", view + 1, args.views,
                   args.view_interval_s);
      std::this_thread::sleep_for(std::chrono::duration<double>(args.view_interval_s));
    }
    capture::CaptureSettings settings;
    settings.exposures_us = exposures;
    settings.gain_db = args.gain_db;
    settings.show_progress = !args.no_progress;
    capture::CapturedStack stack;
    GLARECAM_ASSIGN(stack, capture::captureStack(*camera, settings));
    fs::path path;
    GLARECAM_ASSIGN(path, capture::writeCapturedStack(directory, stack));
    paths.push_back(path.string());
  }
  return paths;
}

Status runProcedure(const CalibrateArgs& given, const Procedure& procedure) {
  GLARECAM_CHECK(requireNonEmptyPath(given.out, "--out"));
  if (!given.out) return badInput("--out FILE is required: where the calibration part goes");
  if (fs::path(*given.out).filename().empty())
    return badInput(fmt::format("--out {}: expected a file name", *given.out));
  if (given.camera.has_value() == !given.inputs.empty())
    return badInput("give the calibration stacks (STACK...) or --camera URI to capture them");
  CalibrateArgs args = given;
  if (args.camera) GLARECAM_ASSIGN(args.inputs, captureInputs(args));
  cal::CalibrationInputs inputs;
  GLARECAM_ASSIGN(inputs, cal::readCalibrationInputs(args.inputs, !args.no_progress));
  cal::PriorCalibration prior;
  GLARECAM_ASSIGN(prior, cal::readPriorCalibration(args.calibrations, inputs));
  GLARECAM_CHECK(ensureDirectory(fs::path(*args.out).parent_path().empty()
                                     ? fs::path(".")
                                     : fs::path(*args.out).parent_path()));
  PartResult part;
  GLARECAM_ASSIGN(part, procedure(args, inputs, prior));
  for (const std::string& warning : part.warnings)
    spdlog::warn("calibrate {}: {}", part.part, warning);
  const cal::CalibrationDocument document =
      cal::partDocument(inputs, part.part, part.method, part.values);
  GLARECAM_CHECK(cal::writeCalibrationDocument(*args.out, document));
  printPart(document, part, args.json, *args.out);
  return {};
}

// calibrate luminance --check: K measured on an in-scene reference against the calibration's.
Status runLuminanceCheck(const CalibrateArgs& args) {
  if (args.calibrations.empty())
    return badInput(
        "calibrate luminance --check: give the calibration to check with --calibration");
  if (args.camera || args.inputs.empty())
    return badInput("calibrate luminance --check: give the recorded field stack(s) to check");
  if (!args.roi)
    return badInput("calibrate luminance --check: give the reference patch's region with --roi");
  cal::CalibrationInputs inputs;
  GLARECAM_ASSIGN(inputs, cal::readCalibrationInputs(args.inputs, !args.no_progress));
  cal::PriorCalibration prior;
  GLARECAM_ASSIGN(prior, cal::readPriorCalibration(args.calibrations, inputs));
  if (!prior.luminance_factor)
    return badInput("calibrate luminance --check: the calibration has no luminance_factor");
  cal::LuminanceCalibration measured;
  GLARECAM_ASSIGN(measured, measureLuminance(args, inputs, prior));
  const double k = *prior.luminance_factor;
  const double drift = measured.luminance_factor / k - 1;
  // Both Ks are uncertain: the check's own budget and the calibration's u(K), in quadrature.
  const double u_k = prior.luminance_factor_u.value_or(0.0) / k;
  const double u = std::hypot(measured.relative.combined(), u_k);
  const json report = {{"stacks", inputs.stack_paths},
                       {"captured_at", inputs.latest_capture},
                       {"luminance_factor", k},
                       {"measured_luminance_factor", measured.luminance_factor},
                       {"drift", drift},
                       {"drift_u", u}};
  if (args.log) {
    std::string text;
    if (fs::exists(*args.log)) {
      std::ifstream in(*args.log);
      text.assign(std::istreambuf_iterator<char>(in), {});
    } else {
      text = "captured_at,stack,luminance_factor,measured_luminance_factor,drift,drift_u\n";
    }
    text += fmt::format("{},{},{:.8g},{:.8g},{:.6f},{:.6f}\n", inputs.latest_capture,
                        inputs.stack_paths.front(), k, measured.luminance_factor, drift, u);
    GLARECAM_CHECK(writeFileAtomic(*args.log, text));
  }
  if (args.json) {
    std::printf("%s", jsonText(report).c_str());
  } else {
    std::printf("K %.6g, measured %.6g: drift %+.2f %% (u %.2f %%)\n", k, measured.luminance_factor,
                100 * drift, 100 * u);
  }
  if (std::abs(drift) > 2 * u)
    spdlog::warn(
        "calibrate luminance --check: the drift exceeds twice its uncertainty: "
        "recalibrate K (docs/calibration.md)");
  return {};
}

Status runMerge(const CalibrateArgs& args) {
  GLARECAM_CHECK(requireNonEmptyPath(args.out, "--out"));
  if (!args.out) return badInput("--out FILE is required");
  if (args.inputs.size() < 2) return badInput("calibrate merge: give two or more files");
  std::vector<cal::CalibrationDocument> documents;
  std::vector<fs::path> files;
  for (const std::string& file : args.inputs) {
    cal::CalibrationDocument document;
    GLARECAM_ASSIGN(document, cal::readCalibrationDocument(file));
    documents.push_back(std::move(document));
    files.push_back(fs::path(file));
  }
  std::vector<std::string> warnings;
  cal::CalibrationDocument merged;
  GLARECAM_ASSIGN(merged, cal::mergeCalibrationDocuments(documents, files, warnings));
  for (const std::string& warning : warnings) spdlog::warn("calibrate merge: {}", warning);
  const fs::path out = *args.out;
  const fs::path directory = out.parent_path().empty() ? fs::path(".") : out.parent_path();
  GLARECAM_CHECK(ensureDirectory(directory));
  GLARECAM_CHECK(cal::attachFiles(merged, directory));
  GLARECAM_CHECK(cal::writeCalibrationDocument(out, merged));
  if (const auto block = cal::calibrationBlock(merged, out.string()); !block)
    spdlog::warn("calibrate merge: {}", block.error().message);
  if (args.json) {
    std::printf("%s", jsonText(cal::toJson(merged)).c_str());
  } else {
    std::printf("%s\n", out.c_str());
  }
  return {};
}

// ---- options ----------------------------------------------------------------------------------

void addCommonOptions(CLI::App* sub, CalibrateArgs& args, bool reads_prior) {
  sub->add_option("STACK", args.inputs, "calibration stacks (glarecam.stack/1)");
  sub->add_option("--camera", args.camera,
                  "capture the stack with this camera instead (saved as <out>-stacks/)");
  sub->add_option("--exposures", args.exposures,
                  "with --camera: exposures in µs, comma-separated; repeat a value for several "
                  "frames (e.g. 1000,1000,10000,10000)");
  sub->add_option("--gain-db", args.gain_db, "with --camera: analogue gain (default 0)");
  sub->add_option("--out", args.out,
                  "the part's glarecam.calibration/1 file (its images go beside it)");
  if (reads_prior) {
    sub->add_option("--calibration", args.calibrations,
                    "earlier parts (black level, saturation, ...), repeatable, merged in order; "
                    "default: the stack's calibration block")
        ->expected(1)
        ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  }
  sub->add_flag("--json", args.json, "print the written file on stdout");
  sub->add_flag("--no-progress", args.no_progress, "no progress on stderr");
}

CLI::App* addProcedure(CLI::App* calibrate, Action& action, const std::string& name,
                       const std::string& help, bool reads_prior, Procedure procedure,
                       std::shared_ptr<CalibrateArgs> args) {
  CLI::App* sub = calibrate->add_subcommand(name, help);
  addCommonOptions(sub, *args, reads_prior);
  sub->callback([args, procedure, &action] {
    action = [args, procedure] { return runProcedure(*args, procedure); };
  });
  return sub;
}

void addRoiOption(CLI::App* sub, CalibrateArgs& args) {
  sub->add_option("--roi", args.roi, "region x,y,w,h in pixels (default: the central quarter)");
}

}  // namespace

void addCalibrateCommand(CLI::App& app, Action& action) {
  CLI::App* calibrate = app.add_subcommand(
      "calibrate", "Measure the camera's calibration, part by part (docs/calibration.md)");
  calibrate->require_subcommand(1);

  addProcedure(calibrate, action, "dark",
               "dark frames (lens capped) -> black level, dark frame, hot-pixel map", false,
               runDark, std::make_shared<CalibrateArgs>());

  addProcedure(calibrate, action, "flat",
               "frames of a uniform source -> flat field, 1 at the principal point", true, runFlat,
               std::make_shared<CalibrateArgs>());

  auto linearity = std::make_shared<CalibrateArgs>();
  CLI::App* linearity_sub =
      addProcedure(calibrate, action, "linearity",
                   "a ramp of exposures of a steady source -> deviation from linear, usable range, "
                   "saturation_dn",
                   true, runLinearity, linearity);
  addRoiOption(linearity_sub, *linearity);
  linearity_sub->add_option("--tolerance-percent", linearity->tolerance_percent,
                            "deviation from linear that ends the usable range (default 1)");

  auto noise = std::make_shared<CalibrateArgs>();
  addRoiOption(addProcedure(calibrate, action, "noise",
                            "pairs of flat frames at several exposures -> read noise and DN per "
                            "electron (photon transfer curve)",
                            true, runNoise, noise),
               *noise);

  auto luminance = std::make_shared<CalibrateArgs>();
  CLI::App* luminance_sub = calibrate->add_subcommand(
      "luminance",
      "a stack of a reference surface measured with a luminance meter -> K with its "
      "uncertainty; --check: an in-scene reference against an existing K (drift)");
  addCommonOptions(luminance_sub, *luminance, true);
  addRoiOption(luminance_sub, *luminance);
  luminance_sub
      ->add_option("--reference", luminance->references_cd_m2,
                   "the meter's reading in cd/m²; repeat for several readings")
      ->required()
      ->expected(1)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  luminance_sub->add_option("--meter-accuracy", luminance->meter_accuracy_percent,
                            "the meter's stated accuracy, ± percent (default 2)");
  luminance_sub->add_flag("--check", luminance->check,
                          "check the --calibration's K for drift instead of writing a part");
  luminance_sub->add_option("--log", luminance->log,
                            "with --check: CSV file the check's line is appended to");
  luminance_sub->callback([luminance, &action] {
    action = [luminance] {
      return luminance->check ? runLuminanceCheck(*luminance)
                              : runProcedure(*luminance, runLuminance);
    };
  });

  auto intrinsics = std::make_shared<CalibrateArgs>();
  CLI::App* intrinsics_sub = addProcedure(
      calibrate, action, "intrinsics",
      "checkerboard views (one stack each) -> fx, fy, cx, cy, distortion (OpenCV calib3d)", true,
      runIntrinsics, intrinsics);
  intrinsics_sub->add_option("--board", intrinsics->board,
                             "inner corners across x down (default 9x6)");
  intrinsics_sub->add_option("--square-mm", intrinsics->square_mm,
                             "side of a square in mm (default 25)");
  intrinsics_sub->add_flag("--fit-k3", intrinsics->fit_k3,
                           "fit k3 too (wide-angle lenses; needs many views)");
  intrinsics_sub->add_option("--views", intrinsics->views,
                             "with --camera: board poses to capture (default 1)");
  intrinsics_sub->add_option(
      "--view-interval", intrinsics->view_interval_s,
      "with --camera: seconds between poses, to move the board (default 10)");

  auto merge = std::make_shared<CalibrateArgs>();
  CLI::App* merge_sub = calibrate->add_subcommand(
      "merge", "combine calibration parts into one file (later files win)");
  merge_sub->add_option("FILE", merge->inputs, "glarecam.calibration/1 files")->required();
  merge_sub->add_option("--out", merge->out, "the combined file (its images are copied beside it)");
  merge_sub->add_flag("--json", merge->json, "print the written file on stdout");
  merge_sub->callback([merge, &action] { action = [merge] { return runMerge(*merge); }; });
}

// ---- simulate-calibration -----------------------------------------------------------------

namespace {

struct SimulateTargetArgs {
  std::string target, out, seed = "1";
  std::optional<std::string> size;
};

Status runSimulateTarget(const SimulateTargetArgs& args) {
  capture::CalibrationTargetOptions options;
  GLARECAM_ASSIGN(options.target, capture::parseCalibrationTarget(args.target));
  if (options.target == capture::CalibrationTarget::kBoard) {
    options.width = 640;  // corners need room: 9x6 inner corners over a third of the width
    options.height = 480;
  }
  if (args.size) {
    std::pair<int, int> size;
    GLARECAM_ASSIGN(size, parseSize(*args.size, "--size"));
    std::tie(options.width, options.height) = size;
  }
  GLARECAM_ASSIGN(options.seed, parseUnsigned(args.seed, "--seed"));
  if (args.out.empty()) return badInput("--out: expected a directory");
  std::vector<capture::CalibrationTargetStack> stacks;
  GLARECAM_ASSIGN(stacks, capture::simulateCalibrationTarget(options));
  std::vector<fs::path> written;
  GLARECAM_ASSIGN(written, capture::writeCalibrationTargetStacks(args.out, options.target, stacks));
  for (const fs::path& path : written) std::printf("%s\n", path.c_str());
  return {};
}

}  // namespace

void addSimulateCalibrationCommand(CLI::App& app, Action& action) {
  auto args = std::make_shared<SimulateTargetArgs>();
  CLI::App* sub =
      app.add_subcommand("simulate-calibration",
                         "Write calibration target stacks of the simulated camera, with truth.json "
                         "(docs/calibration.md)");
  sub->add_option("TARGET", args->target, "dark, flat, linearity, noise, luminance or board")
      ->required();
  sub->add_option("--out", args->out, "directory the stacks go into")->required();
  sub->add_option("--size", args->size, "WxH (default 320x256; board 640x480)");
  sub->add_option("--seed", args->seed, "noise seed (default 1)");
  sub->callback([args, &action] { action = [args] { return runSimulateTarget(*args); }; });
}

}  // namespace glarecam::apps
