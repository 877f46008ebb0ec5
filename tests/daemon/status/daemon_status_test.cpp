// The daemon's state in one status line, and the LED showing the worst fault.
#include "daemon/status/daemon_status.h"

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
  EXPECT_NE(
      statusLine(state, "x").find("retention deleted 2 stacks, 0 result images, 1 results, 1 days"),
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

// Each tier counts apart; the last result's images pruned (or the result deleted) marks it so
// that the page stops offering its picture.
TEST(DaemonStatus, RetentionCountsEachTierAndMarksThePrunedLastResult) {
  DaemonState state;
  state.ready = true;
  state.last_result = LastResult{.stack_id = "b", .directory = "/out/results/b", .brief = {}};
  RetentionSummary summary;
  summary.deleted = {{kDeletedStack, "a", 10, "over the 1.0 GiB budget"},
                     {kDeletedResultImages, "a", 5, "over the 1.0 GiB budget"},
                     {kDeletedResultImages, "c", 5, "over the 1.0 GiB budget"},
                     {kDeletedResult, "d", 1, "over the 1.0 GiB budget"}};
  recordRetention(state, summary);
  EXPECT_FALSE(state.last_result->images_pruned);
  EXPECT_NE(
      statusLine(state, "x").find("retention deleted 1 stacks, 2 result images, 1 results, 0 days"),
      std::string::npos)
      << statusLine(state, "x");
  recordRetention(state, {.deleted = {{kDeletedResultImages, "b", 5, "below the reserve"}}});
  EXPECT_TRUE(state.last_result->images_pruned);
  EXPECT_EQ(state.result_images_pruned, 3u);
  recordRetention(state, {.shortfall = "over; the budget is smaller than one day's stacks",
                          .day_overflows = true});
  EXPECT_TRUE(state.retention_day_overflows);
}

// The status page's one word: the camera lost outranks a pause, a pause outranks the other
// faults, and warnings (clock, retention's budget) leave the rig capturing; the reason is the
// faults in the status line's words.
TEST(DaemonStatus, RigActivityNamesTheStateAndTheReasonInTheStatusLinesWords) {
  DaemonState state;
  EXPECT_EQ(rigActivity(state).state, "starting");
  state.ready = true;
  EXPECT_EQ(rigActivity(state).state, "capturing");
  EXPECT_EQ(rigActivity(state).reason, "");
  state.clock_warning = "not synchronised";
  state.retention_shortfall = "3.0 GiB used, over the 2.0 GiB budget";
  EXPECT_EQ(rigActivity(state).state, "capturing");
  EXPECT_EQ(rigActivity(state).reason,
            "clock: not synchronised; retention: 3.0 GiB used, over the 2.0 GiB budget");
  state.worker_fault = "stack x: bad frame";
  EXPECT_EQ(rigActivity(state).state, "fault");
  state.inclinometer_fault = "implausible tilt 50°";
  EXPECT_EQ(rigActivity(state).state, "fault");
  state.inclinometer_pauses = true;
  EXPECT_EQ(rigActivity(state).state, "paused");
  state.inclinometer_pauses = false;
  state.disk_fault = "12.0 MiB free, below the 1.0 GiB reserve";
  EXPECT_EQ(rigActivity(state).state, "paused");
  EXPECT_TRUE(rigActivity(state).reason.starts_with("disk: 12.0 MiB free"));
  state.camera_fault = "lost: no frame";
  EXPECT_EQ(rigActivity(state).state, "fault");
  EXPECT_TRUE(rigActivity(state).reason.starts_with("camera: lost: no frame; disk: "));
  // Every fault the status line names, in its words and order.
  const std::string line = statusLine(state, "x");
  for (const std::string& fault : statusFaults(state))
    EXPECT_NE(line.find(fault), std::string::npos) << fault;
  state.stopping = true;
  EXPECT_EQ(rigActivity(state).state, "stopping");
}

// The page's record of the last stack processed, the last day rebuilt and retention's last pass.
TEST(DaemonStatus, WorkerEventsAndRetentionKeepWhatThePageShows) {
  DaemonState state;
  recordWorkerEvent(
      state,
      {.stage = WorkerEvent::Stage::kProcessed,
       .stack_id = "20260621T101503Z-a42.30",
       .path = "/out/results/20260621T101503Z-a42.30",
       .result =
           ResultBrief{
               .alpha_deg = 42.3, .lmax_cd_m2 = 5.4e5, .limit_cd_m2 = 30000, .glare = true}},
      false);
  ASSERT_TRUE(state.last_result);
  EXPECT_EQ(state.last_result->stack_id, "20260621T101503Z-a42.30");
  EXPECT_EQ(state.last_result->directory, "/out/results/20260621T101503Z-a42.30");
  EXPECT_EQ(state.last_result->brief.glare, true);
  recordWorkerEvent(state,
                    {.stage = WorkerEvent::Stage::kPublished,
                     .stack_id = "20260621T101503Z-a42.30",
                     .path = "/out/days/2026-06-21",
                     .detail = "5 stacks, data sheet updated",
                     .last = true,
                     .day_stacks = 5,
                     .day_datasheet = true},
                    false);
  ASSERT_TRUE(state.last_day);
  EXPECT_EQ(state.last_day->day, "2026-06-21");
  EXPECT_EQ(state.last_day->stacks, 5u);
  EXPECT_TRUE(state.last_day->datasheet);
  // A failed processing leaves the last good result shown.
  recordWorkerEvent(state,
                    {.stage = WorkerEvent::Stage::kProcessed,
                     .stack_id = "b",
                     .error = Error{ErrorCode::kBadInput, "bad"},
                     .last = true},
                    false);
  EXPECT_EQ(state.last_result->stack_id, "20260621T101503Z-a42.30");
  recordRetention(state, {.deleted = {{"stack", "a", 10u << 20, "older than 2 days"},
                                      {"stack", "b", 12u << 20, "older than 2 days"}},
                          .freed_bytes = 22u << 20});
  EXPECT_EQ(state.retention_last,
            "deleted stack b (12.0 MiB): older than 2 days, with 1 more (22.0 MiB freed in all)");
}

}  // namespace
}  // namespace glarecam::daemon
