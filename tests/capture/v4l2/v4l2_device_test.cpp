// The real V4L2 device path on nodes that are not cameras, and /dev/video0 when the machine has
// one.
#include "capture/v4l2/v4l2_device.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <vector>

#include "capture/v4l2/v4l2_backend.h"
#include "support/test_support.h"

namespace glarecam::capture {
namespace {

TEST(V4l2Device, AMissingNodeIsAOneLineHardwareError) {
  auto camera = makeV4l2Backend()->open("/dev/video-glarecam-missing", {});
  ASSERT_FALSE(camera);
  EXPECT_EQ(camera.error().code, ErrorCode::kHardware);
  EXPECT_EQ(camera.error().message, "v4l2:/dev/video-glarecam-missing: no such device");
}

TEST(V4l2Device, ARegularFileIsNotAV4l2Device) {
  testing::TempDir dir;
  std::ofstream(dir / "video0") << "not a camera";
  const auto path = (dir / "video0").string();
  auto camera = makeV4l2Backend()->open(path, {});
  ASSERT_FALSE(camera);
  EXPECT_EQ(camera.error().code, ErrorCode::kBadInput);
  EXPECT_EQ(camera.error().message,
            "v4l2:" + path + ": not a V4L2 device (not a character device)");
}

TEST(V4l2Device, ACharacterDeviceThatIsNoCameraIsNotAV4l2Device) {
  if (!std::filesystem::exists("/dev/null")) GTEST_SKIP() << "no /dev/null";
  auto camera = makeV4l2Backend()->open("/dev/null", {});
  ASSERT_FALSE(camera);
  EXPECT_EQ(camera.error().message,
            "v4l2:/dev/null: not a V4L2 device (VIDIOC_QUERYCAP not supported)");
}

// Listing probes every video* node through the real device path: nodes that are no camera (a
// file, a character device that is not V4L2) are skipped, not errors, and leave nothing to open.
TEST(V4l2Device, ListingSkipsNodesThatAreNoCamera) {
  testing::TempDir dev;
  std::ofstream(dev / "video0") << "not a camera";
  std::filesystem::create_symlink("/dev/null", dev / "video1");
  V4l2Options options;
  options.device_directory = dev.path().string();
  auto backend = makeV4l2Backend(openV4l2Device, options);
  auto cameras = backend->list();
  ASSERT_TRUE(cameras) << cameras.error().message;
  EXPECT_TRUE(cameras->empty());
  auto first = backend->open("", {});
  ASSERT_FALSE(first);
  EXPECT_EQ(first.error().code, ErrorCode::kHardware);
  EXPECT_EQ(first.error().message, "v4l2: no V4L2 capture device found in " + dev.path().string());
}

// Needs a mono V4L2 camera at /dev/video0; skipped elsewhere.
TEST(V4l2OnDevice, CapturesTwoExposuresFromVideo0) {
  if (!std::filesystem::exists("/dev/video0")) GTEST_SKIP() << "no /dev/video0 on this machine";
  auto camera = makeV4l2Backend()->open("/dev/video0", {});
  ASSERT_TRUE(camera) << camera.error().message;
  const auto limits = (*camera)->limits();
  const double short_us = std::max(limits.min_exposure_us, 1000.0);
  const std::vector<ExposureRequest> requests{{short_us, 0.0}, {2 * short_us, 0.0}};
  auto frames = (*camera)->capture(requests);
  ASSERT_TRUE(frames) << frames.error().message;
  ASSERT_EQ(frames->size(), 2u);
  for (const auto& frame : *frames) {
    EXPECT_EQ(frame.image.width(), (*camera)->format().width);
    EXPECT_EQ(frame.image.height(), (*camera)->format().height);
    EXPECT_GE(frame.exposure_us, limits.min_exposure_us);
  }
}

}  // namespace
}  // namespace glarecam::capture
