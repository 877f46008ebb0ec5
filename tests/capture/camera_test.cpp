// The Camera base class's contract (capture/camera.h): every request is checked against the
// camera's limits before a backend sees it, a bracket comes back with one frame per request, an
// exception becomes an Error, and every error names the camera's URI; and the simulated camera's
// scene follows its α source.
#include "capture/camera.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>

#include "capture/camera_registry.h"
#include "capture/sim/sim_camera.h"

namespace glarecam::capture {
namespace {

constexpr double kNan = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

// A backend that counts what reaches it and answers as told.
class CountingCamera final : public Camera {
 public:
  enum class Answer { kFrames, kTooFew, kThrow, kError, kNamedError };

  explicit CountingCamera(CameraLimits limits, Answer answer = Answer::kFrames)
      : limits_(limits), answer_(answer) {
    info_.uri = "test:counting";
  }
  const CameraInfo& info() const override { return info_; }
  CameraLimits limits() const override { return limits_; }
  SensorFormat format() const override { return {"Mono8", 4, 4, 8}; }
  int calls() const { return calls_; }

 private:
  Result<std::vector<CapturedFrame>> doCapture(std::span<const ExposureRequest> requests) override {
    ++calls_;
    switch (answer_) {
      case Answer::kThrow:
        throw std::runtime_error("driver exploded");
      case Answer::kError:
        return hardwareError("control-lost");
      case Answer::kNamedError:
        return hardwareError("test:counting: control-lost");
      case Answer::kTooFew:
        return std::vector<CapturedFrame>(requests.size() - 1);
      case Answer::kFrames:
        break;
    }
    std::vector<CapturedFrame> frames(requests.size());
    for (std::size_t i = 0; i < requests.size(); ++i)
      frames[i].exposure_us = requests[i].exposure_us;
    return frames;
  }

