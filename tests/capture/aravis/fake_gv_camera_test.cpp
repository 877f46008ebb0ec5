// Aravis's GigE Vision fake camera serving a glare scene on loopback: one camera per port.
#include "capture/aravis/fake_gv_camera.h"

#include <gtest/gtest.h>

#include "capture/aravis/fake_gv_test_support.h"

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

}  // namespace
}  // namespace glarecam::capture
