// Cameras by URI: the scheme and id, every backend listed, and missing devices failing with the
// URI and no crash.
#include "capture/camera_registry.h"

#include <gtest/gtest.h>

namespace glarecam::capture {
namespace {

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

}  // namespace
}  // namespace glarecam::capture
