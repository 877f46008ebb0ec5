// The Camera base class's contract (capture/camera.h): every request is checked against the
// camera's limits before a backend sees it, a bracket comes back with one frame per request, an
// exception becomes an Error, and every error names the camera's URI.
#include "capture/camera.h"

#include <gtest/gtest.h>

#include <limits>
#include <vector>

#include "capture/test_cameras.h"

namespace glarecam::capture {
namespace {

using testing::CountingCamera;

constexpr double kNan = std::numeric_limits<double>::quiet_NaN();

constexpr double kInf = std::numeric_limits<double>::infinity();

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

}  // namespace
}  // namespace glarecam::capture
