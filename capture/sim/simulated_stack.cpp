#include "capture/sim/simulated_stack.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <numbers>
#include <span>

#include "calibration/radiometry.h"
#include "capture/sim/module_model.h"
#include "capture/sim/surface_scene.h"
#include "core/angles.h"
#include "core/json.h"
#include "core/progress.h"
#include "core/stack_io.h"
#include "core/stack_manifest.h"
#include "pipeline/limit_curve.h"
#include "surface/surface_catalogue.h"

namespace glarecam::capture {
namespace {

constexpr int kMinSide = 16, kMaxSide = 16384;
constexpr double kMinFovDeg = 1.0, kMaxFovDeg = 150.0;  // a pinhole model's sensible range
constexpr double kMaxOffsetDeg = 80.0;                  // the lobe stays in front of the lens

}  // namespace

Calibration simulatedCalibration(const SimulationOptions& options) {
  Calibration calibration;
  calibration.black_level_dn = options.sensor.black_level_dn;
  calibration.saturation_dn = options.sensor.saturation_dn;
  calibration.luminance_factor = options.luminance_factor;
  calibration.reference_f_number = options.f_number;
  calibration.intrinsics = pinholeIntrinsics(options.width, options.height,
                                             options.horizontal_fov_deg, options.distortion);
  calibration.noise = NoiseModel{options.sensor.read_noise_dn, options.sensor.dn_per_electron};
  calibration.source = nlohmann::json::object();
  return calibration;
}

namespace {

std::string stackId(const SimulationOptions& options) {
  char id[96];
  std::snprintf(id, sizeof id, "sim-%.40s-a%05.2f-s%llu", options.moduleLabel().c_str(),
                options.alpha_deg, static_cast<unsigned long long>(options.seed));
  return id;
}

// The metering a real auto-bracket does on a first frame: the brightest and the darkest
// (5th percentile) luminance of the scene.
std::pair<double, double> meterScene(const FloatImage& luminance) {
  std::vector<float> values(luminance.data(), luminance.data() + luminance.pixelCount());
  auto fifth = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 20);
  std::nth_element(values.begin(), fifth, values.end());
  const float peak = *std::max_element(values.begin(), values.end());
  return {peak, *fifth};
}

StackManifest makeManifest(const SimulationOptions& options, const Calibration& calibration,
                           const BracketPlan& plan) {
  StackManifest manifest;
  manifest.id = stackId(options);
  manifest.alpha_deg = options.alpha_deg;
  manifest.calibration = calibration;
  for (std::size_t i = 0; i < plan.exposures_us.size(); ++i) {
    char file[32];
    std::snprintf(file, sizeof file, "frame-%02zu.png", i);
    manifest.frames.push_back({.file = file,
                               .exposure_us = plan.exposures_us[i],
                               .gain_db = 0.0,
                               .f_number = options.f_number,
                               .nd_transmission = options.nd_transmission});
  }
  if (options.record_source)
    manifest.source_illuminance = SourceIlluminance{
        .illuminance_lx = options.source_illuminance_lx,
        .illuminance_u_lx = options.source_illuminance_u_lx,
        .origin = IlluminanceOrigin::kGiven,
        .instrument = "the simulated sun",
    };
  manifest.source = {{"camera",
                      {{"backend", "sim"},
                       {"model", "glarecam-sim"},
                       {"serial", "SIM-0001"},
                       {"pixel_format", "Mono" + std::to_string(options.sensor.adc_bits)},
                       {"width", options.width},
                       {"height", options.height}}},
                     {"module", "simulated " + options.moduleLabel() + " module"},
                     {"simulation",
                      {{"module", options.moduleLabel()},
                       {"surface", options.surface},
                       {"seed", options.seed},
                       {"background_cd_m2", options.background_cd_m2},
                       {"peak_scale", options.peak_scale},
                       {"bracket",
                        {{"peak_clipped", plan.peak_clipped},
                         {"background_underexposed", plan.background_underexposed}}}}}};
  return manifest;
}

// Each frame's own noise stream: distinct for every (seed, frame) over the whole uint64 range.
std::uint64_t frameSeed(std::uint64_t seed, std::size_t frame) {
  constexpr std::uint64_t kGoldenRatio64 = 0x9e3779b97f4a7c15ull;  // odd: a bijection per frame
  return seed * kGoldenRatio64 + frame;
}

nlohmann::json axesJson(const std::optional<EllipseAxes>& axes) {
  if (!axes) return nullptr;
  return {{"vertical", axes->vertical_deg}, {"horizontal", axes->horizontal_deg}};
}

}  // namespace

