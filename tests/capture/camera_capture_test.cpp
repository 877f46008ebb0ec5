// The camera interface end to end without hardware: URIs and the registry, the `sim:` camera,
// the auto-bracket's decisions, and the bracketer writing stacks whose merged luminance matches
// the simulator's truth.
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "capture/auto_bracket.h"
#include "capture/bracketer.h"
#include "capture/camera_registry.h"
#include "capture/sim/sim_camera.h"
#include "core/stack_io.h"
#include "support/sim_support.h"

namespace glarecam::capture {
namespace {

constexpr double kRange = 3936.0;  // the simulated sensor: 4000 saturation - 64 black
const CameraLimits kLimits{.min_exposure_us = 10,
                           .max_exposure_us = 2e6,
                           .exposure_step_us = 1,
                           .min_gain_db = 0,
                           .max_gain_db = 24};

std::unique_ptr<Camera> openSim(const std::string& id, double alpha_deg = 40.0) {
  auto camera = openCamera("sim:" + id, {}, [alpha_deg] { return alpha_deg; });
  EXPECT_TRUE(camera) << camera.error().message;
  return camera ? std::move(*camera) : nullptr;
}

TEST(CameraUri, SplitsSchemeAndIdAndRefusesUnknownBackends) {
  auto uri = parseCameraUri("aravis:Aravis-Fake-GV01");
  ASSERT_TRUE(uri);
  EXPECT_EQ(uri->scheme, "aravis");
  EXPECT_EQ(uri->id, "Aravis-Fake-GV01");
  uri = parseCameraUri("v4l2:/dev/video0");
  ASSERT_TRUE(uri);
  EXPECT_EQ(uri->id, "/dev/video0");
  ASSERT_TRUE(parseCameraUri("sim"));  // a bare scheme is the first camera
  auto bad = parseCameraUri("gige:cam1");
  ASSERT_FALSE(bad);
  EXPECT_EQ(bad.error().code, ErrorCode::kBadInput);
  EXPECT_NE(bad.error().message.find("sim:, aravis:, libcamera:, v4l2:"), std::string::npos)
      << bad.error().message;
}

TEST(CameraRegistry, ListsEveryBackendAndTheSimulator) {
  const auto backends = cameraBackends();
  ASSERT_EQ(backends.size(), 4u);
  EXPECT_EQ(backends[0]->scheme(), "sim");
  auto sims = backends[0]->list();
  ASSERT_TRUE(sims);
  ASSERT_EQ(sims->size(), 1u);
  EXPECT_EQ(sims->front().uri, "sim:");
}

TEST(CameraRegistry, MissingDevicesFailWithTheUriAndNoCrash) {
  auto v4l2 = openCamera("v4l2:/dev/video-glarecam-missing", {});
  ASSERT_FALSE(v4l2);
  EXPECT_EQ(v4l2.error().code, ErrorCode::kHardware);
  EXPECT_NE(v4l2.error().message.find("v4l2:/dev/video-glarecam-missing"), std::string::npos);
  auto aravis = openCamera("aravis:glarecam-no-such-camera", {});
  ASSERT_FALSE(aravis);
  EXPECT_EQ(aravis.error().code, ErrorCode::kHardware);
  EXPECT_NE(aravis.error().message.find("aravis:glarecam-no-such-camera"), std::string::npos)
      << aravis.error().message;
}

TEST(SimCamera, ParsesItsParametersAndRefusesBadOnes) {
  auto options = parseSimCameraId("module=standard,size=320x256,fov=20,seed=3,alpha=55", {});
  ASSERT_TRUE(options) << options.error().message;
  EXPECT_EQ(options->width, 320);
  EXPECT_EQ(options->height, 256);
  EXPECT_EQ(options->seed, 3u);
  EXPECT_DOUBLE_EQ(options->alpha_deg, 55.0);
  EXPECT_DOUBLE_EQ(parseSimCameraId("", 20.0)->alpha_deg, 20.0);
  for (const char* bad : {"size=320", "fov=wide", "colour=red", "seed", "seed=-1", "seed=1e300",
                          "size=1e10x5", "size=0x0"}) {
    auto parsed = parseSimCameraId(bad, {});
    ASSERT_FALSE(parsed) << bad;
    EXPECT_EQ(parsed.error().code, ErrorCode::kBadInput) << bad;
  }
  auto tiny = openCamera("sim:size=8x8", {});
  ASSERT_FALSE(tiny);
  EXPECT_EQ(tiny.error().code, ErrorCode::kBadInput);
}

// Mean DN above black of the frame's top-left 32x32 corner: background only, far from the lobe.
double cornerSignal(const RawFrame& frame, double black_dn) {
  double sum = 0;
  for (int y = 0; y < 32; ++y) {
    for (int x = 0; x < 32; ++x) sum += frame.at(x, y);
  }
  return sum / (32 * 32) - black_dn;
}

TEST(SimCamera, ExposureScalesTheFramesAndIsRoundedLikeACamera) {
  auto camera = openSim("size=160x128");
  ASSERT_TRUE(camera);
  const std::vector<ExposureRequest> requests{{100.4, 0}, {40000, 0}, {80000, 0}, {40000, 6.0}};
  auto frames = camera->capture(requests);
  ASSERT_TRUE(frames) << frames.error().message;
  ASSERT_EQ(frames->size(), 4u);
  EXPECT_DOUBLE_EQ((*frames)[0].exposure_us, 100.0);  // 1 µs resolution
  EXPECT_DOUBLE_EQ((*frames)[3].gain_db, 6.0);
  const double black = camera->info().calibration->black_level_dn;
  const double signal_40ms = cornerSignal((*frames)[1].image, black);
  const double signal_80ms = cornerSignal((*frames)[2].image, black);
  const double signal_6db = cornerSignal((*frames)[3].image, black);
  // The background (about 70 DN at 40 ms) is linear in exposure and in linear gain (6 dB =
  // ×1.995); each mean of 1024 pixels carries about 0.5 % noise, so a ratio within 4 % is
  // about 6 σ.
  EXPECT_GT(signal_40ms, 30);
  EXPECT_NEAR(signal_80ms / signal_40ms, 2.0, 0.04);
  EXPECT_NEAR(signal_6db / signal_40ms, std::pow(10.0, 6.0 / 20.0), 0.04);
}

TEST(FrameLevels, IgnoreHotPixelsAndFindTheBackgroundPercentile) {
  RawFrame frame(100, 100, 164);  // background 100 DN above a black level of 64
  frame.at(5, 5) = 4095;          // one hot pixel
  for (int y = 40; y < 50; ++y) {
    for (int x = 40; x < 50; ++x) frame.at(x, y) = 2064;  // a 100-pixel peak at 2000 DN
  }
  FrameLevels levels = measureFrameLevels(frame, 64, 4000);
  EXPECT_DOUBLE_EQ(levels.peak_dn, 2000);
  EXPECT_DOUBLE_EQ(levels.background_dn, 100);
  EXPECT_FALSE(levels.peak_clipped);
  for (int x = 0; x < 100; ++x) frame.at(x, 60) = 4095;
  levels = measureFrameLevels(frame, 64, 4000);
  EXPECT_TRUE(levels.peak_clipped);
}

TEST(AutoBracket, MeteringShortensClippedPeaksAndLengthensDarkOnes) {
  const AutoBracketOptions options;
  // Clipped: a decade shorter.
  auto next = nextPeakMetering({1000, {kRange, 10, true}}, kRange, kLimits, options);
  ASSERT_TRUE(next);
  EXPECT_DOUBLE_EQ(*next, 100);
  // Dark (1 % of range): towards 70 % of range, at most 100× at once.
  next = nextPeakMetering({1000, {39.36, 1, false}}, kRange, kLimits, options);
  ASSERT_TRUE(next);
  EXPECT_NEAR(*next, 70000, 1);
  // Usable.
  EXPECT_FALSE(nextPeakMetering({1000, {2000, 1, false}}, kRange, kLimits, options));
  // At the camera's limit nothing better exists.
  EXPECT_FALSE(nextPeakMetering({10, {kRange, 10, true}}, kRange, kLimits, options));
  EXPECT_FALSE(nextPeakMetering({2e6, {1, 0, false}}, kRange, kLimits, options));
  // The background below 2 % of the range is metered longer, towards 50 % of the range.
  next = nextBackgroundMetering({1000, {2000, 0, false}}, kRange, kLimits, options);
  ASSERT_TRUE(next);
  EXPECT_DOUBLE_EQ(*next, 100000);
  EXPECT_FALSE(nextBackgroundMetering({1000, {2000, 100, false}}, kRange, kLimits, options));
}

TEST(AutoBracket, PlansWithinTheCameraLimits) {
  CameraLimits narrow = kLimits;
  narrow.min_exposure_us = 50;
  narrow.max_exposure_us = 20000;
  auto plan = planForRates(10.0, 1e-4, kRange, narrow, {});
  ASSERT_TRUE(plan) << plan.error().message;
  EXPECT_GE(plan->exposures_us.front(), 50);
  EXPECT_LE(plan->exposures_us.back(), 20000);
  EXPECT_TRUE(plan->background_underexposed);
  EXPECT_NEAR(clippedPeakRate(100, kRange), 10 * kRange / 100, 1e-9);
}

CaptureSettings quietAuto(double alpha_deg) {
  CaptureSettings settings;
  settings.alpha_deg = alpha_deg;
  return settings;
}

// The auto-bracket against the simulated rig: every rule of the issue on the planned frames,
// and the stack it writes reproduces the scene's truth through the whole pipeline.
TEST(Bracketer, AutoBracketOfTheSimulatedRigMatchesTheTruth) {
  for (const double alpha : {10.0, 60.0}) {
    auto camera = openSim("size=320x256,fov=20,seed=5", alpha);
    ASSERT_TRUE(camera);
    auto stack = captureStack(*camera, quietAuto(alpha));
    ASSERT_TRUE(stack) << stack.error().message;
    const auto& frames = stack->manifest.frames;
    ASSERT_GE(frames.size(), 6u) << alpha;
    for (std::size_t i = 1; i < frames.size(); ++i) {
      EXPECT_LE(frames[i].exposure_us / frames[i - 1].exposure_us, 10.0 * 1.001) << alpha;
    }
    const Calibration calibration = *camera->info().calibration;
    const FrameLevels shortest = measureFrameLevels(
        stack->frames.front(), calibration.black_level_dn, calibration.saturation_dn);
    EXPECT_FALSE(shortest.peak_clipped) << alpha;
    // Margin: the peak lands near 70 % of the range (noise and metering error: ±15 %).
    EXPECT_NEAR(shortest.peak_dn / kRange, 0.7, 0.15) << alpha;
    const FrameLevels longest = measureFrameLevels(stack->frames.back(), calibration.black_level_dn,
                                                   calibration.saturation_dn);
    EXPECT_GT(longest.background_dn / kRange, 0.3) << alpha;  // good SNR for the background
    const auto& log = stack->manifest.source["capture"]["auto_bracket"];
    EXPECT_GE(log["metering"].size(), 2u);
    EXPECT_EQ(log["rebrackets"], 0);

    testing::TempDir dir;
    auto written = writeCapturedStack(dir.path(), *stack);
    ASSERT_TRUE(written) << written.error().message;
    auto options = parseSimCameraId("size=320x256,fov=20,seed=5", {});
    options->alpha_deg = alpha;
    const auto scene = renderSimulatedScene(*options);
    ASSERT_TRUE(scene);
    // The issue-2 tolerance: maximum and axes within 1 % of the truth (process_stack_test).
    testing::expectProcessedMatchesTruth(*written, scene->truth, 0.01);
  }
}

TEST(Bracketer, FixedExposuresAreRecordedAsApplied) {
  auto camera = openSim("size=160x128");
  CaptureSettings settings = quietAuto(40);
  settings.exposures_us = std::vector<double>{100.3, 1000.7, 10000};
  auto stack = captureStack(*camera, settings);
  ASSERT_TRUE(stack) << stack.error().message;
  ASSERT_EQ(stack->manifest.frames.size(), 3u);
  EXPECT_DOUBLE_EQ(stack->manifest.frames[0].exposure_us, 100);
  EXPECT_DOUBLE_EQ(stack->manifest.frames[1].exposure_us, 1001);
  EXPECT_EQ(stack->manifest.source["capture"]["bracketing"], "fixed");
  EXPECT_EQ(stack->manifest.source["camera"]["backend"], "sim");
  EXPECT_DOUBLE_EQ(*stack->manifest.frames[0].f_number, 8.0);  // the simulated optics
  EXPECT_DOUBLE_EQ(stack->manifest.frames[0].source["requested_exposure_us"].get<double>(), 100.3);
  // The simulated camera's truth travels with the stack.
  ASSERT_TRUE(stack->truth);
  EXPECT_EQ((*stack->truth)["schema"], "glarecam.truth/1");
  testing::TempDir dir;
  auto written = writeCapturedStack(dir.path(), *stack);
  ASSERT_TRUE(written);
  EXPECT_TRUE(std::filesystem::is_regular_file(*written / "truth.json"));
}

TEST(Bracketer, ACaptureNeverReplacesAStackWrittenMeanwhile) {
  auto camera = openSim("size=64x48");
  CaptureSettings settings = quietAuto(40);
  settings.exposures_us = std::vector<double>{1000};
  auto stack = captureStack(*camera, settings);
  ASSERT_TRUE(stack);
  testing::TempDir dir;
  // Another process's stack under the name this one would take.
  StackWriteRequest other;
  other.manifest = stack->manifest;
  other.frames = stack->frames;
  other.text_files.emplace_back("marker.txt", "theirs");
  ASSERT_TRUE(writeStack(dir / *stack->manifest.id, other));
  StackWriteRequest mine = other;
  mine.may_replace = false;
  mine.text_files.clear();
  auto refused = writeStack(dir / *stack->manifest.id, mine);
  EXPECT_FALSE(refused);
  EXPECT_EQ(testing::readText(dir / *stack->manifest.id / "marker.txt"), "theirs");
  auto written = writeCapturedStack(dir.path(), *stack);
  ASSERT_TRUE(written) << written.error().message;
  EXPECT_EQ(written->filename().string(), *stack->manifest.id + "-2");
}

TEST(Bracketer, RefusesExposuresAndGainOutsideTheCamera) {
  auto camera = openSim("size=160x128");
  CaptureSettings settings;
  settings.exposures_us = std::vector<double>{1, 1000};
  auto stack = captureStack(*camera, settings);
  ASSERT_FALSE(stack);
  EXPECT_EQ(stack.error().code, ErrorCode::kBadInput);
  EXPECT_NE(stack.error().message.find("outside sim:size=160x128's range"), std::string::npos)
      << stack.error().message;
  settings.exposures_us.reset();
  settings.gain_db = 40;
  EXPECT_FALSE(captureStack(*camera, settings));
}

TEST(Bracketer, SeriesNeverOverwriteAStack) {
  auto camera = openSim("size=160x128");
  CaptureSettings settings = quietAuto(40);
  settings.exposures_us = std::vector<double>{1000, 10000};
  auto stack = captureStack(*camera, settings);
  ASSERT_TRUE(stack);
  testing::TempDir dir;
  auto first = writeCapturedStack(dir.path(), *stack);
  auto second = writeCapturedStack(dir.path(), *stack);
  ASSERT_TRUE(first && second);
  EXPECT_NE(*first, *second);
  EXPECT_EQ(second->filename().string(), first->filename().string() + "-2");
  auto read = readStack(*second);
  ASSERT_TRUE(read) << read.error().message;
  EXPECT_EQ(read->manifest.id, second->filename().string());
}

// A camera whose scene brightens after metering (the sun came out of a cloud): the shortest
// frame clips, and the bracketer must re-bracket shorter, boundedly, and record it.
class BrighteningCamera final : public Camera {
 public:
  explicit BrighteningCamera(double brighten_after_frames)
      : brighten_after_(brighten_after_frames) {}
  const CameraInfo& info() const override { return info_; }
  CameraLimits limits() const override { return kLimits; }
  SensorFormat format() const override { return {"Mono12", 64, 64, 16}; }

