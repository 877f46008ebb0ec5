#include "capture/sim/calibration_targets.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

#include "calibration/camera_model.h"
#include "capture/sim/simulated_stack.h"
#include "core/angles.h"
#include "core/json.h"
#include "core/progress.h"
#include "core/stack_io.h"

namespace glarecam::capture {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

constexpr std::pair<CalibrationTarget, std::string_view> kTargetNames[] = {
    {CalibrationTarget::kDark, "dark"},           {CalibrationTarget::kFlat, "flat"},
    {CalibrationTarget::kLinearity, "linearity"}, {CalibrationTarget::kNoise, "noise"},
    {CalibrationTarget::kLuminance, "luminance"}, {CalibrationTarget::kBoard, "board"},
};

// The plans (exposures in µs; with the source at K cd/m² they are also the signal in DN).
constexpr double kDarkExposuresUs[] = {1000, 10000};
// Enough that the dark frame's own noise (2 DN / sqrt(32) = 0.35 DN) stays under the 0.5 DN
// fixed pattern it removes (calibrate dark warns otherwise).
constexpr int kDarkFramesPerExposure = 32;
constexpr double kFlatExposureUs = 2000;  // half the range at the principal point
constexpr int kFlatFrames = 8;
// Equal steps, as EMVA 1288 takes them: 120 µs apart, 3 % of the signal where the response bends.
constexpr double kRampFirstUs = 100, kRampLastUs = 4800;  // 2.5 % .. beyond the ADC's full scale
constexpr int kRampSteps = 40;
constexpr double kNoiseExposuresUs[] = {20, 60, 150, 300, 600, 1200, 2000, 3000};
constexpr double kLuminanceExposuresUs[] = {180, 720, 2880};
constexpr double kLinearityTolerance = 0.01;  // the truth's crossing, as the procedure's default
// The board: white and dark squares (lit to ~2400 and ~120 DN at the exposure), the wall behind.
constexpr double kBoardWhiteCdM2 = 3000, kBoardDarkCdM2 = 150, kBoardWallCdM2 = 800;
constexpr double kBoardExposureUs = 1200;
constexpr double kBoardDistanceMm = 750;
constexpr double kTiltXDeg = 35, kTiltYDeg = 40;  // the poses' largest tilts
// The simulated lens' principal point sits off the centre by this much (cx, cy): a calibration
// must find it, not assume the centre.
constexpr double kPrincipalOffsetXPx = 3.2, kPrincipalOffsetYPx = -2.1;

// The simulated camera as the target sees it: its sensor, K and f-number, without the ND filter.
SimulationOptions cameraOptions(const CalibrationTargetOptions& options) {
  SimulationOptions sim;
  static_cast<SimulatedCameraModel&>(sim) = options;
  sim.nd_transmission = 1.0;
  return sim;
}

Calibration targetCalibration(const CalibrationTargetOptions& options) {
  return simulatedCalibration(cameraOptions(options));
}

Intrinsics targetIntrinsics(const CalibrationTargetOptions& options) {
  Intrinsics k = pinholeIntrinsics(options.width, options.height, options.horizontal_fov_deg,
                                   options.distortion);
  k.cx += kPrincipalOffsetXPx;
  k.cy += kPrincipalOffsetYPx;
  return k;
}

FrameSpec frameSpec(const CalibrationTargetOptions& options, double exposure_us, int index) {
  return {.file = fmt::format("frame-{:02}.png", index),
          .exposure_us = exposure_us,
          .gain_db = 0,
          .f_number = options.f_number,
          .nd_transmission = 1.0,
          .source = json::object()};
}

// A stack of frames of `scene` at `exposures_us`, each frame with its own noise; `analogue`, when
// given, renders through a wider ADC so that a transform can bend the signal before it clips.
CalibrationTargetStack exposeStack(const CalibrationTargetOptions& options, const FloatImage& scene,
                                   std::span<const double> exposures_us,
                                   std::uint64_t first_frame = 0,
                                   const SensorModel* analogue = nullptr,
                                   const SensorDefectMap* defects = nullptr) {
  CalibrationTargetStack stack;
  const Calibration calibration = targetCalibration(options);
  const std::string name(calibrationTargetName(options.target));
  stack.manifest.id = fmt::format("sim-calibration-{}-s{}", name, options.seed);
  stack.manifest.captured_at = "2026-06-21T10:00:00Z";
  stack.manifest.source["camera"] = {
      {"backend", "sim"},         {"model", "glarecam simulated camera"},
      {"serial", options.serial}, {"pixel_format", fmt::format("Mono{}", options.sensor.adc_bits)},
      {"width", options.width},   {"height", options.height}};
  for (std::size_t i = 0; i < exposures_us.size(); ++i) {
    FrameSpec spec = frameSpec(options, exposures_us[i], static_cast<int>(i));
    stack.frames.push_back(exposeFrame(scene, spec, calibration,
                                       analogue ? *analogue : options.sensor,
                                       simulatedFrameSeed(options.seed, first_frame + i), defects));
    stack.manifest.frames.push_back(std::move(spec));
  }
  stack.truth = {{"schema", kTruthSchema}, {"target", name}};
  return stack;
}

// Applies `dn(x, y, raw)` to every pixel of every frame, rounding and clipping to the ADC.
template <typename Transform>
void transformFrames(CalibrationTargetStack& stack, const SensorModel& sensor,
                     Transform transform) {
  for (std::size_t f = 0; f < stack.frames.size(); ++f) {
    RawFrame& frame = stack.frames[f];
    const double exposure_us = stack.manifest.frames[f].exposure_us;
    for (int y = 0; y < frame.height(); ++y) {
      for (int x = 0; x < frame.width(); ++x) {
        const double dn = transform(x, y, static_cast<double>(frame.at(x, y)), exposure_us);
        frame.at(x, y) =
            static_cast<std::uint16_t>(std::clamp(std::round(dn), 0.0, sensor.full_scale_dn()));
      }
    }
  }
}

std::vector<double> repeated(std::span<const double> exposures, int times) {
  std::vector<double> out;
  for (double t : exposures)
    for (int i = 0; i < times; ++i) out.push_back(t);
  return out;
}

CalibrationTargetStack darkTarget(const CalibrationTargetOptions& options) {
  const FloatImage black(options.width, options.height, 0.0f);
  const SensorDefectMap defects = sensorDefectMap(
      options.width, options.height,
      {.fixed_pattern_dn = options.fixed_pattern_dn, .hot_pixels = options.hot_pixels},
      options.sensor_seed);
  CalibrationTargetStack stack = exposeStack(
      options, black, repeated(kDarkExposuresUs, kDarkFramesPerExposure), 0, nullptr, &defects);
  json hot_list = json::array();
  for (const auto& [x, y] : defects.hot_pixels) hot_list.push_back({x, y});
  stack.truth["black_level_dn"] = options.sensor.black_level_dn;
  stack.truth["fixed_pattern_dn"] = options.fixed_pattern_dn;
  stack.truth["hot_pixels"] = hot_list;
  return stack;
}

// A uniform source at K cd/m² seen through the lens' vignetting.
FloatImage vignettedSource(const CalibrationTargetOptions& options) {
  FloatImage scene = naturalVignetting(options.width, options.height, options.horizontal_fov_deg);
  for (std::size_t i = 0; i < scene.pixelCount(); ++i)
    scene.data()[i] *= static_cast<float>(options.luminance_factor);
  return scene;
}

CalibrationTargetStack flatTarget(const CalibrationTargetOptions& options) {
  const FloatImage scene = vignettedSource(options);
  const std::vector<double> exposures(kFlatFrames, kFlatExposureUs);
  CalibrationTargetStack stack = exposeStack(options, scene, exposures);
  stack.truth["flat_field"] = "cos^4 of the field angle (naturalVignetting)";
  stack.truth["horizontal_fov_deg"] = options.horizontal_fov_deg;
  return stack;
}

// The simulated response bend: signal s above the knee loses curvature (s - knee)².
double bentSignal(const CalibrationTargetOptions& options, double s) {
  const double over = s - options.nonlinearity_knee_dn;
  return over > 0 ? s - options.nonlinearity_curvature_per_dn * over * over : s;
}

// Signal at which the bend reaches the tolerance: bisection of (s - bent(s)) / s = tolerance.
double bendCrossingDn(const CalibrationTargetOptions& options, double tolerance) {
  double low = options.nonlinearity_knee_dn, high = 1e6;
  for (int i = 0; i < 200; ++i) {
    const double mid = (low + high) / 2;
    ((mid - bentSignal(options, mid)) / mid < tolerance ? low : high) = mid;
  }
  return low;
}

CalibrationTargetStack linearityTarget(const CalibrationTargetOptions& options) {
  const FloatImage scene(options.width, options.height,
                         static_cast<float>(options.luminance_factor));
  std::vector<double> exposures;
  for (int i = 0; i < kRampSteps; ++i)
    exposures.push_back(kRampFirstUs + (kRampLastUs - kRampFirstUs) * i / (kRampSteps - 1));
  // The bend is analogue: it comes before the ADC clips at its full scale (transformFrames).
  SensorModel analogue = options.sensor;
  analogue.adc_bits = 16;
  CalibrationTargetStack stack = exposeStack(options, scene, exposures, 0, &analogue);
  const double black = options.sensor.black_level_dn;
  transformFrames(stack, options.sensor, [&](int, int, double dn, double) {
    return black + bentSignal(options, dn - black);
  });
  const double crossing = bendCrossingDn(options, kLinearityTolerance);
  stack.truth["tolerance"] = kLinearityTolerance;
  // The raw DN at which the bend reaches the tolerance, unless the ADC clips first.
  stack.truth["saturation_dn"] =
      std::min(black + bentSignal(options, crossing), options.sensor.full_scale_dn());
  stack.truth["slope_dn_per_us"] = 1.0;
  return stack;
}

CalibrationTargetStack noiseTarget(const CalibrationTargetOptions& options) {
  const FloatImage scene = vignettedSource(options);
  CalibrationTargetStack stack = exposeStack(options, scene, repeated(kNoiseExposuresUs, 2));
  stack.truth["read_noise_dn"] = options.sensor.read_noise_dn;
  stack.truth["dn_per_electron"] = options.sensor.dn_per_electron;
  // Rounding to whole DN adds 1/12 DN² of variance to every reading (uniform quantisation).
  stack.truth["read_noise_with_quantisation_dn"] =
      std::sqrt(options.sensor.read_noise_dn * options.sensor.read_noise_dn + 1.0 / 12.0);
  return stack;
}

// The reference patch (the central quarter of the area) over its background, vignetted.
FloatImage referencePatch(const CalibrationTargetOptions& options) {
  FloatImage scene = naturalVignetting(options.width, options.height, options.horizontal_fov_deg);
  const int x0 = options.width / 4, y0 = options.height / 4;
  const int x1 = x0 + options.width / 2, y1 = y0 + options.height / 2;
  for (int y = 0; y < options.height; ++y) {
    for (int x = 0; x < options.width; ++x) {
      const bool patch = x >= x0 && x < x1 && y >= y0 && y < y1;
      scene.at(x, y) *=
          static_cast<float>(patch ? options.reference_cd_m2 : options.background_cd_m2);
    }
  }
  return scene;
}

CalibrationTargetStack luminanceTarget(const CalibrationTargetOptions& options) {
  const FloatImage scene = referencePatch(options);
  const int x0 = options.width / 4, y0 = options.height / 4;
  const int x1 = x0 + options.width / 2, y1 = y0 + options.height / 2;
  CalibrationTargetStack stack = exposeStack(options, scene, kLuminanceExposuresUs);
  constexpr int kMarginPx = 4;  // the ROI stays off the patch's edges
  stack.truth["luminance_factor"] = options.luminance_factor;
  stack.truth["reference_cd_m2"] = options.reference_cd_m2;
  stack.truth["roi"] = {x0 + kMarginPx, y0 + kMarginPx, x1 - x0 - 2 * kMarginPx,
                        y1 - y0 - 2 * kMarginPx};
  stack.truth["flat_field"] = "cos^4 of the field angle (naturalVignetting)";
  return stack;
}

// ---- the board ----------------------------------------------------------------------------

struct Pose {
  std::array<double, 9> rotation;  // row-major, board -> camera
  std::array<double, 3> translation_mm;
};

std::array<double, 9> rotationXyz(double ax, double ay, double az) {
  const double cx = std::cos(ax), sx = std::sin(ax), cy = std::cos(ay), sy = std::sin(ay),
               cz = std::cos(az), sz = std::sin(az);
  // Rz * Ry * Rx
  return {cz * cy,
          cz * sy * sx - sz * cx,
          cz * sy * cx + sz * sx,
          sz * cy,
          sz * sy * sx + cz * cx,
          sz * sy * cx - cz * sx,
          -sy,
          cy * sx,
          cy * cx};
}

// View k: the board's centre over a 3x3 grid of the image (and three more central views), tilted
// up to 25° so that focal length and distance separate.
Pose boardPose(const CalibrationTargetOptions& options, int k) {
  constexpr double kOffsetX = 0.14, kOffsetY = 0.1;  // of the distance: inside a 40° view
  const double ox = (k % 3 - 1) * kOffsetX * (k < 9), oy = (k / 3 % 3 - 1) * kOffsetY * (k < 9);
  const auto rotation =
      rotationXyz(radians(kTiltXDeg) * std::sin(1.3 * k + 0.4),
                  radians(kTiltYDeg) * std::cos(0.9 * k), radians(10.0) * std::sin(0.7 * k));
  const double centre_x = (options.board_inner_columns - 1) * options.board_square_mm / 2;
  const double centre_y = (options.board_inner_rows - 1) * options.board_square_mm / 2;
  const double z = kBoardDistanceMm;
  Pose pose{rotation, {}};
  pose.translation_mm = {ox * z - (rotation[0] * centre_x + rotation[1] * centre_y),
                         oy * z - (rotation[3] * centre_x + rotation[4] * centre_y),
                         z - (rotation[6] * centre_x + rotation[7] * centre_y)};
  return pose;
}

double boardLuminance(const CalibrationTargetOptions& options, double x_mm, double y_mm) {
  const int i = static_cast<int>(std::floor(x_mm / options.board_square_mm));
  const int j = static_cast<int>(std::floor(y_mm / options.board_square_mm));
  const int columns = options.board_inner_columns, rows = options.board_inner_rows;
  if (i >= -1 && i <= columns - 1 && j >= -1 && j <= rows - 1)
    return (i + j) % 2 == 0 ? kBoardDarkCdM2 : kBoardWhiteCdM2;
  if (i >= -2 && i <= columns && j >= -2 && j <= rows) return kBoardWhiteCdM2;  // margin
  return kBoardWallCdM2;
}

// Where a camera ray meets the board's plane, in board millimetres.
std::optional<std::pair<double, double>> onBoard(const Pose& pose, const calibration::Ray& ray) {
  const auto& r = pose.rotation;
  const auto& t = pose.translation_mm;
  // Rᵀ d and Rᵀ t.
  const double dz = r[2] * ray.x + r[5] * ray.y + r[8] * ray.z;
  const double tz = r[2] * t[0] + r[5] * t[1] + r[8] * t[2];
  if (std::abs(dz) < 1e-12) return std::nullopt;
  const double lambda = tz / dz;
  if (lambda <= 0) return std::nullopt;
  const double px = lambda * ray.x - t[0], py = lambda * ray.y - t[1], pz = lambda * ray.z - t[2];
  return std::pair{r[0] * px + r[3] * py + r[6] * pz, r[1] * px + r[4] * py + r[7] * pz};
}

// 2x2 samples a pixel would leave the squares' edges aliased by ~0.1 px; 4x4 brings the corners'
// scatter down to the sensor noise's.
constexpr int kBoardSamples = 4;

// The viewing rays of every sub-pixel sample, row by row (computed once for all views).
std::vector<calibration::Ray> sampleRays(const CalibrationTargetOptions& options) {
  const calibration::CameraModel camera(targetIntrinsics(options));
  std::vector<calibration::PixelPoint> samples;
  for (int y = 0; y < options.height; ++y)
    for (int x = 0; x < options.width; ++x)
      for (int sy = 0; sy < kBoardSamples; ++sy)
        for (int sx = 0; sx < kBoardSamples; ++sx)
          samples.push_back(
              {x + (sx + 0.5) / kBoardSamples - 0.5, y + (sy + 0.5) / kBoardSamples - 0.5});
  return camera.rays(samples);
}

FloatImage boardScene(const CalibrationTargetOptions& options,
                      const std::vector<calibration::Ray>& rays, int view) {
  constexpr int kPerPixel = kBoardSamples * kBoardSamples;
  const Pose pose = boardPose(options, view);
  FloatImage scene(options.width, options.height);
  for (std::size_t p = 0; p < scene.pixelCount(); ++p) {
    double sum = 0;
    for (int s = 0; s < kPerPixel; ++s) {
      const auto hit = onBoard(pose, rays[p * kPerPixel + s]);
      sum += hit ? boardLuminance(options, hit->first, hit->second) : kBoardWallCdM2;
    }
    scene.data()[p] = static_cast<float>(sum / kPerPixel);
  }
  return scene;
}

std::vector<CalibrationTargetStack> boardTarget(const CalibrationTargetOptions& options) {
  const std::vector<calibration::Ray> rays = sampleRays(options);
  const Intrinsics k = targetIntrinsics(options);
  std::vector<CalibrationTargetStack> stacks;
  for (int view = 0; view < options.board_views; ++view) {
    const double exposure[] = {kBoardExposureUs};
    CalibrationTargetStack stack =
        exposeStack(options, boardScene(options, rays, view), exposure, view);
    stack.manifest.id = fmt::format("sim-calibration-board-s{}-v{:02}", options.seed, view);
    stack.truth["intrinsics"] = {
        {"fx", k.fx}, {"fy", k.fy}, {"cx", k.cx}, {"cy", k.cy}, {"distortion", k.distortion}};
    stack.truth["board"] = {{"inner_columns", options.board_inner_columns},
                            {"inner_rows", options.board_inner_rows},
                            {"square_mm", options.board_square_mm}};
    stacks.push_back(std::move(stack));
  }
  return stacks;
}

Status validate(const CalibrationTargetOptions& options) {
  constexpr int kMinSide = 64, kMaxSide = 4096;
  if (options.width < kMinSide || options.height < kMinSide || options.width > kMaxSide ||
      options.height > kMaxSide)
    return badInput(fmt::format("simulate-calibration: --size must be between {0}x{0} and {1}x{1}",
                                kMinSide, kMaxSide));
  if (options.hot_pixels < 0 || options.hot_pixels > options.width * options.height / 100)
    return badInput("simulate-calibration: hot pixels must be between 0 and 1 % of the pixels");
  if (options.board_views < 1) return badInput("simulate-calibration: --views must be at least 1");
  return {};
}

}  // namespace