Intrinsics pinholeIntrinsics(int width, int height, double horizontal_fov_deg,
                             const std::array<double, 5>& distortion) {
  Intrinsics k;
  k.fx = k.fy = (width / 2.0) / std::tan(radians(horizontal_fov_deg / 2.0));
  k.cx = (width - 1) / 2.0;
  k.cy = (height - 1) / 2.0;
  k.distortion = distortion;
  return k;
}

std::string SimulationOptions::moduleLabel() const {
  if (surface.starts_with(kCurvesPrefix)) return surface.substr(kCurvesPrefix.size());
  const std::filesystem::path path(surface);
  return "surface-" + (path.has_extension() ? path.stem().string() : surface);
}

Status SimulationOptions::validate() const {
  if (surface.empty() || surface == kCurvesPrefix)
    return badInput("simulate: --surface must name a surface, a file or curves:MODULE");
  if (!(alpha_deg >= 0 && alpha_deg <= pipeline::kMaxLimitAlphaDeg)) {
    return badInput("simulate: --alpha must be between 0 and 80 degrees (the method's range)");
  }
  if (width < kMinSide || height < kMinSide || width > kMaxSide || height > kMaxSide) {
    return badInput("simulate: --size must be between 16x16 and 16384x16384");
  }
  if (!(horizontal_fov_deg > kMinFovDeg && horizontal_fov_deg < kMaxFovDeg)) {
    return badInput("simulate: --fov must be between 1 and 150 degrees");
  }
  if (!(background_cd_m2 > 0 && std::isfinite(background_cd_m2))) {
    return badInput("simulate: --background must be a positive luminance");
  }
  if (!(peak_scale > 0 && std::isfinite(peak_scale)))
    return badInput("simulate: --peak-scale must be positive");
  if (!(source_illuminance_lx > 0 && source_illuminance_lx <= kMaxSourceIlluminanceLx))
    return badInput(fmt::format("simulate: --source-illuminance must be in (0, {:g}] lx",
                                kMaxSourceIlluminanceLx));
  if (!(source_illuminance_u_lx >= 0 && source_illuminance_u_lx < source_illuminance_lx))
    return badInput("simulate: --source-illuminance's uncertainty must be >= 0 and below it");
  if (!std::isfinite(lobe_orientation_deg))
    return badInput("simulate: --orientation must be finite");
  const auto within = [](double deg) { return std::abs(deg) < kMaxOffsetDeg; };
  if (!within(lobe_offset_deg[0]) || !within(lobe_offset_deg[1])) {
    return badInput("simulate: --offset-deg must stay within 80 degrees of the optical axis");
  }
  if (!std::all_of(distortion.begin(), distortion.end(),
                   [](double k) { return std::isfinite(k); })) {
    return badInput("simulate: --distortion coefficients must be finite");
  }
  if (defects.hot_pixels < 0 || defects.hot_pixels > width * height / 100)
    return badInput("simulate: --hot-pixels must be between 0 and 1 % of the pixels");
  if (!(defects.fixed_pattern_dn >= 0 && defects.fixed_pattern_dn <= kMaxFixedPatternDn))
    return badInput("simulate: --fixed-pattern must be between 0 and 100 DN");
  if (!(luminance_factor > 0 && nd_transmission > 0 && nd_transmission <= 1 && f_number > 0)) {
    return fail(ErrorCode::kInternal,
                "simulate: the simulated camera's K, ND and f-number must be positive");
  }
  return bracket.validate();
}

namespace {

// The lens model must be invertible over the frame: a distortion polynomial that folds over
// (strong negative k1) maps two directions to one pixel and the scene would be drawn torn.
Status checkLensInvertible(const calibration::CameraModel& camera, int width, int height) {
  constexpr double kRoundTripTolerancePx = 0.01;
  const double w = width - 1, h = height - 1;
  const calibration::PixelPoint border[] = {{0, 0}, {w / 2, 0}, {w, 0}, {w, h / 2},
                                            {w, h}, {w / 2, h}, {0, h}, {0, h / 2}};
  for (const auto& pixel : border) {
    const calibration::PixelPoint back = camera.project(camera.ray(pixel));
    if (!(std::hypot(back.x - pixel.x, back.y - pixel.y) < kRoundTripTolerancePx)) {
      return badInput(
          "simulate: --distortion folds the image over inside the frame; use weaker coefficients");
    }
  }
  return {};
}

}  // namespace

