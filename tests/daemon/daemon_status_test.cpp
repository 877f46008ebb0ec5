// The daemon's state in one status line, and the LED showing the worst fault.
#include "daemon/daemon_status.h"

#include <gtest/gtest.h>

#include "daemon/daemon_test_support.h"

namespace glarecam::daemon {
namespace {

using testing::utc;

TEST(DaemonStatus, OneLineWithEveryFaultAndTheLedShowsTheWorst) {
  DaemonState state;
  state.ready = true;
  EXPECT_EQ(statusLine(state, "every 600 s"), "ready, every 600 s");
  EXPECT_EQ(ledState(state, false), rig::RigState::ready());
  EXPECT_EQ(ledState(state, true), rig::RigState::capturing());
  state.last_stack = "20260621T101503Z-a42.30";
  state.last_alpha_deg = 42.3;
  state.last_capture_time = utc("2026-06-21T10:15:03.25Z");
  state.next_capture_time = utc("2026-06-21T10:25:03Z");
  state.clock_warning = "not synchronised";
  EXPECT_EQ(statusLine(state, "every 600 s"),
            "ready, every 600 s; last 20260621T101503Z-a42.30 (α 42.30°) at "
            "2026-06-21T10:15:03Z; next at 2026-06-21T10:25:03Z; clock: not synchronised");
  EXPECT_EQ(ledState(state, false), rig::RigState::faulted(rig::FaultCode::kClock));
  state.disk_fault = "full";
  EXPECT_TRUE(statusLine(state, "x").starts_with("paused, x"));
  EXPECT_EQ(ledState(state, false), rig::RigState::faulted(rig::FaultCode::kDisk));
  state.camera_fault = "lost";
  EXPECT_EQ(ledState(state, false), rig::RigState::faulted(rig::FaultCode::kCamera));
  state.stopping = true;
  EXPECT_TRUE(statusLine(state, "x").starts_with("stopping, x"));
  EXPECT_EQ(statusLine(state, "x").find("next at"), std::string::npos);
}

}  // namespace
}  // namespace glarecam::daemon
