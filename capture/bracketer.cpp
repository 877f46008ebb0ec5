#include "capture/bracketer.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <charconv>
#include <chrono>
#include <cmath>
#include <ctime>

#include "capture/sim/sim_camera.h"
#include "core/json.h"
#include "core/progress.h"
#include "core/stack_io.h"
#include "core/time.h"

namespace glarecam::capture {
namespace {

// Without a calibration: no black level known, and the top 5 % of the pixel format's range
// treated as saturated (sensors leave the linear range before full scale).
constexpr double kUncalibratedSaturationFraction = 0.95;
// Stacks captured into one directory within the same second get "-2", "-3", ... up to this.
constexpr int kMaxStackNameSuffix = 1000;
// Progress steps of an auto-bracket: peak metered, background metered, bracket captured (one
// more per re-bracket).
constexpr int kAutoBracketStages = 3;

// The bits a pixel format carries: the number ending its name (Mono12, BayerRG10), else the
// stored depth.
int significantBits(const SensorFormat& format) {
  const std::string& name = format.pixel_format;
  const auto digits = name.find_last_not_of("0123456789") + 1;
  int bits = 0;
  const auto [end, error] = std::from_chars(name.data() + digits, name.data() + name.size(), bits);
  if (error != std::errc() || bits < 8 || bits > format.bits_per_pixel) {
    return format.bits_per_pixel;
  }
  return bits;
}

struct SensorLevels {
  double black_dn = 0;
  double saturation_dn = 0;
  double usableRange() const { return saturation_dn - black_dn; }
};

// The calibration in force: the capture's, else the camera's own.
std::optional<Calibration> calibrationFor(const Camera& camera, const CaptureSettings& settings) {
  return settings.calibration ? settings.calibration : camera.info().calibration;
}

SensorLevels sensorLevels(const Camera& camera, const CaptureSettings& settings) {
  if (const auto calibration = calibrationFor(camera, settings)) {
    return {calibration->black_level_dn, calibration->saturation_dn};
  }
  const double full_scale = std::ldexp(1.0, significantBits(camera.format())) - 1.0;
  return {0.0, kUncalibratedSaturationFraction * full_scale};
}

Result<CapturedFrame> captureOne(Camera& camera, double exposure_us, double gain_db) {
  const ExposureRequest request{exposure_us, gain_db};
  std::vector<CapturedFrame> frames;
  GLARECAM_ASSIGN(frames, camera.capture({&request, 1}));
  return std::move(frames.front());
}

using NextMetering = std::optional<double> (*)(const MeteringFrame&, double, const CameraLimits&,
                                               const AutoBracketOptions&);

// Meters from `exposure_us` until `next` is satisfied; every frame goes into the log.
Result<MeteringFrame> meter(Camera& camera, const CaptureSettings& settings,
                            const SensorLevels& levels, double exposure_us, NextMetering next,
                            AutoBracketLog& log) {
  for (int attempt = 0;; ++attempt) {
    CapturedFrame frame;
    GLARECAM_ASSIGN(frame, captureOne(camera, exposure_us, settings.gain_db));
    const MeteringFrame metered{
        frame.exposure_us, measureFrameLevels(frame.image, levels.black_dn, levels.saturation_dn)};
    log.metering.push_back(metered);
    const auto following =
        next(metered, levels.usableRange(), camera.limits(), settings.auto_bracket);
    if (!following) return metered;
    if (attempt + 1 >= settings.auto_bracket.max_metering_frames) {
      spdlog::warn("{}: metering did not settle in {} frames; planning from the last one",
                   camera.info().uri, settings.auto_bracket.max_metering_frames);
      return metered;
    }
    exposure_us = *following;
  }
}

struct Bracket {
  std::vector<ExposureRequest> requested;
  std::vector<CapturedFrame> frames;  // as applied, one per request
  AutoBracketLog log;
};

// Captures one frame per exposure into `bracket`, replacing what it held.
Status captureExposures(Camera& camera, const std::vector<double>& exposures_us, double gain_db,
                        Bracket& bracket) {
  bracket.requested.clear();
  for (const double exposure : exposures_us) bracket.requested.push_back({exposure, gain_db});
  GLARECAM_ASSIGN(bracket.frames, camera.capture(bracket.requested));
  return {};
}

// Captures `plan`, re-planning shorter while the peak is clipped in the shortest frame.
Status captureUnclipped(Camera& camera, const CaptureSettings& settings, const SensorLevels& levels,
                        double background_rate, BracketPlan plan, Bracket& bracket,
                        Progress& progress) {
  for (int attempt = 0;; ++attempt) {
    GLARECAM_CHECK(captureExposures(camera, plan.exposures_us, settings.gain_db, bracket));
    progress.advance(fmt::format("{} frames", bracket.frames.size()));
    const double shortest_us = bracket.frames.front().exposure_us;
    bracket.log.peak_clipped =
        measureFrameLevels(bracket.frames.front().image, levels.black_dn, levels.saturation_dn)
            .peak_clipped;
    bracket.log.background_underexposed = plan.background_underexposed;
    // Nothing shorter to try at the camera's shortest exposure.
    const bool at_shortest =
        shortest_us <= camera.limits().min_exposure_us + camera.limits().exposure_step_us;
    if (!bracket.log.peak_clipped || plan.peak_clipped || at_shortest ||
        attempt >= settings.auto_bracket.max_rebrackets) {
      return {};
    }
    ++bracket.log.rebrackets;
    progress.setTotal(kAutoBracketStages + bracket.log.rebrackets);
    spdlog::info("{}: peak clipped at {:g} µs; re-bracketing shorter", camera.info().uri,
                 shortest_us);
    GLARECAM_ASSIGN(
        plan, planForRates(clippedPeakRate(shortest_us, levels.usableRange()), background_rate,
                           levels.usableRange(), camera.limits(), settings.auto_bracket));
  }
}

Result<Bracket> autoBracket(Camera& camera, const CaptureSettings& settings, Progress& progress) {
  const SensorLevels levels = sensorLevels(camera, settings);
  if (!(levels.usableRange() > 0)) {
    return badInput(fmt::format("{}: the calibration's saturation is not above its black level",
                                camera.info().uri));
  }
  const CameraLimits limits = camera.limits();
  Bracket bracket;
  MeteringFrame peak, background;
  GLARECAM_ASSIGN(peak, meter(camera, settings, levels,
                              std::clamp(settings.auto_bracket.first_metering_exposure_us,
                                         limits.min_exposure_us, limits.max_exposure_us),
                              nextPeakMetering, bracket.log));
  progress.advance("peak metered");
  background = peak;
  if (const auto longer =
          nextBackgroundMetering(peak, levels.usableRange(), limits, settings.auto_bracket)) {
    GLARECAM_ASSIGN(background,
                    meter(camera, settings, levels, *longer, nextBackgroundMetering, bracket.log));
  }
  progress.advance("background metered");
  BracketPlan plan;
  GLARECAM_ASSIGN(plan,
                  planForRates(peakRate(peak, levels.usableRange()), backgroundRate(background),
                               levels.usableRange(), limits, settings.auto_bracket));
  GLARECAM_CHECK(captureUnclipped(camera, settings, levels, backgroundRate(background),
                                  std::move(plan), bracket, progress));
  if (bracket.log.peak_clipped) {
    spdlog::warn(
        "{}: the peak is clipped even in the shortest frame ({:g} µs); Lmax will be a "
        "lower bound",
        camera.info().uri, bracket.frames.front().exposure_us);
  }
  return bracket;
}

nlohmann::json cameraJson(const Camera& camera) {
  const CameraInfo& info = camera.info();
  const SensorFormat format = camera.format();
  return {{"backend", info.backend}, {"uri", info.uri},
          {"vendor", info.vendor},   {"model", info.model},
          {"serial", info.serial},   {"pixel_format", format.pixel_format},
          {"width", format.width},   {"height", format.height}};
}

// "20260621T091203Z-a32.72": the capture's UTC time, and α when known.
constexpr std::string_view kAlphaIdSeparator = "-a";
std::string stackId(const std::string& stamp, std::optional<double> alpha_deg) {
  return alpha_deg ? fmt::format("{}{}{:05.2f}", stamp, kAlphaIdSeparator, *alpha_deg) : stamp;
}

// α as given, else as a simulated camera knows it from its scene.
std::optional<double> alphaFor(const Camera& camera, const CaptureSettings& settings) {
  if (settings.alpha_deg || !settings.alpha_from_scene) return settings.alpha_deg;
  const auto truth = sceneTruthOf(camera);
  if (truth && truth->contains("alpha_deg") && (*truth)["alpha_deg"].is_number()) {
    return (*truth)["alpha_deg"].get<double>();
  }
  return std::nullopt;
}

// The source as given, else as a simulated camera lit its scene (only where the scene also gives
// α: a rig measures its own).
std::optional<SourceIlluminance> sourceFor(const Camera& camera, const CaptureSettings& settings) {
  if (settings.source_illuminance || !settings.alpha_from_scene) return settings.source_illuminance;
  const auto truth = sceneTruthOf(camera);
  if (!truth || !truth->contains("source_illuminance_lx") ||
      !(*truth)["source_illuminance_lx"].is_number())
    return std::nullopt;
  return SourceIlluminance{.illuminance_lx = (*truth)["source_illuminance_lx"].get<double>(),
                           .illuminance_u_lx = 0,
                           .origin = IlluminanceOrigin::kGiven,
                           .instrument = "the simulated sun"};
}

StackManifest makeManifest(const Camera& camera, const CaptureSettings& settings,
                           const Bracket& bracket) {
  const std::optional<double> alpha_deg = alphaFor(camera, settings);
  StackManifest manifest;
  const UtcTime now = settings.start_time.value_or(utcNow());
  manifest.id = stackId(formatStackStamp(now), alpha_deg);
  manifest.captured_at = formatIsoSeconds(now);
  manifest.alpha_deg = alpha_deg;
  manifest.source_illuminance = sourceFor(camera, settings);
  manifest.calibration = calibrationFor(camera, settings);
  const CameraOptics& known = camera.info().optics;
  const auto f_number = settings.optics.f_number ? settings.optics.f_number : known.f_number;
  const double nd = settings.optics.nd_transmission.value_or(known.nd_transmission.value_or(1.0));
  int retries = 0;
  for (std::size_t i = 0; i < bracket.frames.size(); ++i) {
    const CapturedFrame& frame = bracket.frames[i];
    manifest.frames.push_back(
        {.file = fmt::format("frame-{:02}.png", i),
         .exposure_us = frame.exposure_us,
         .gain_db = frame.gain_db,
         .f_number = f_number,
         .nd_transmission = nd,
         .source = {{"requested_exposure_us", bracket.requested[i].exposure_us},
                    {"requested_gain_db", bracket.requested[i].gain_db},
                    {"discarded_frames", frame.retries}}});
    retries += frame.retries;
  }
  nlohmann::json capture = {{"bracketing", settings.exposures_us ? "fixed" : "auto"},
                            {"discarded_frames", retries}};
  if (!settings.exposures_us) capture["auto_bracket"] = bracket.log.toJson();
  manifest.source = {{"camera", cameraJson(camera)}, {"capture", std::move(capture)}};
  if (settings.geometry) manifest.source["geometry"] = *settings.geometry;
  if (settings.module) manifest.source["module"] = *settings.module;
  return manifest;
}

// A calibration made for another pixel format (Mono8's for Mono16 frames, say) puts saturation
// outside the frames' range, or far below it: refused rather than merged into nonsense. Sensors
// of 10 bits and more in a 16-bit container are 6 bits short at most; Mono8 in Mono16 is 8.
Status checkCalibrationFitsFormat(const Camera& camera, const Calibration& calibration) {
  constexpr double kMaxUnusedBits = 7;
  const SensorFormat format = camera.format();
  const double full_scale = std::ldexp(1.0, significantBits(format)) - 1.0;
  if (calibration.saturation_dn > full_scale ||
      calibration.saturation_dn < std::ldexp(full_scale, -static_cast<int>(kMaxUnusedBits))) {
    return badInput(fmt::format(
        "capture: the calibration's saturation ({:g} DN) does not fit {}'s {} frames (0 … {:g} "
        "DN): a calibration for another pixel format?",
        calibration.saturation_dn, camera.info().uri, format.pixel_format, full_scale));
  }
  return {};
}

Status checkSettings(const Camera& camera, const CaptureSettings& settings) {
  if (settings.calibration)
    GLARECAM_CHECK(checkCalibrationFitsFormat(camera, *settings.calibration));
  const CameraLimits limits = camera.limits();
  if (settings.exposures_us) {
    if (settings.exposures_us->empty()) return badInput("capture: --exposures lists no exposure");
    for (const double exposure : *settings.exposures_us) {
      if (!(exposure >= limits.min_exposure_us && exposure <= limits.max_exposure_us)) {
        return badInput(
            fmt::format("capture: exposure {:g} µs is outside {}'s range {:g} … {:g} µs", exposure,
                        camera.info().uri, limits.min_exposure_us, limits.max_exposure_us));
      }
    }
  }
  if (!(settings.gain_db >= limits.min_gain_db && settings.gain_db <= limits.max_gain_db)) {
    return badInput(fmt::format("capture: gain {:g} dB is outside {}'s range {:g} … {:g} dB",
                                settings.gain_db, camera.info().uri, limits.min_gain_db,
                                limits.max_gain_db));
  }
  return settings.auto_bracket.validate();
}

// The calibration's images, to be copied into the stack's calibration/ folder, with the manifest's
// paths pointing there. Checked before the bracket: a capture whose stacks could not be
// processed is refused at once.
constexpr const char* kCalibrationImagesFolder = "calibration";

Result<std::vector<StackAttachment>> calibrationAttachments(Calibration& calibration) {
  std::vector<StackAttachment> attachments;
  if (calibration.directory.empty()) return attachments;  // a camera's own: nothing to copy
  for (const auto& [key, relative] : calibrationImages(calibration)) {
    const std::filesystem::path source = calibration.directory / relative;
    std::error_code ec;
    if (!std::filesystem::is_regular_file(source, ec)) {
      return badInput(
          fmt::format("capture: the calibration's {} {} does not exist", key, source.string()));
    }
    const std::string inside = fmt::format("{}/{}", kCalibrationImagesFolder,
                                           std::filesystem::path(relative).filename().string());
    if (std::ranges::any_of(attachments, [&](const StackAttachment& other) {
          return other.relative_path == inside;
        })) {
      return badInput(
          fmt::format("capture: the calibration names two images called {}: give "
                      "them different file names",
                      std::filesystem::path(relative).filename().string()));
    }
    attachments.push_back({inside, source});
    setCalibrationImage(calibration, key, inside);
  }
  return attachments;
}

}  // namespace

Result<CapturedStack> captureStack(Camera& camera, const CaptureSettings& settings) {
  GLARECAM_CHECK(checkSettings(camera, settings));
  std::optional<Calibration> calibration = calibrationFor(camera, settings);
  std::vector<StackAttachment> attachments;
  if (calibration) GLARECAM_ASSIGN(attachments, calibrationAttachments(*calibration));
  const int planned = settings.exposures_us ? 1 : kAutoBracketStages;
  Progress progress("capture", planned, settings.show_progress);
  Bracket bracket;
  if (settings.exposures_us) {
    GLARECAM_CHECK(captureExposures(camera, *settings.exposures_us, settings.gain_db, bracket));
    progress.advance(fmt::format("{} frames", bracket.frames.size()));
  } else {
    GLARECAM_ASSIGN(bracket, autoBracket(camera, settings, progress));
  }
  progress.finish();
  CapturedStack stack;
  stack.manifest = makeManifest(camera, settings, bracket);
  stack.manifest.calibration = calibration;
  stack.attachments = std::move(attachments);
  stack.bit_depth = camera.format().bits_per_pixel <= 8 ? 8 : 16;
  stack.truth = sceneTruthOf(camera);
  for (CapturedFrame& frame : bracket.frames) stack.frames.push_back(std::move(frame.image));
  return stack;
}

Result<std::filesystem::path> writeCapturedStack(const std::filesystem::path& parent,
                                                 const CapturedStack& stack) {
  const std::string id = stack.manifest.id.value_or("stack");
  StackWriteRequest request;
  request.manifest = stack.manifest;
  request.frames = stack.frames;
  request.bit_depth = stack.bit_depth;
  request.attachments = stack.attachments;
  request.may_replace = false;
  if (stack.truth) request.text_files.emplace_back("truth.json", jsonText(*stack.truth));
  for (int suffix = 1; suffix <= kMaxStackNameSuffix; ++suffix) {
    const std::filesystem::path target =
        parent / (suffix == 1 ? id : fmt::format("{}-{}", id, suffix));
    std::error_code error;
    if (std::filesystem::exists(std::filesystem::symlink_status(target, error))) continue;
    request.manifest.id = target.filename().string();
    Status written = writeStack(target, request);
    if (written) return target;
    // Another capture took the name meanwhile (its stack is left alone): try the next one.
    if (!std::filesystem::exists(std::filesystem::symlink_status(target, error))) {
      return std::unexpected(written.error());
    }
  }
  return fail(ErrorCode::kIo, fmt::format("{}: {} stacks named {} already exist", parent.string(),
                                          kMaxStackNameSuffix, id));
}

void recordAlpha(CapturedStack& stack, double alpha_deg, nlohmann::json geometry) {
  stack.manifest.alpha_deg = alpha_deg;
  stack.manifest.source["geometry"] = std::move(geometry);
  if (stack.manifest.id) {
    const std::string& id = *stack.manifest.id;
    stack.manifest.id = stackId(id.substr(0, id.rfind(kAlphaIdSeparator)), alpha_deg);
  }
}

}  // namespace glarecam::capture
