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

// Retention in the status line: its deletions counted, or why it cannot free enough.
TEST(DaemonStatus, RetentionCountsItsDeletionsOrSaysWhyItCannotFreeEnough) {
  DaemonState state;
  state.ready = true;
  EXPECT_EQ(statusLine(state, "x").find("retention"), std::string::npos);
  RetentionSummary summary;
  summary.deleted = {{"stack", "a", 10, "older than 2 days"},
                     {"stack", "b", 10, "older than 2 days"},
                     {"result", "a", 5, "older than 9 days"},
                     {"day", "2026-06-01", 5, "older than 9 days"}};
  recordRetention(state, summary);
  EXPECT_EQ(state.stacks_deleted, 2u);
  EXPECT_EQ(state.results_deleted, 1u);
  EXPECT_EQ(state.days_deleted, 1u);
  EXPECT_NE(statusLine(state, "x").find("retention deleted 2 stacks, 1 results, 1 days"),
            std::string::npos);
  const RetentionSummary short_of_space{
      .shortfall =
          "3.0 GiB used, over the 2.0 GiB budget; nothing more may go (stacks kept: 4 "
          "of today)"};
  recordRetention(state, short_of_space);
  const std::string line = statusLine(state, "x");
  EXPECT_NE(line.find("retention: 3.0 GiB used, over the 2.0 GiB budget"), std::string::npos)
      << line;
  EXPECT_EQ(line.find("retention deleted"), std::string::npos) << line;
  recordRetention(state, {});
  EXPECT_TRUE(state.retention_shortfall.empty());
  EXPECT_EQ(state.stacks_deleted, 2u);
}

}  // namespace
}  // namespace glarecam::daemon