  CameraInfo info_;
  CameraLimits limits_;
  Answer answer_;
  int calls_ = 0;
};

const CameraLimits kLimits{.min_exposure_us = 10,
                           .max_exposure_us = 1e6,
                           .exposure_step_us = 1,
                           .min_gain_db = 0,
                           .max_gain_db = 12};

TEST(Camera, PassesRequestsWithinItsLimits) {
  CountingCamera camera(kLimits);
  const std::vector<ExposureRequest> requests{{10, 0}, {1e6, 12}, {500, 6}};
  auto frames = camera.capture(requests);
  ASSERT_TRUE(frames) << frames.error().message;
  ASSERT_EQ(frames->size(), 3u);
  EXPECT_EQ((*frames)[1].exposure_us, 1e6);
  EXPECT_EQ(camera.calls(), 1);
}

TEST(Camera, NoRequestIsNoFrameAndNoCall) {
  CountingCamera camera(kLimits);
  auto frames = camera.capture({});
  ASSERT_TRUE(frames);
  EXPECT_TRUE(frames->empty());
  EXPECT_EQ(camera.calls(), 0);
}

TEST(Camera, RefusesRequestsOutsideItsLimitsBeforeTheBackendSeesThem) {
  struct Case {
    ExposureRequest request;
    const char* message;
  };
  const Case cases[] = {
      {{kNan, 0}, "test:counting: exposure nan µs is outside the camera's 10 … 1e+06 µs"},
      {{kInf, 0}, "exposure inf µs is outside"},
      {{-5, 0}, "exposure -5 µs is outside"},
      {{0, 0}, "exposure 0 µs is outside"},
      {{9.99, 0}, "exposure 9.99 µs is outside"},
      {{1.1e6, 0}, "exposure 1.1e+06 µs is outside"},
      {{100, kNan}, "test:counting: gain nan dB is outside the camera's 0 … 12 dB"},
      {{100, -1}, "gain -1 dB is outside"},
      {{100, 12.5}, "gain 12.5 dB is outside"},
  };
  for (const Case& c : cases) {
    CountingCamera camera(kLimits);
    // The bad request is second: nothing of the bracket may be taken.
    const std::vector<ExposureRequest> requests{{100, 0}, c.request};
    auto frames = camera.capture(requests);
    ASSERT_FALSE(frames) << c.message;
    EXPECT_EQ(frames.error().code, ErrorCode::kBadInput) << c.message;
    EXPECT_NE(frames.error().message.find(c.message), std::string::npos)
        << frames.error().message << "\nwant: " << c.message;
    EXPECT_EQ(camera.calls(), 0) << c.message;
  }
}

TEST(Camera, AGainTheCameraDoesNotHaveIsRefused) {
  CameraLimits no_gain = kLimits;
  no_gain.max_gain_db = 0;
  CountingCamera camera(no_gain);
  const std::vector<ExposureRequest> requests{{100, 3}};
  auto frames = camera.capture(requests);
  ASSERT_FALSE(frames);
  EXPECT_EQ(frames.error().message,
            "test:counting: gain 3 dB requested, but the camera has no analogue gain");
  EXPECT_TRUE(camera.capture(std::vector<ExposureRequest>{{100, 0}}));
}

TEST(Camera, AnUnknownLongestExposureIsNoUpperBound) {
  CameraLimits open_ended = kLimits;
  open_ended.max_exposure_us = 0;
  CountingCamera camera(open_ended);
  EXPECT_TRUE(camera.capture(std::vector<ExposureRequest>{{5e7, 0}}));
}

TEST(Camera, AShortBracketIsAnErrorNamingTheCamera) {
  CountingCamera camera(kLimits, CountingCamera::Answer::kTooFew);
  auto frames = camera.capture(std::vector<ExposureRequest>{{100, 0}, {200, 0}});
  ASSERT_FALSE(frames);
  EXPECT_EQ(frames.error().code, ErrorCode::kInternal);
  EXPECT_EQ(frames.error().message, "test:counting: 1 frames for 2 requests");
}

TEST(Camera, AnExceptionBecomesAnErrorNamingTheCamera) {
  CountingCamera camera(kLimits, CountingCamera::Answer::kThrow);
  auto frames = camera.capture(std::vector<ExposureRequest>{{100, 0}});
  ASSERT_FALSE(frames);
  EXPECT_EQ(frames.error().code, ErrorCode::kInternal);
  EXPECT_EQ(frames.error().message, "test:counting: internal error: driver exploded");
}

TEST(Camera, ErrorsNameTheCameraOnce) {
  CountingCamera unnamed(kLimits, CountingCamera::Answer::kError);
  auto lost = unnamed.capture(std::vector<ExposureRequest>{{100, 0}});
  ASSERT_FALSE(lost);
  EXPECT_EQ(lost.error().code, ErrorCode::kHardware);
  EXPECT_EQ(lost.error().message, "test:counting: control-lost");
  CountingCamera named(kLimits, CountingCamera::Answer::kNamedError);
  EXPECT_EQ(named.capture(std::vector<ExposureRequest>{{100, 0}}).error().message,
            "test:counting: control-lost");
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
  auto camera = openCamera("sim:size=64x48", {}, [&] { return alpha_deg; });
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

TEST(SimCamera, OpensUnderALowSunAndRefusesOnlyTheBracket) {
  std::optional<double> alpha_deg = 85.0;  // the sun low behind the module: no scene there
  auto camera = openCamera("sim:size=64x48", {}, [&] { return alpha_deg; });
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
  auto contradicted = openCamera("sim:size=64x48,alpha=40", {}, [&] { return alpha_deg; });
  ASSERT_FALSE(contradicted);
  EXPECT_NE(contradicted.error().message.find("alpha=40 contradicts the capture's α 20"),
            std::string::npos)
      << contradicted.error().message;
  alpha_deg.reset();
  auto fixed = openCamera("sim:size=64x48,alpha=40", {}, [&] { return alpha_deg; });
  ASSERT_TRUE(fixed) << fixed.error().message;
  alpha_deg = 60.0;
  ASSERT_TRUE((*fixed)->capture(std::vector<ExposureRequest>{{1000, 0}}));
  EXPECT_DOUBLE_EQ(truthAlpha(**fixed), 40.0);
}

TEST(SimCamera, KnowsItsCalibrationAndRealCamerasTellNoTruth) {
  auto camera = openCamera("sim:size=64x48", {});
  ASSERT_TRUE(camera);
  ASSERT_TRUE((*camera)->info().calibration);
  EXPECT_GT((*camera)->info().calibration->luminance_factor, 0);
  CountingCamera real(kLimits);
  EXPECT_FALSE(sceneTruthOf(real));
  EXPECT_FALSE(real.info().calibration);
}

}  // namespace
}  // namespace glarecam::capture