nlohmann::json sceneTruthJson(const SimulatedScene& scene, double alpha_deg) {
  const SceneTruth& truth = scene.truth;
  const SceneTruth& lit = scene.truth_as_lit;
  return {{"schema", kTruthSchema},
          {"alpha_deg", alpha_deg},
          {"reference_illuminance_lx", kDefaultReferenceIlluminanceLx},
          {"source_illuminance_lx", scene.source_illuminance_lx},
          {"luminance_max_cd_m2", truth.peak_cd_m2},
          {"limit_cd_m2", truth.limit_cd_m2},
          {"limit_axes_deg", axesJson(truth.limit_axes)},
          {"fwhm_axes_deg", axesJson(truth.fwhm_axes)},
          {"glare", truth.peak_cd_m2 >= truth.limit_cd_m2},
          {"as_lit",
           {{"luminance_max_cd_m2", lit.peak_cd_m2},
            {"limit_axes_deg", axesJson(lit.limit_axes)},
            {"fwhm_axes_deg", axesJson(lit.fwhm_axes)},
            {"glare", lit.peak_cd_m2 >= lit.limit_cd_m2}}},
          {"centre_pixel", scene.centre_pixel}};
}

nlohmann::json SimulatedStack::truthJson() const {
  SimulatedScene scene;
  scene.truth = truth;
  scene.truth_as_lit = truth_as_lit;
  scene.source_illuminance_lx = source_illuminance_lx;
  scene.centre_pixel = centre_pixel;
  nlohmann::json document = sceneTruthJson(scene, manifest.alpha_deg.value_or(0.0));
  document["stack"] = manifest.id.value_or("");
  document["bracket"] = {{"exposures_us", bracket.exposures_us},
                         {"peak_clipped", bracket.peak_clipped}};
  if (!defects.offset_dn.empty()) {
    nlohmann::json hot = nlohmann::json::array();
    for (const auto& [x, y] : defects.hot_pixels) hot.push_back({x, y});
    document["hot_pixels"] = hot;
  }
  return document;
}

namespace {

// The lobe of a module's empirical curves: an elliptical Gaussian whose limit contour has the
// curves' axes (glare_scene.h).
Status renderCurvesScene(const SimulationOptions& options, double limit,
                         const calibration::CameraModel& camera, SimulatedScene& result) {
  ModuleGlareModel module;
  GLARECAM_ASSIGN(module, moduleModel(options.surface.substr(kCurvesPrefix.size())));
  // The lobe's shape comes from the module's axes at the limit for its own peak; peak_scale
  // then changes only the brightness (a dimmer module glares less and over a smaller ellipse).
  const double model_peak = module.lmax_cd_m2(options.alpha_deg);
  auto lobe = lobeWithAxesAt(limit, model_peak, options.background_cd_m2,
                             module.vertical_deg(options.alpha_deg),
                             module.horizontal_deg(options.alpha_deg));
  if (!lobe) return std::unexpected(lobe.error());
  lobe->peak_cd_m2 = model_peak * options.peak_scale;
  lobe->orientation_deg = options.lobe_orientation_deg;
  lobe->centre_direction_deg = options.lobe_offset_deg;
  // The scene as lit: every luminance in proportion to the source (the module's reflection, and
  // the sky's in its glass, which that sun also lights), so that referred it is the reference's.
  auto reference_scene = GlareScene::create(*lobe);
  if (!reference_scene) return std::unexpected(reference_scene.error());
  const double lit = options.source_illuminance_lx / kDefaultReferenceIlluminanceLx;
  lobe->peak_cd_m2 *= lit;
  lobe->background_cd_m2 *= lit;
  auto scene = GlareScene::create(*lobe);
  if (!scene) return std::unexpected(scene.error());
  const auto centre = camera.project(scene->centreRay());
  result.centre_pixel = {centre.x, centre.y};
  result.true_luminance_cd_m2 = scene->render(camera, options.width, options.height);
  result.truth = reference_scene->truth(limit);
  result.truth_as_lit = scene->truth(limit);
  return {};
}

// The lobe of a physical surface under the sun's disc (surface_scene.h): its truth from the
// surface's own contours.
Status renderSurfaceScene(const SimulationOptions& options, double limit,
                          const calibration::CameraModel& camera, SimulatedScene& result) {
  std::unique_ptr<surface::BrdfModel> model;
  GLARECAM_ASSIGN(model, surface::surfaceModel(options.surface));
  auto scene =
      SurfaceScene::create(std::move(model), {.alpha_deg = options.alpha_deg,
                                              .background_cd_m2 = options.background_cd_m2,
                                              .peak_scale = options.peak_scale,
                                              .orientation_deg = options.lobe_orientation_deg,
                                              .centre_direction_deg = options.lobe_offset_deg});
  if (!scene) return std::unexpected(scene.error());
  const double lit = options.source_illuminance_lx / kDefaultReferenceIlluminanceLx;
  const SceneTruths truths = scene->truth(limit, lit);
  const auto peak = camera.project(truths.peak_ray);
  result.centre_pixel = {peak.x, peak.y};
  result.true_luminance_cd_m2 = scene->render(camera, options.width, options.height);
  for (float& value :
       std::span(result.true_luminance_cd_m2.data(), result.true_luminance_cd_m2.pixelCount()))
    value = static_cast<float>(value * lit);
  result.truth = truths.reference;
  result.truth_as_lit = truths.as_lit;
  return {};
}

}  // namespace

