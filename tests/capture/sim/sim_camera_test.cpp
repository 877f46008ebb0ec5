// The sim: camera: its URI's parameters, frames that scale with exposure and gain and are rounded
// like a camera's, its scene following its α source, and its calibration and truth.
#include "capture/sim/sim_camera.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <optional>
#include <vector>

#include "capture/camera_registry.h"
#include "capture/test_cameras.h"

namespace glarecam::capture {
namespace {

constexpr double kNan = std::numeric_limits<double>::quiet_NaN();

using testing::CountingCamera;
using testing::kSimLimits;
using testing::openSim;

TEST(SimCamera, ParsesItsParametersAndRefusesBadOnes) {
  auto options = parseSimCameraId("module=standard,size=320x256,fov=20,seed=3,alpha=55", {});
  ASSERT_TRUE(options) << options.error().message;
  EXPECT_EQ(options->width, 320);
  EXPECT_EQ(options->height, 256);
  EXPECT_EQ(options->seed, 3u);
  EXPECT_DOUBLE_EQ(options->alpha_deg, 55.0);
  EXPECT_DOUBLE_EQ(parseSimCameraId("", 20.0)->alpha_deg, 20.0);
  EXPECT_EQ(options->surface, "curves:standard");  // module=NAME is the module's curves
  EXPECT_EQ(parseSimCameraId("surface=glare-reduced", {})->surface, "glare-reduced");
  for (const char* bad :
       {"size=320", "fov=wide", "colour=red", "seed", "seed=-1", "seed=1e300", "size=1e10x5",
        "size=0x0", "module=standard,surface=standard", "surface=standard,surface=glare-reduced"}) {
    auto parsed = parseSimCameraId(bad, {});
    ASSERT_FALSE(parsed) << bad;
    EXPECT_EQ(parsed.error().code, ErrorCode::kBadInput) << bad;
  }
  // A surface the catalogue does not know is refused when the camera opens, naming the known ones.
  auto unknown = openCamera("sim:size=64x48,surface=velvet", {});
  ASSERT_FALSE(unknown);
  EXPECT_EQ(unknown.error().code, ErrorCode::kBadInput);
  EXPECT_NE(unknown.error().message.find("glare-reduced"), std::string::npos)
      << unknown.error().message;
  auto surface = openCamera("sim:size=64x48,surface=glare-reduced", {});
  ASSERT_TRUE(surface) << surface.error().message;
  EXPECT_NE((*surface)->info().model.find("surface-glare-reduced"), std::string::npos);
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

// Its timestamps are a camera's over Gigabit Ethernet: each frame starts when the previous one's
// exposure and transfer ended. 160x128 16-bit frames are 40 960 bytes, 345 µs at 118.75 MB/s;
// exact to the nanosecond the clock is rounded to.
TEST(SimCamera, ItsClockTakesEachExposureAndTransfer) {
  auto camera = openSim("size=160x128");
  ASSERT_TRUE(camera);
  const std::vector<ExposureRequest> requests{{1000, 0}, {250000, 0}, {20, 0}};
  auto frames = camera->capture(requests);
  ASSERT_TRUE(frames) << frames.error().message;
  const double transfer_ns = 160 * 128 * 2 / kGigabitPayloadBytesPerS * 1e9;
  EXPECT_NEAR(transfer_ns, 344926, 1);
  EXPECT_EQ((*frames)[0].timestamp_ns, 0u);
  EXPECT_NEAR(static_cast<double>((*frames)[1].timestamp_ns), 1000e3 + transfer_ns, 1);
  EXPECT_NEAR(static_cast<double>((*frames)[2].timestamp_ns - (*frames)[1].timestamp_ns),
              250000e3 + transfer_ns, 1);
  // The next bracket goes on where this one ended: the camera's time for all three.
  auto next = camera->capture(std::vector<ExposureRequest>{{10, 0}});
  ASSERT_TRUE(next) << next.error().message;
  EXPECT_NEAR(static_cast<double>((*next)[0].timestamp_ns),
              1e9 * bracketFloorS(requests, 160 * 128 * 2), 2);
}

TEST(SimCamera, RefusesANanExposure) {
  auto camera = openCamera("sim:size=64x48", {});
  ASSERT_TRUE(camera) << camera.error().message;
  auto frames = (*camera)->capture(std::vector<ExposureRequest>{{kNan, 0}});
  ASSERT_FALSE(frames);
  EXPECT_EQ(frames.error().code, ErrorCode::kBadInput);
  EXPECT_TRUE(frames.error().message.starts_with("sim:size=64x48: exposure nan µs"))
      << frames.error().message;
}

double truthAlpha(const Camera& camera) {
  const auto truth = sceneTruthOf(camera);
  EXPECT_TRUE(truth);
  return truth ? truth->value("alpha_deg", -1.0) : -1.0;
}

TEST(SimCamera, ItsSceneFollowsItsAlphaSource) {
  std::optional<double> alpha_deg = 30.0;
  auto camera =
      openCamera("sim:size=64x48", {}, [&] { return SceneState{.alpha_deg = alpha_deg}; });
  ASSERT_TRUE(camera) << camera.error().message;
  EXPECT_DOUBLE_EQ(truthAlpha(**camera), 30.0);  // asked at the open
  const std::vector<ExposureRequest> one{{1000, 0}};
  alpha_deg = 55.0;
  ASSERT_TRUE((*camera)->capture(one));
  EXPECT_DOUBLE_EQ(truthAlpha(**camera), 55.0);  // rendered again before the bracket
  EXPECT_NE((*camera)->info().detail.find("α 55°"), std::string::npos);
  alpha_deg.reset();  // α not known: the scene stays
  ASSERT_TRUE((*camera)->capture(one));
  EXPECT_DOUBLE_EQ(truthAlpha(**camera), 55.0);
  // Just past 80° (an inclinometer's noise on an 80° target) shows the 80° scene; beyond is
  // refused, naming the camera.
  alpha_deg = 80.0 + kSceneAlphaSlackDeg / 2;
  ASSERT_TRUE((*camera)->capture(one));
  EXPECT_DOUBLE_EQ(truthAlpha(**camera), 80.0);
  alpha_deg = 80.0 + 2 * kSceneAlphaSlackDeg;
  auto beyond = (*camera)->capture(one);
  ASSERT_FALSE(beyond);
  EXPECT_EQ(beyond.error().code, ErrorCode::kBadInput);
  EXPECT_NE(beyond.error().message.find("must be within 0…80°"), std::string::npos)
      << beyond.error().message;
}

// The sun that lights the scene follows the source too (a rig's clear-sky sun), and lights the
// frames in proportion; a URI's illuminance= fixes it.
TEST(SimCamera, ItsSunFollowsItsSource) {
  SceneState state{.alpha_deg = 30.0, .source_illuminance_lx = 60'000.0};
  auto camera = openCamera("sim:size=64x48", {}, [&] { return state; });
  ASSERT_TRUE(camera) << camera.error().message;
  const auto lit = [&] { return sceneTruthOf(**camera)->value("source_illuminance_lx", -1.0); };
  EXPECT_DOUBLE_EQ(lit(), 60'000.0);  // asked at the open
  // Long enough that the background (the median pixel) stands some 100 DN above the black level.
  const std::vector<ExposureRequest> one{{100'000, 0}};
  const double black_dn = SensorModel{}.black_level_dn;
  const auto median = [&] {
    auto frames = (*camera)->capture(one);
    EXPECT_TRUE(frames) << frames.error().message;
    const auto& image = (*frames)[0].image;
    std::vector<std::uint16_t> values(image.data(), image.data() + image.pixelCount());
    std::ranges::nth_element(values, values.begin() + values.size() / 2);
    return values[values.size() / 2] - black_dn;
  };
  const double at_60 = median();
  state.source_illuminance_lx = 90'000.0;
  const double at_90 = median();
  EXPECT_DOUBLE_EQ(lit(), 90'000.0);  // rendered again before the bracket
  // Lobe and background both scale with E: the background's signal by 1.5; 3 % for the median's
  // whole DN and noise.
  std::printf("median signal %.1f DN at 60 klx, %.1f DN at 90 klx\n", at_60, at_90);
  EXPECT_GT(at_90 / at_60, 1.45);
  EXPECT_LT(at_90 / at_60, 1.55);
  state.source_illuminance_lx.reset();  // not known: the scene stays
  median();
  EXPECT_DOUBLE_EQ(lit(), 90'000.0);
  auto fixed = openCamera("sim:size=64x48,illuminance=70000", {}, [&] { return state; });
  ASSERT_TRUE(fixed) << fixed.error().message;
  state.source_illuminance_lx = 50'000.0;
  ASSERT_TRUE((*fixed)->capture(one));
  EXPECT_DOUBLE_EQ(sceneTruthOf(**fixed)->value("source_illuminance_lx", -1.0), 70'000.0);
  // An absurd sun from the source is refused by the bracket, naming the range.
  state.source_illuminance_lx = 500'000.0;
  auto absurd = (*camera)->capture(one);
  ASSERT_FALSE(absurd);
  EXPECT_EQ(absurd.error().code, ErrorCode::kBadInput);
}

TEST(SimCamera, OpensUnderALowSunAndRefusesOnlyTheBracket) {
  std::optional<double> alpha_deg = 85.0;  // the sun low behind the module: no scene there
  auto camera =
      openCamera("sim:size=64x48", {}, [&] { return SceneState{.alpha_deg = alpha_deg}; });
  ASSERT_TRUE(camera) << camera.error().message;
  const std::vector<ExposureRequest> one{{1000, 0}};
  auto refused = (*camera)->capture(one);
  ASSERT_FALSE(refused);
  EXPECT_EQ(refused.error().code, ErrorCode::kBadInput);
  alpha_deg = 75.0;  // the sun rose: the camera was never lost
  ASSERT_TRUE((*camera)->capture(one));
  EXPECT_DOUBLE_EQ(truthAlpha(**camera), 75.0);
}

TEST(SimCamera, AnAlphaInItsUriIsKeptAndMayNotBeContradicted) {
  std::optional<double> alpha_deg = 20.0;
  auto contradicted =
      openCamera("sim:size=64x48,alpha=40", {}, [&] { return SceneState{.alpha_deg = alpha_deg}; });
  ASSERT_FALSE(contradicted);
  EXPECT_NE(contradicted.error().message.find("alpha=40 contradicts the capture's α 20"),
            std::string::npos)
      << contradicted.error().message;
  alpha_deg = 85.0;  // beyond the scene's range: still a contradiction, not a low sun
  contradicted =
      openCamera("sim:size=64x48,alpha=40", {}, [&] { return SceneState{.alpha_deg = alpha_deg}; });
  ASSERT_FALSE(contradicted);
  EXPECT_NE(contradicted.error().message.find("alpha=40 contradicts the capture's α 85"),
            std::string::npos)
      << contradicted.error().message;

  // Opened before α is known, the URI's α is kept, and every bracket checks it: a stack must
  // never record one α and show another.
  alpha_deg.reset();
  auto fixed =
      openCamera("sim:size=64x48,alpha=40", {}, [&] { return SceneState{.alpha_deg = alpha_deg}; });
  ASSERT_TRUE(fixed) << fixed.error().message;
  const std::vector<ExposureRequest> one{{1000, 0}};
  ASSERT_TRUE((*fixed)->capture(one));
  EXPECT_DOUBLE_EQ(truthAlpha(**fixed), 40.0);
  alpha_deg = 40.0;
  ASSERT_TRUE((*fixed)->capture(one));
  alpha_deg = 60.0;
  auto moved = (*fixed)->capture(one);
  ASSERT_FALSE(moved);
  EXPECT_EQ(moved.error().code, ErrorCode::kBadInput);
  EXPECT_NE(moved.error().message.find("alpha=40 contradicts the capture's α 60"),
            std::string::npos)
      << moved.error().message;
  EXPECT_DOUBLE_EQ(truthAlpha(**fixed), 40.0);
}

TEST(SimCamera, KnowsItsCalibrationAndRealCamerasTellNoTruth) {
  auto camera = openCamera("sim:size=64x48", {});
  ASSERT_TRUE(camera);
  ASSERT_TRUE((*camera)->info().calibration);
  EXPECT_GT((*camera)->info().calibration->luminance_factor, 0);
  CountingCamera real(kSimLimits);
  EXPECT_FALSE(sceneTruthOf(real));
  EXPECT_FALSE(real.info().calibration);
}

}  // namespace
}  // namespace glarecam::capture
