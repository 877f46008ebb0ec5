// The daemon's camera: the backoff between failed opens doubles to its cap, and a success clears
// the count.
#include "daemon/hardware/camera_supervisor.h"

#include <gtest/gtest.h>

#include <chrono>
#include <memory>
#include <string_view>

namespace glarecam::daemon {
namespace {

using namespace std::chrono_literals;

TEST(CameraSupervisor, BackoffDoublesToItsCapAndSuccessClearsTheCount) {
  int opens = 0;
  CameraSupervisor supervisor(
      {.camera_max_failures = 4, .camera_backoff = 2s, .camera_backoff_max = 10s},
      [&](std::string_view, const capture::CameraOptions&,
          const capture::SceneSource&) -> Result<std::unique_ptr<capture::Camera>> {
        ++opens;
        return hardwareError("absent");
      },
      {});
  supervisor.configure("sim:", {},
                       {.camera_max_failures = 4, .camera_backoff = 2s, .camera_backoff_max = 10s});
  EXPECT_EQ(supervisor.backoffAfter(1), 2s);
  EXPECT_EQ(supervisor.backoffAfter(2), 4s);
  EXPECT_EQ(supervisor.backoffAfter(3), 8s);
  EXPECT_EQ(supervisor.backoffAfter(4), 10s);
  EXPECT_EQ(supervisor.backoffAfter(40), 10s);
  const SteadyTime t0{};
  EXPECT_FALSE(supervisor.acquire(t0));
  EXPECT_EQ(supervisor.retryAt(), t0 + 2s);
  EXPECT_FALSE(supervisor.acquire(t0 + 1s));  // too soon: not even tried
  EXPECT_EQ(opens, 1);
  EXPECT_FALSE(supervisor.acquire(t0 + 2s));
  EXPECT_EQ(supervisor.failures(), 2);
  EXPECT_FALSE(supervisor.exhausted());
  supervisor.succeeded();
  EXPECT_EQ(supervisor.failures(), 0);
}

}  // namespace
}  // namespace glarecam::daemon
