// Aravis's GigE Vision fake camera serving a glare scene on loopback: one camera per port.
#include "capture/aravis/fake_gv_camera.h"

#include <gtest/gtest.h>

#include <chrono>
#include <vector>

#include "capture/aravis/fake_gv_test_support.h"
#include "capture/camera_registry.h"

namespace glarecam::capture {
namespace {

using testing::loopbackScene;

TEST(AravisGigE, ASecondFakeCameraOnTheSamePortIsRefused) {
  auto first = FakeGvCamera::start(loopbackScene(40));
  ASSERT_TRUE(first) << first.error().message;
  auto second = FakeGvCamera::start(loopbackScene(40));
  ASSERT_FALSE(second);
  EXPECT_NE(second.error().message.find("UDP port 3956"), std::string::npos);
}

// Like a camera, it takes each exposure before it sends the frame: a bracket of 0.1 + 0.2 + 0.05 s
// lasts at least that (a lower bound the camera's sleep guarantees, not a speed measured), and
// the frames still arrive whole, with the control channel's heartbeat waiting out the exposures.
TEST(AravisGigE, TheFakeCameraTakesItsExposures) {
  auto fake = FakeGvCamera::start(loopbackScene(40));
  ASSERT_TRUE(fake) << fake.error().message;
  auto camera = openCamera((*fake)->uri(), {});
  ASSERT_TRUE(camera) << camera.error().message;
  const std::vector<ExposureRequest> requests{{100000, 0}, {200000, 0}, {50000, 0}};
  const auto started = std::chrono::steady_clock::now();
  auto frames = (*camera)->capture(requests);
  const auto elapsed = std::chrono::steady_clock::now() - started;
  ASSERT_TRUE(frames) << frames.error().message;
  ASSERT_EQ(frames->size(), 3u);
  EXPECT_GE(elapsed, std::chrono::milliseconds(350));
  for (const CapturedFrame& frame : *frames) EXPECT_EQ(frame.retries, 0);
}

}  // namespace
}  // namespace glarecam::capture