Result<CalibrationTarget> parseCalibrationTarget(std::string_view name) {
  std::string known;
  for (const auto& [target, target_name] : kTargetNames) {
    if (name == target_name) return target;
    known += (known.empty() ? "" : ", ") + std::string(target_name);
  }
  return badInput(fmt::format("unknown calibration target \"{}\" (known: {})", name, known));
}

std::string_view calibrationTargetName(CalibrationTarget target) {
  for (const auto& [t, name] : kTargetNames)
    if (t == target) return name;
  return "unknown";
}

Result<FloatImage> calibrationTargetScene(const CalibrationTargetOptions& options) {
  GLARECAM_CHECK(validate(options));
  switch (options.target) {
    case CalibrationTarget::kDark:
      return FloatImage(options.width, options.height, 0.0f);
    case CalibrationTarget::kFlat:
    case CalibrationTarget::kNoise:
      return vignettedSource(options);
    case CalibrationTarget::kLinearity:
      return FloatImage(options.width, options.height,
                        static_cast<float>(options.luminance_factor));
    case CalibrationTarget::kLuminance:
      return referencePatch(options);
    case CalibrationTarget::kBoard:
      return boardScene(options, sampleRays(options), 0);
  }
  return badInput("unknown calibration target");
}

FloatImage naturalVignetting(int width, int height, double horizontal_fov_deg) {
  const Intrinsics k = pinholeIntrinsics(width, height, horizontal_fov_deg);
  FloatImage field(width, height);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const double u = (x - k.cx) / k.fx, v = (y - k.cy) / k.fy;
      const double cos2 = 1.0 / (1.0 + u * u + v * v);
      field.at(x, y) = static_cast<float>(cos2 * cos2);
    }
  }
  return field;
}