Result<SimulatedScene> renderSimulatedScene(const SimulationOptions& options) {
  GLARECAM_CHECK(options.validate());
  const double limit =
      pipeline::glareLimitCdM2(options.alpha_deg).value_or(pipeline::kConstantGlareLimitCdM2);
  if (options.background_cd_m2 >= limit) {
    return badInput(fmt::format(
        "simulate: --background ({:g} cd/m²) must be below the glare limit at this α ({:g} cd/m²)",
        options.background_cd_m2, limit));
  }
  SimulatedScene result;
  result.source_illuminance_lx = options.source_illuminance_lx;
  result.calibration = simulatedCalibration(options);
  const calibration::CameraModel camera(result.calibration.intrinsics);
  GLARECAM_CHECK(checkLensInvertible(camera, options.width, options.height));
  // The lobe's centre (the specular direction) must be in the frame.
  const auto centre = camera.project(
      calibration::rayFromDirection({options.lobe_offset_deg[0], options.lobe_offset_deg[1]}));
  if (!(centre.x >= 0 && centre.y >= 0 && centre.x <= options.width - 1 &&
        centre.y <= options.height - 1)) {
    return badInput("simulate: --offset-deg puts the lobe centre outside the frame");
  }
  GLARECAM_CHECK(options.surface.starts_with(kCurvesPrefix)
                     ? renderCurvesScene(options, limit, camera, result)
                     : renderSurfaceScene(options, limit, camera, result));
  return result;
}

std::uint64_t simulatedFrameSeed(std::uint64_t seed, std::uint64_t frame) {
  constexpr std::uint64_t kSeedStride = 1'000'003;  // a prime above any session's frame count
  return seed * kSeedStride + frame;
}

FrameSpec simulatedFrameSpec(const SimulationOptions& options, double exposure_us, double gain_db) {
  return {.file = {},
          .exposure_us = exposure_us,
          .gain_db = gain_db,
          .f_number = options.f_number,
          .nd_transmission = options.nd_transmission,
          .source = nlohmann::json::object()};
}

Result<SimulatedStack> simulateStack(const SimulationOptions& options) {
  Progress progress("simulate", 1 + options.bracket.min_frames, options.show_progress);
  SimulatedScene scene;
  GLARECAM_ASSIGN(scene, renderSimulatedScene(options));
  progress.advance("scene rendered");
  SimulatedStack result;
  result.true_luminance_cd_m2 = std::move(scene.true_luminance_cd_m2);
  result.truth = scene.truth;
  result.truth_as_lit = scene.truth_as_lit;
  result.source_illuminance_lx = scene.source_illuminance_lx;
  result.centre_pixel = scene.centre_pixel;
  const Calibration& calibration = scene.calibration;

  // Signal rates at the reference exposure of 1 µs, from a unit-exposure frame's radiometry.
  const FrameSpec unit = simulatedFrameSpec(options, 1.0, 0.0);
  const double scale = calibration::frameRadiometry(unit, calibration).scale_cd_m2_per_dn;
  const auto [peak, background] = meterScene(result.true_luminance_cd_m2);
  GLARECAM_ASSIGN(
      result.bracket,
      planBracket(peak / scale, background / scale,
                  calibration.saturation_dn - calibration.black_level_dn, options.bracket));
  result.manifest = makeManifest(options, calibration, result.bracket);
  progress.setTotal(1 + static_cast<int>(result.manifest.frames.size()));
  if (options.defects.any()) {
    result.defects =
        sensorDefectMap(options.width, options.height, options.defects, options.sensor_seed);
  }
  for (std::size_t i = 0; i < result.manifest.frames.size(); ++i) {
    result.frames.push_back(exposeFrame(result.true_luminance_cd_m2, result.manifest.frames[i],
                                        calibration, options.sensor, frameSeed(options.seed, i),
                                        options.defects.any() ? &result.defects : nullptr));
    progress.advance("frame " + std::to_string(i + 1) + "/" +
                     std::to_string(result.manifest.frames.size()));
  }
  return result;
}

Status writeSimulatedStack(const std::filesystem::path& directory, const SimulatedStack& stack) {
  StackWriteRequest request;
  request.manifest = stack.manifest;
  request.frames = stack.frames;
  request.text_files.emplace_back("truth.json", jsonText(stack.truthJson()));
  return writeStack(directory, request);
}

}  // namespace glarecam::capture
