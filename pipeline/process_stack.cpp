#include "pipeline/process_stack.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <functional>

#include "calibration/frame_consistency.h"
#include "calibration/hdr_merge.h"
#include "core/atomic_file.h"
#include "core/image_io.h"
#include "core/json.h"
#include "core/parallel.h"
#include "core/progress.h"
#include "core/sha256.h"
#include "core/stack_io.h"
#include "core/stack_manifest.h"
#include "pipeline/false_colour_picture.h"
#include "pipeline/glare_analysis.h"
#include "pipeline/glare_picture.h"
#include "pipeline/limit_curve.h"
#include "pipeline/luminance_stats.h"
#include "pipeline/result.h"
#include "render/number_format.h"

namespace glarecam::pipeline {
namespace fs = std::filesystem;

namespace {

constexpr int kProcessSteps = 7;

// luminance.exr and quality.exr at their price (docs/process.md, "Output encodings"; measured on
// simulated 1.25 and 5 MP stacks). HALF cannot hold luminance (magnitudes above 65504 cd/m², every
// glare peak, become infinite), and noisy float32 barely compresses: 17.0 MB at 5 MP with PIZ,
// 20.2 raw. Rounded to 24 bits (relative 1.5e-5, far below any calibration's uncertainty) it
// halves: PXR24 did that in 814 ms for 9.68 MB, the same rounding with PIZ takes 127 ms for
// 9.62 MB (ZIP through libdeflate: as fast or slower, 12.5 MB). The uncertainty, relative and of
// order 0.001–1, is HALF (relative 4.9e-4 of itself) and the counts and flags UINT, straight from
// their bytes, ZIP through libdeflate: 4.02 MB in 160 ms at 5 MP against PIZ's 4.53 MB in 300 ms.
// --float32: every channel lossless float32 with ZIP (PIZ takes 1.2 s for unrounded float32 at
// 5 MP).
Status writeLuminanceExr(const fs::path& path, const calibration::MergedImage& merged,
                         bool float32) {
  const ExrChannel luminance{"Y", &merged.luminance_cd_m2,
                             float32 ? ExrStorage::kFloat : ExrStorage::kFloat24};
  return writeExr(path, std::span(&luminance, 1),
                  float32 ? ExrCompression::kZip : ExrCompression::kPiz);
}

Status writeQualityExr(const fs::path& path, const calibration::MergedImage& merged, bool float32) {
  const ExrStorage integers = float32 ? ExrStorage::kFloat : ExrStorage::kUint;
  const ExrChannel channels[] = {{"relative_uncertainty", &merged.relative_uncertainty,
                                  float32 ? ExrStorage::kFloat : ExrStorage::kHalf},
                                 {"valid_frames", &merged.valid_frames, integers},
                                 {"bound", &merged.bound, integers}};
  return writeExr(path, channels, ExrCompression::kZip);
}

std::string stackId(const Stack& stack) {
  if (stack.manifest.id && !stack.manifest.id->empty()) return *stack.manifest.id;
  return fs::absolute(stack.directory).lexically_normal().filename().string();
}

// A leftover temporary younger than this may belong to another process still writing.
constexpr std::chrono::minutes kStaleTemporaryAge{10};

// The files `process` writes; only their leftovers are ever cleaned up in the output directory.
constexpr std::string_view kOutputNames[] = {"luminance.exr", "quality.exr", "luminance.png",
                                             "result.json"};

// Creates the output directory and withdraws an earlier result.json first, so that an
// interrupted run never leaves old results beside new pictures under a complete-looking set.
// A result.json that is not glarecam's is refused, not overwritten.
Status prepareOutputDirectory(const fs::path& directory) {
  GLARECAM_CHECK(ensureDirectory(directory));
  std::error_code ec;
  removeStaleTemporaries(directory, kStaleTemporaryAge, kOutputNames);
  const fs::path previous = directory / kResultFileName;
  if (!fs::exists(fs::symlink_status(previous, ec))) return {};
  auto document = readJsonFile(previous);
  if (!document || !hasResultSchema(*document)) {
    return badInput(previous.string() +
                    ": exists and is not a glarecam result; refusing to overwrite it");
  }
  fs::remove(previous, ec);
  if (ec)
    return ioError(previous.string() + ": cannot remove the previous result: " + ec.message());
  return fsyncPath(directory);
}

// A frame cannot hold values above its container's maximum: the merge treats that maximum as
// saturation (an 8-bit frame under a 12-bit calibration); say so.
void warnAboutNarrowFrames(const Stack& stack) {
  for (std::size_t i = 0; i < stack.frames.size(); ++i) {
    const double container_max_dn = static_cast<double>((1 << stack.bit_depths[i]) - 1);
    if (stack.calibration.saturation_dn <= container_max_dn) continue;
    spdlog::warn(
        "{}: saturation_dn {} exceeds what {}-bit frames such as {} hold; treating {} DN as "
        "saturated there",
        stack.directory.string(), stack.calibration.saturation_dn, stack.bit_depths[i],
        stack.manifest.frames[i].file, container_max_dn);
    return;
  }
}

// The file the calibration came from: --calibration, the manifest's calibration path, or the
// manifest itself for an inline block.
fs::path calibrationSource(const Stack& stack, const ProcessOptions& options) {
  if (options.calibration_file) return *options.calibration_file;
  if (stack.calibration_origin == "inline") return stack.directory / kManifestFileName;
  return stack.directory / stack.calibration_origin;
}

// A wrong (too high) saturation_dn lets clipped readings into the merge as valid ones.
void warnAboutClipping(const Stack& stack, const calibration::MergeInput& input,
                       const ProcessOptions& options) {
  const auto clipped = calibration::clippingBelowSaturation(input);
  if (!clipped) return;
  spdlog::warn(
      "{}: {} pixels of {} sit at {:g} DN, its maximum, below saturation_dn {:g}: the sensor "
      "seems to clip there, and the merge takes those readings as valid; check saturation_dn",
      calibrationSource(stack, options).string(), clipped->pixels,
      stack.manifest.frames[clipped->frame].file, clipped->dn, stack.calibration.saturation_dn);
}

// Refuses, naming the file and frame, manifests whose numbers are valid one by one but combine
// into a scale the merge cannot compute with (gain_db 1000, exposure_us 1e-30).
Status checkRadiometry(const Stack& stack,
                       const std::vector<calibration::FrameRadiometry>& radiometry) {
  for (std::size_t i = 0; i < radiometry.size(); ++i) {
    if (calibration::isRepresentable(radiometry[i])) continue;
    return badInput((stack.directory / kManifestFileName).string() + ": frames[" +
                    std::to_string(i) + "] (" + stack.manifest.frames[i].file +
                    "): exposure_us, gain_db, nd_transmission and luminance_factor give " +
                    fmt::format("{:.3g}", radiometry[i].scale_cd_m2_per_dn) +
                    " cd/m² per DN, outside the range the merge computes in");
  }
  return {};
}

}  // namespace

std::string ProcessSummary::briefReport() const {
  const ResultLuminance& lum = result.luminance;
  const std::optional<double>& limit = result.limit.limit_cd_m2;
  return fmt::format("{}: Lmax {}{:.4g} cd/m² at ({}, {}), limit {}, glare {}", result.stack,
                     lum.isLowerBound()   ? ">= "
                     : lum.isUpperBound() ? "<= "
                                          : "",
                     lum.max_cd_m2, lum.max_pixel[0], lum.max_pixel[1],
                     limit ? std::to_string(std::lround(*limit)) : "none",
                     result.glare ? (*result.glare ? "yes" : "no") : "n/a");
}

namespace {

struct MergedStack {
  calibration::MergedImage image;
  std::vector<FrameCheck> frames;  // each frame's agreement with the merge
};

// Frames whose luminance disagrees with the merge make every number wrong without any other
// symptom: say which, and by how much.
std::vector<FrameCheck> checkFrames(const Stack& stack, const calibration::MergeInput& input,
                                    const calibration::MergedImage& merged) {
  std::vector<FrameCheck> checks;
  const auto agreement = calibration::frameAgreement(input, merged);
  for (std::size_t i = 0; i < agreement.size(); ++i) {
    checks.push_back({stack.manifest.frames[i].file, agreement[i]});
    if (agreement[i].agrees()) continue;
    spdlog::warn(
        "{}: frames[{}] ({}) reads {} the other frames (median of {} pixel pairs): swapped "
        "files, a wrong exposure_us, gain_db, nd_transmission or saturation_dn, or a scene that "
        "changed during the bracket? Every luminance and ellipse of this stack is suspect",
        (stack.directory / kManifestFileName).string(), i, stack.manifest.frames[i].file,
        formatFrameRatio(agreement[i].median_ratio), agreement[i].samples);
  }
  std::vector<double> ratios;
  for (const auto& frame : agreement) ratios.push_back(frame.median_ratio);
  for (const auto& [i, j] : swappedFramePairs(ratios)) {
    spdlog::warn(
        "{}: frames[{}] ({}) and frames[{}] ({}) look swapped: each reads about what the "
        "other's exposure would",
        (stack.directory / kManifestFileName).string(), i, stack.manifest.frames[i].file, j,
        stack.manifest.frames[j].file);
  }
  return checks;
}

// A dark frame holds the offsets at the gain it was taken at: a frame at another gain (whose
// fixed pattern and dark current scale with it) is merged above the black level instead, said
// once; the hot pixels stay masked.
void dropDarkFrameAtAnotherGain(Stack& stack) {
  constexpr double kSameGainDb = 0.01;  // a camera's readback of one gain setting
  if (!stack.dark_frame_dn) return;
  for (const FrameSpec& frame : stack.manifest.frames) {
    if (std::abs(frame.gain_db - stack.calibration.dark_frame_gain_db) <= kSameGainDb) continue;
    spdlog::warn(
        "{}: frame {} is at {:g} dB but the dark frame was taken at {:g} dB: the black level is "
        "subtracted instead (calibrate dark at this gain to use one)",
        stackId(stack), frame.file, frame.gain_db, stack.calibration.dark_frame_gain_db);
    stack.dark_frame_dn.reset();
    return;
  }
}

// The radiometric checks, the merge and the frames' agreement with it; the raw frames are
// freed once merged.
Result<MergedStack> mergeStack(Stack& stack, const ProcessOptions& options) {
  const auto radiometry = calibration::frameRadiometry(stack.manifest.frames, stack.calibration);
  GLARECAM_CHECK(checkRadiometry(stack, radiometry));
  warnAboutNarrowFrames(stack);
  if (!stack.calibration.noise) {
    spdlog::warn("{}: calibration has no noise model; assuming a typical sensor", stackId(stack));
  }
  dropDarkFrameAtAnotherGain(stack);
  const std::vector<double> dark_offsets =
      calibration::darkOffsetsDn(stack.manifest.frames, stack.calibration);
  const calibration::MergeInput input{
      .frames = stack.frames,
      .radiometry = radiometry,
      .black_level_dn = stack.calibration.black_level_dn,
      .saturation_dn = stack.calibration.saturation_dn,
      .flat_field = stack.flat_field ? &*stack.flat_field : nullptr,
      .bit_depths = stack.bit_depths,
      .dark_frame_dn = stack.dark_frame_dn ? &*stack.dark_frame_dn : nullptr,
      .dark_offsets_dn = dark_offsets,
      .masked_pixels = stack.hot_pixels ? &*stack.hot_pixels : nullptr};
  warnAboutClipping(stack, input, options);
  MergedStack result;
  GLARECAM_ASSIGN(result.image, calibration::merge(input, {.threads = options.threads}));
  result.frames = checkFrames(stack, input, result.image);
  stack.frames.clear();
  return result;
}

// luminance.png shows a frame under this height enlarged (a 160x128 frame 4x, 320x256 2x): its
// spot, ellipses and labels then stay readable.
constexpr int kPictureMinImageHeightPx = 512;

// The picture's caption: the stack, Lmax (≥/≤ for a bound), the limit and the verdict, as in
// result.json, so that the picture alone says what was measured.
std::vector<std::string> pictureCaption(const StackResult& result) {
  constexpr int kCaptionDigits = 4;  // as the data sheet: a measurement is not known better
  const ResultLuminance& luminance = result.luminance;
  const char* bound = luminance.isLowerBound()   ? "\u2265 "
                      : luminance.isUpperBound() ? "\u2264 "
                                                 : "";
  const std::optional<double>& limit = result.limit.limit_cd_m2;
  return {
      result.stack,
      fmt::format("Lmax {}{} cd/m\u00b2", bound,
                  render::formatGrouped(luminance.max_cd_m2, kCaptionDigits)),
      limit ? fmt::format("limit {} cd/m\u00b2", render::formatGrouped(*limit, kCaptionDigits))
            : std::string("no limit"),
      result.glare ? (*result.glare ? "glare: yes" : "glare: no") : std::string("glare: \u2013"),
      result.illuminance.referred()
          ? fmt::format("at E = {:g} klx", *result.illuminance.reference_lx / 1000)
          : std::string("unreferred")};
}

std::string pictureTitle(const std::optional<double>& alpha_deg) {
  return alpha_deg ? fmt::format("\u03b1 {:.0f}\u00b0", *alpha_deg) : std::string();
}

// An ellipse lost to a camera model that cannot be inverted is the calibration's fault: say
// which file to fix (the luminance results stand).
void warnAboutCameraModel(const GlareAnalysis& glare, const fs::path& calibration_file) {
  std::vector<const EllipseMeasurement*> all{&glare.fwhm};
  if (glare.limit) all.push_back(&*glare.limit);
  for (const EllipseMeasurement& m : glare.thresholds) all.push_back(&m);
  for (const EllipseMeasurement* m : all) {
    if (m->status != EllipseStatus::kCameraModelNotInvertible) continue;
    spdlog::warn(
        "{}: the distortion coefficients cannot be inverted where the contour at {:.6g} cd/m² "
        "lies; that ellipse is missing (status camera_model_not_invertible)",
        calibration_file.string(), m->level_cd_m2);
  }
}

// How far from the image centre a principal point may lie, as a fraction of the frame's width or
// height, before it looks like intrinsics of another size, crop or orientation: real lenses sit
// within a few per cent (the simulated board's lens: 2 %).
constexpr double kPrincipalPointOffCentreFraction = 0.1;

void warnAboutPrincipalPoint(const Stack& stack, const fs::path& calibration_file) {
  if (stack.frames.empty()) return;
  const Intrinsics& k = stack.calibration.intrinsics;
  const double width = stack.frames.front().width(), height = stack.frames.front().height();
  const double dx = k.cx - (width - 1) / 2, dy = k.cy - (height - 1) / 2;
  if (std::abs(dx) <= kPrincipalPointOffCentreFraction * width &&
      std::abs(dy) <= kPrincipalPointOffCentreFraction * height)
    return;
  spdlog::warn(
      "{}: the principal point ({:.1f}, {:.1f}) lies {:.0f} px from the centre of the {}x{} frames "
      "(more than {:g} % of the frame): were the intrinsics calibrated at this size and "
      "orientation?",
      calibration_file.string(), k.cx, k.cy, std::hypot(dx, dy), width, height,
      100 * kPrincipalPointOffCentreFraction);
}

// The manifest's geometry.alpha_uncertainty_deg (rig_geometry.h) when it is a positive number.
std::optional<double> alphaUncertaintyDeg(const StackManifest& manifest) {
  const auto geometry = manifest.source.find("geometry");
  if (geometry == manifest.source.end() || !geometry->is_object()) return std::nullopt;
  const auto u = geometry->find("alpha_uncertainty_deg");
  if (u == geometry->end() || !u->is_number()) return std::nullopt;
  const double value = u->get<double>();
  return value > 0 && std::isfinite(value) ? std::optional(value) : std::nullopt;
}

// The manifest's module (its name or serial), when it is a non-empty string.
std::optional<std::string> moduleName(const StackManifest& manifest) {
  const auto module = manifest.source.find("module");
  if (module == manifest.source.end() || !module->is_string() || module->get<std::string>().empty())
    return std::nullopt;
  return module->get<std::string>();
}

// The manifest's camera block (backend, model, serial, size), or null.
nlohmann::json cameraBlock(const StackManifest& manifest) {
  const auto camera = manifest.source.find("camera");
  return camera != manifest.source.end() && camera->is_object() ? *camera : nlohmann::json();
}

// The calibration's identity for result.json: the file (and its SHA-256) it was read from, the
// camera and parts it states, K and u(K).
CalibrationIdentity calibrationIdentity(const Stack& stack, const ProcessOptions& options) {
  const nlohmann::json& source = stack.calibration.source;
  CalibrationIdentity identity{.origin = stack.calibration_origin,
                               .luminance_factor = stack.calibration.luminance_factor,
                               .noise_model_assumed = !stack.calibration.noise,
                               .dark_frame = stack.dark_frame_dn.has_value(),
                               .hot_pixels = stack.hot_pixels.has_value()};
  if (stack.calibration_origin != "inline") {
    const fs::path file = fs::absolute(calibrationSource(stack, options)).lexically_normal();
    identity.file = file.string();
    // Read a moment ago: a digest that fails now (the file replaced meanwhile) is left out.
    if (auto digest = sha256OfFile(file)) identity.sha256 = std::move(*digest);
  }
  if (const auto camera = source.find("camera"); camera != source.end() && camera->is_object())
    identity.camera = *camera;
  if (const auto parts = source.find("parts"); parts != source.end() && parts->is_object()) {
    identity.parts.emplace();
    const auto text = [](const nlohmann::json& part, const char* key) {
      const auto value = part.find(key);
      return value != part.end() && value->is_string() ? std::optional(value->get<std::string>())
                                                       : std::nullopt;
    };
    for (const auto& [name, part] : parts->items()) {
      if (!part.is_object()) continue;
      (*identity.parts)[name] = {.measured_at = text(part, "measured_at"),
                                 .method = text(part, "method")};
    }
  }
  constexpr std::size_t kIdHexDigits = 16;  // 64 bits: no two calibrations of a lab collide
  // Image paths by file name: a stack's inline copy (calibration/dark.exr) and the file it was
  // captured with (dark.exr) are one calibration.
  nlohmann::json hashed = source;
  for (std::string_view key : {"flat_field", "dark_frame", "hot_pixels"}) {
    if (const auto path = hashed.find(key); path != hashed.end() && path->is_string())
      *path = fs::path(path->get<std::string>()).filename().string();
  }
  identity.id = sha256Hex(hashed.dump()).substr(0, kIdHexDigits);
  if (const auto u = source.find("luminance_factor_u");
      u != source.end() && u->is_number() && u->get<double>() >= 0)
    identity.luminance_factor_u = u->get<double>();
  return identity;
}

// --alpha for a stack that records no α (true: given so); the same α confirms it, another is
// refused.
Result<bool> applyGivenAlpha(Stack& stack, const std::optional<double>& alpha_deg) {
  if (!alpha_deg) return false;
  const std::optional<double>& recorded = stack.manifest.alpha_deg;
  if (recorded && *recorded != *alpha_deg)
    return badInput(fmt::format(
        "{}: records alpha_deg {:g}, which --alpha {:g} contradicts (--alpha gives α to a stack "
        "that records none)",
        (stack.directory / kManifestFileName).string(), *recorded, *alpha_deg));
  if (recorded) return false;
  stack.manifest.alpha_deg = alpha_deg;
  return true;
}

// The stack's source illuminance: --source-illuminance, else the manifest's, else the estimate
// (clear sky) when asked for, else none.
Result<std::optional<SourceIlluminance>> sourceIlluminance(const Stack& stack,
                                                           const ProcessOptions& options) {
  const std::optional<SourceIlluminance>& recorded = stack.manifest.source_illuminance;
  if (!options.source_illuminance && !recorded && options.estimate_source) {
    auto estimate = options.estimate_source(stack.manifest);
    if (!estimate)
      return badInput(fmt::format("{}: {}", stack.directory.string(), estimate.error().message));
    spdlog::info("{}: no source illuminance recorded; the clear-sky estimate {}",
                 stack.directory.string(), describe(*estimate));
    return std::optional(*estimate);
  }
  if (recorded && options.estimate_source)
    spdlog::warn(
        "{}: records a source illuminance of {}, kept: the clear-sky estimate is only "
        "for a stack that records none",
        (stack.directory / kManifestFileName).string(), describe(*recorded));
  if (!options.source_illuminance) return recorded;
  if (recorded && recorded->illuminance_lx != options.source_illuminance->illuminance_lx)
    spdlog::warn("{}: records a source illuminance of {}; --source-illuminance {} replaces it",
                 (stack.directory / kManifestFileName).string(), describe(*recorded),
                 describe(*options.source_illuminance));
  return options.source_illuminance;
}

// Multiplies the merged luminance by `factor` (E_ref / E), in place; the relative uncertainty
// and the masks are unchanged.
void referLuminance(calibration::MergedImage& merged, double factor, unsigned threads) {
  FloatImage& luminance = merged.luminance_cd_m2;
  parallelRows(luminance.height(), threads, [&](int first_row, int end_row) {
    for (int y = first_row; y < end_row; ++y)
      for (float& value : luminance.row(y)) value = static_cast<float>(value * factor);
  });
}

// --threshold, else the α curve, else none.
std::optional<double> glareLimit(const Stack& stack, const ProcessOptions& options) {
  if (options.threshold_cd_m2) return options.threshold_cd_m2;
  if (!stack.manifest.alpha_deg) return std::nullopt;
  const auto limit = glareLimitCdM2(*stack.manifest.alpha_deg);
  if (!limit) {
    spdlog::warn(
        "{}: alpha_deg {:g} is beyond the method's {:g}°: no glare limit and no verdict (give "
        "--threshold for a constant limit)",
        (stack.directory / kManifestFileName).string(), *stack.manifest.alpha_deg,
        kMaxLimitAlphaDeg);
  }
  return limit;
}

}  // namespace

// luminance.exr, quality.exr, luminance.png, then result.json: each atomically, result last.
// The three images are encoded at once as far as the thread budget allows, each encoder on one
// thread and each thread taking the next when it is free, longest first (5 MP, one thread each:
// the quality EXR about 160 ms, the luminance EXR 180, the picture 150). After a failure (a full
// disk) the images not yet started are skipped.
Status writeResultFiles(const fs::path& out, const calibration::MergedImage& merged,
                        const calibration::CameraModel& camera, const GlareAnalysis& glare,
                        const LuminancePeak& peak, const StackResult& result, bool float32,
                        Progress& progress) {
  FalseColourOptions picture_options;
  picture_options.limit_cd_m2 = result.limit.limit_cd_m2;
  picture_options.title = pictureTitle(result.alpha_deg);
  picture_options.min_image_height_px = kPictureMinImageHeightPx;
  picture_options.overlay = glareOverlay(glare, camera, peak);
  picture_options.caption = pictureCaption(result);
  if (result.luminance.frames_consistent == false)
    picture_options.banner = "SUSPECT: frames disagree with the merge";
  GLARECAM_CHECK(prepareOutputDirectory(out));
  enum Output { kLuminance, kQuality, kPicture, kOutputCount };  // longest first
  const std::function<Status()> writers[kOutputCount] = {
      [&] { return writeLuminanceExr(out / "luminance.exr", merged, float32); },
      [&] { return writeQualityExr(out / "quality.exr", merged, float32); },
      [&]() -> Status {
        render::RgbImage picture;
        GLARECAM_ASSIGN(picture, renderFalseColour(merged, picture_options));
        return writePngRgb(out / "luminance.png", picture.width, picture.height, picture.rgb);
      }};
  Status written[kOutputCount];
  std::atomic<bool> failed{false};
  parallelTasks(kOutputCount, availableThreads(), [&](int i) {
    if (failed) return;
    written[i] = catchExceptions(writers[i]);
    if (!written[i]) failed = true;
  });
  for (const Status& status : written) GLARECAM_CHECK(status);
  progress.advance("luminance.exr");
  progress.advance("quality.exr");
  progress.advance("luminance.png");
  GLARECAM_CHECK(writeJsonFile(out / kResultFileName, toJson(result)));
  progress.advance("result.json");
  return {};
}

Status ProcessOptions::validate() const {
  const auto positive = [](double v) { return std::isfinite(v) && v > 0; };
  if (threshold_cd_m2 && !positive(*threshold_cd_m2))
    return badInput("--threshold: must be a positive luminance in cd/m²");
  if (thresholds_cd_m2.size() > kMaxThresholds)
    return badInput("--thresholds: at most " + std::to_string(kMaxThresholds) + " levels");
  if (!std::all_of(thresholds_cd_m2.begin(), thresholds_cd_m2.end(), positive))
    return badInput("--thresholds: must be positive luminances in cd/m²");
  if (alpha_deg && !(*alpha_deg >= 0 && *alpha_deg <= kMaxStackAlphaDeg))
    return badInput(fmt::format("--alpha: must be between 0 and {:g} degrees", kMaxStackAlphaDeg));
  GLARECAM_CHECK(checkReferenceIlluminance(reference_illuminance_lx, "--reference-illuminance"));
  return {};
}

Result<ProcessSummary> processStack(const fs::path& stack_directory,
                                    const ProcessOptions& options) {
  GLARECAM_CHECK(options.validate());
  const ThreadBudget budget(options.threads);  // every step below keeps to --threads
  Progress progress("process " + stack_directory.filename().string(), kProcessSteps,
                    options.show_progress);
  Stack stack;
  GLARECAM_ASSIGN(stack, readStack(stack_directory, {.calibration_file = options.calibration_file,
                                                     .threads = options.threads}));
  bool alpha_given = false;
  GLARECAM_ASSIGN(alpha_given, applyGivenAlpha(stack, options.alpha_deg));
  std::vector<std::string> warnings;
  GLARECAM_CHECK(calibration::checkCalibrationUse(stack.calibration, stack.manifest,
                                                  calibrationSource(stack, options).string(),
                                                  options.calibration_use, warnings));
  for (const std::string& warning : warnings) spdlog::warn("{}", warning);
  warnAboutPrincipalPoint(stack, calibrationSource(stack, options));
  ResultIlluminance illuminance;
  GLARECAM_ASSIGN(illuminance.source, sourceIlluminance(stack, options));
  progress.advance("read");
  MergedStack merged_stack;
  GLARECAM_ASSIGN(merged_stack, mergeStack(stack, options));
  if (illuminance.source) {
    illuminance.reference_lx = options.reference_illuminance_lx;
    referLuminance(merged_stack.image, illuminance.factor(), options.threads);
  }
  const calibration::MergedImage& merged = merged_stack.image;
  progress.advance("merged");

  const std::optional<double> limit = glareLimit(stack, options);
  const LuminanceStats stats = luminanceStats(merged);
  const calibration::CameraModel camera(stack.calibration.intrinsics);
  const GlareAnalysis glare =
      analyseGlare(merged, camera, stats.max,
                   {.limit_cd_m2 = limit,
                    .thresholds_cd_m2 = options.thresholds_cd_m2,
                    .scale_relative_uncertainty =
                        illuminance.source ? illuminance.source->relativeUncertainty() : 0.0,
                    .ladder = options.ladder});
  warnAboutCameraModel(glare, calibrationSource(stack, options));
  progress.advance("analysed");
  ProcessSummary summary;
  summary.output_directory = options.output_directory.value_or(stack_directory / "result");
  summary.result = makeResult(
      {.stack_id = stackId(stack),
       .alpha_deg = stack.manifest.alpha_deg,
       .alpha_source = alpha_given                ? "given"
                       : stack.manifest.alpha_deg ? "manifest"
                                                  : "",
       .alpha_uncertainty_deg = alpha_given ? std::nullopt : alphaUncertaintyDeg(stack.manifest),
       .camera = cameraBlock(stack.manifest),
       .module = moduleName(stack.manifest),
       .width = merged.luminance_cd_m2.width(),
       .height = merged.luminance_cd_m2.height(),
       .calibration = calibrationIdentity(stack, options),
       .illuminance = illuminance,
       .stats = stats,
       .frames = merged_stack.frames,
       .limit_cd_m2 = limit,
       .constant_limit = options.threshold_cd_m2.has_value(),
       .glare = glare,
       .ladder = options.ladder});
  GLARECAM_CHECK(writeResultFiles(summary.output_directory, merged, camera, glare, stats.max,
                                  summary.result, options.float32, progress));
  return summary;
}

}  // namespace glarecam::pipeline