 private:
  Result<std::vector<CapturedFrame>> doCapture(std::span<const ExposureRequest> requests) override {
    std::vector<CapturedFrame> frames;
    for (const auto& request : requests) {
      const double peak_rate = taken_++ < brighten_after_ ? 1.0 : 20.0;  // DN/µs
      CapturedFrame frame;
      frame.exposure_us = std::round(request.exposure_us);
      frame.image = RawFrame(64, 64, 0);
      for (std::size_t i = 0; i < frame.image.pixelCount(); ++i) {
        const double rate = i < 400 ? peak_rate : 1e-3;
        frame.image.data()[i] =
            static_cast<std::uint16_t>(std::min(4095.0, 64 + rate * frame.exposure_us));
      }
      frames.push_back(std::move(frame));
    }
    return frames;
  }

  double brighten_after_;
  int taken_ = 0;
  CameraInfo info_ = [] {
    CameraInfo info;
    info.uri = "test:brightening";
    info.calibration = Calibration{};
    info.calibration->black_level_dn = 64;
    info.calibration->saturation_dn = 4000;
    return info;
  }();
};

TEST(Bracketer, ReBracketsShorterWhenThePeakClipsAfterMetering) {
  BrighteningCamera camera(
      2);  // the two metering frames see the dim scene, the bracket the bright one
  auto stack = captureStack(camera, {});
  ASSERT_TRUE(stack) << stack.error().message;
  const auto& log = stack->manifest.source["capture"]["auto_bracket"];
  EXPECT_EQ(log["rebrackets"], 1);
  EXPECT_EQ(log["peak_clipped"], false);
  const FrameLevels shortest = measureFrameLevels(stack->frames.front(), 64, 4000);
  EXPECT_FALSE(shortest.peak_clipped);
}

TEST(Bracketer, ReBracketingIsBoundedAndRecorded) {
  AutoBracketOptions options;
  options.max_rebrackets = 0;
  CaptureSettings settings;
  settings.auto_bracket = options;
  BrighteningCamera camera(2);
  auto stack = captureStack(camera, settings);
  ASSERT_TRUE(stack) << stack.error().message;
  const auto& log = stack->manifest.source["capture"]["auto_bracket"];
  EXPECT_EQ(log["rebrackets"], 0);
  EXPECT_EQ(log["peak_clipped"], true);
}

}  // namespace
}  // namespace glarecam::capture
