// The libcamera backend against the real library: without a camera it lists nothing and fails
// quietly, backends share the one camera manager, and with a camera a bracket carries the
// requested exposures.
#include <gtest/gtest.h>

#include "core/build_config.h"
#if GLARECAM_WITH_LIBCAMERA
#include <algorithm>
#include <array>
#include <cstdlib>

#include "capture/libcamera/libcamera_backend.h"
#include "capture/libcamera/request_matching.h"
#endif

namespace glarecam::capture::libcam {
namespace {

#if GLARECAM_WITH_LIBCAMERA

// This machine and CI have no camera; a rig has one, and then the no-camera checks skip.
TEST(LibcameraBackend, WithoutACameraListsNothingAndOpenFailsQuietly) {
  const bool user_set_log_levels = std::getenv("LIBCAMERA_LOG_LEVELS") != nullptr;
  auto backend = makeLibcameraBackend();
  EXPECT_EQ(backend->scheme(), "libcamera");
  ::testing::internal::CaptureStderr();  // libcamera's own log lines would land here
  const auto cameras = backend->list();
  ASSERT_TRUE(cameras) << cameras.error().message;
  if (!cameras->empty()) {
    ::testing::internal::GetCapturedStderr();
    GTEST_SKIP() << "a libcamera camera is present";
  }
  const auto first = backend->open("", {});
  const auto named = backend->open("/base/soc/i2c0mux/i2c@1/imx477@1a", {});
  const std::string stderr_text = ::testing::internal::GetCapturedStderr();
  ASSERT_FALSE(first);
  EXPECT_EQ(first.error().code, ErrorCode::kHardware);
  EXPECT_EQ(first.error().message, "libcamera:: no camera found (libcamera 0.0.3 sees none)");
  ASSERT_FALSE(named);
  EXPECT_EQ(named.error().message.rfind("libcamera:/base/soc/i2c0mux/i2c@1/imx477@1a: ", 0), 0u)
      << named.error().message;
  if (!user_set_log_levels) {
    EXPECT_EQ(stderr_text, "");
  }
}

TEST(LibcameraBackend, BackendsShareTheOneCameraManager) {
  // libcamera aborts when a second CameraManager is built while one exists.
  auto first = makeLibcameraBackend();
  auto second = makeLibcameraBackend();
  EXPECT_TRUE(first->list());
  EXPECT_TRUE(second->list());
  first.reset();
  EXPECT_TRUE(second->list());
}

TEST(LibcameraBackend, OnDeviceTwoStepBracketCarriesTheRequestedExposures) {
  auto backend = makeLibcameraBackend();
  const auto cameras = backend->list();
  ASSERT_TRUE(cameras) << cameras.error().message;
  if (cameras->empty()) GTEST_SKIP() << "no libcamera camera present";
  auto camera = backend->open("", {});
  ASSERT_TRUE(camera) << camera.error().message;
  const CameraLimits limits = (*camera)->limits();
  const double short_us = std::max(1000.0, limits.min_exposure_us);
  const std::array<ExposureRequest, 2> bracket{{{short_us, 0.0}, {4 * short_us, 0.0}}};
  const auto frames = (*camera)->capture(bracket);
  ASSERT_TRUE(frames) << frames.error().message;
  ASSERT_EQ(frames->size(), 2u);
  const MatchRule rule{.exposure_rounding_us = std::min(100.0, limits.min_exposure_us)};
  for (std::size_t i = 0; i < bracket.size(); ++i) {
    EXPECT_TRUE(rule.exposureMatches(bracket[i].exposure_us, (*frames)[i].exposure_us))
        << "step " << i << ": " << (*frames)[i].exposure_us << " µs";
    EXPECT_EQ((*frames)[i].image.width(), (*camera)->format().width);
    EXPECT_EQ((*frames)[i].image.height(), (*camera)->format().height);
  }
  // Frames fill steps in whatever order their metadata says; each has its own timestamp.
  EXPECT_NE((*frames)[0].timestamp_ns, (*frames)[1].timestamp_ns);
}

#endif  // GLARECAM_WITH_LIBCAMERA

}  // namespace
}  // namespace glarecam::capture::libcam