Result<std::vector<CalibrationTargetStack>> simulateCalibrationTarget(
    const CalibrationTargetOptions& options) {
  GLARECAM_CHECK(validate(options));
  switch (options.target) {
    case CalibrationTarget::kDark:
      return std::vector{darkTarget(options)};
    case CalibrationTarget::kFlat:
      return std::vector{flatTarget(options)};
    case CalibrationTarget::kLinearity:
      return std::vector{linearityTarget(options)};
    case CalibrationTarget::kNoise:
      return std::vector{noiseTarget(options)};
    case CalibrationTarget::kLuminance:
      return std::vector{luminanceTarget(options)};
    case CalibrationTarget::kBoard:
      return boardTarget(options);
  }
  return badInput("unknown calibration target");
}

Result<std::vector<fs::path>> writeCalibrationTargetStacks(
    const fs::path& directory, CalibrationTarget target,
    const std::vector<CalibrationTargetStack>& stacks, bool show_progress) {
  std::vector<fs::path> written;
  const std::string name(calibrationTargetName(target));
  Progress progress("writing " + name, static_cast<int>(stacks.size()), show_progress);
  for (std::size_t i = 0; i < stacks.size(); ++i) {
    const fs::path path =
        directory / (stacks.size() == 1 ? name : fmt::format("{}-{:02}", name, i));
    StackWriteRequest request;
    request.manifest = stacks[i].manifest;
    request.frames = stacks[i].frames;
    request.text_files.emplace_back("truth.json", jsonText(stacks[i].truth));
    GLARECAM_CHECK(writeStack(path, request));
    written.push_back(path);
    progress.advance(path.filename().string());
  }
  progress.finish();
  return written;
}

}  // namespace glarecam::capture
