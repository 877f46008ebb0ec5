// What glarecamd watches besides its schedule, on the manual clock: systemd's watchdog fed at half
// its interval and not for a stuck worker, the disk against the reserve, the clock's warning.
#include "daemon/health_monitor.h"

#include <gtest/gtest.h>

#include <chrono>
#include <string>

#include "daemon/daemon_test_support.h"

namespace glarecam::daemon {
namespace {

using namespace std::chrono_literals;
using testing::ManualClock;
using testing::RecordingNotifier;
using testing::ScriptedDisk;
using testing::utc;

struct Monitored {
  ManualClock clock{utc("2026-06-21T08:00:00Z")};
  RecordingNotifier notifier;
  ScriptedDisk disk;
  HealthMonitor monitor{clock, notifier, disk};
  explicit Monitored(std::optional<std::chrono::microseconds> watchdog = 10s)
      : notifier(clock, watchdog) {
    monitor.start();
  }
  std::size_t pings() const { return notifier.count("WATCHDOG=1"); }
};

TEST(HealthMonitor, FeedsTheWatchdogAtHalfItsInterval) {
  Monitored m;
  const SteadyTime start = m.clock.now();
  EXPECT_EQ(m.monitor.nextWatchdog(), start);  // the first ping is due at once
  EXPECT_TRUE(m.monitor.feedWatchdog(std::nullopt));
  EXPECT_EQ(m.pings(), 1u);
  EXPECT_EQ(m.monitor.nextWatchdog(), start + 5s);
  EXPECT_FALSE(m.monitor.feedWatchdog(std::nullopt));  // not yet due: nothing sent
  m.clock.advance(4999ms);
  EXPECT_FALSE(m.monitor.feedWatchdog(std::nullopt));
  m.clock.advance(1ms);
  EXPECT_TRUE(m.monitor.feedWatchdog(std::nullopt));
  EXPECT_EQ(m.pings(), 2u);
  EXPECT_EQ(m.monitor.nextWatchdog(), start + 10s);
}

// Before a bracket of `away`: a ping that would fall due during it is sent now (the boundary,
// due exactly at its end, included), never twice at one instant.
TEST(HealthMonitor, APingDueDuringTheComingBracketIsSentBeforeIt) {
  Monitored m;
  EXPECT_TRUE(m.monitor.feedWatchdog(std::nullopt));
  EXPECT_FALSE(m.monitor.feedWatchdog(std::nullopt, 24h));  // the same instant: one is enough
  m.clock.advance(1s);
  EXPECT_FALSE(m.monitor.feedWatchdog(std::nullopt, 3999ms));  // due at 5 s, after the bracket
  EXPECT_TRUE(m.monitor.feedWatchdog(std::nullopt, 4s));       // due as the bracket ends
  EXPECT_EQ(m.pings(), 2u);
  EXPECT_EQ(m.monitor.nextWatchdog(), m.clock.now() + 5s);
}

TEST(HealthMonitor, WithoutAWatchdogNothingIsSent) {
  Monitored m(std::nullopt);
  EXPECT_FALSE(m.monitor.nextWatchdog());
  EXPECT_FALSE(m.monitor.feedWatchdog(std::nullopt));
  EXPECT_TRUE(m.notifier.messages().empty());
}

TEST(HealthMonitor, AStuckWorkerStopsTheHeartbeatUntilItIsDone) {
  Monitored m;
  const SteadyTime busy_since = m.clock.now();
  EXPECT_TRUE(m.monitor.feedWatchdog(busy_since));  // a job just started
  // Each call below is at a ping's due time (every 5 s from the start).
  m.clock.advance(kWorkerStallLimit - 5s);
  EXPECT_TRUE(m.monitor.feedWatchdog(busy_since));  // long, not yet stuck
  m.clock.advance(5s);
  EXPECT_FALSE(m.monitor.feedWatchdog(busy_since));  // stuck: systemd will restart the daemon
  m.clock.advance(10min);
  EXPECT_FALSE(m.monitor.feedWatchdog(busy_since));
  EXPECT_EQ(m.pings(), 2u);
  // The job ended: the heartbeat is back at the next ping.
  EXPECT_FALSE(m.monitor.feedWatchdog(std::nullopt));
  m.clock.advance(5s);
  EXPECT_TRUE(m.monitor.feedWatchdog(std::nullopt));
  EXPECT_EQ(m.pings(), 3u);
}

TEST(HealthMonitor, ChecksTheDiskAgainstTheReserve) {
  Monitored m;
  m.disk.set({.free_bytes = 50ull << 20, .total_bytes = 100ull << 30});
  const HealthMonitor::DiskCheck full = m.monitor.checkDisk("/data", 100ull << 20);
  EXPECT_EQ(full.pause_reason, "50.0 MiB free on /data, below the 100.0 MiB reserve");
  ASSERT_TRUE(full.state);
  EXPECT_EQ(full.state->free_bytes, 50ull << 20);
  EXPECT_EQ(m.monitor.nextDiskCheck(), m.clock.now() + kDiskCheckPeriod);
  m.clock.advance(3s);
  m.disk.set({.free_bytes = 1ull << 30, .total_bytes = 100ull << 30});
  EXPECT_TRUE(m.monitor.checkDisk("/data", 100ull << 20).pause_reason.empty());
  EXPECT_EQ(m.monitor.nextDiskCheck(), m.clock.now() + kDiskCheckPeriod);
  m.disk.set({.free_bytes = 1ull << 30, .total_bytes = 100ull << 30, .read_only = true});
  EXPECT_NE(m.monitor.checkDisk("/data", 0).pause_reason.find("read-only"), std::string::npos);
  EXPECT_EQ(m.disk.probes(), 3);
}

// A disk that cannot be examined.
class UnreadableDisk final : public DiskProbe {
 public:
  Result<DiskState> probe(const std::filesystem::path& path) override {
    return fail(ErrorCode::kIo, path.string() + ": statvfs: Input/output error");
  }
};

TEST(HealthMonitor, ADiskThatCannotBeExaminedPausesCaptureSayingWhy) {
  ManualClock clock(utc("2026-06-21T08:00:00Z"));
  RecordingNotifier notifier(clock);
  UnreadableDisk disk;
  HealthMonitor monitor(clock, notifier, disk);
  const HealthMonitor::DiskCheck check = monitor.checkDisk("/data", 0);
  EXPECT_EQ(check.pause_reason, "/data: statvfs: Input/output error");
  EXPECT_FALSE(check.state);
}

TEST(HealthMonitor, WarnsAboutTheClockOnlyWhenItIsNotSynchronised) {
  Monitored m;
  EXPECT_EQ(HealthMonitor::clockWarning(m.clock.clockStatus()), "");
  m.clock.setClockStatus({.synchronised = false, .detail = "kernel: STA_UNSYNC"});
  EXPECT_EQ(HealthMonitor::clockWarning(m.clock.clockStatus()),
            "not synchronised (kernel: STA_UNSYNC); stacks are flagged");
}

}  // namespace
}  // namespace glarecam::daemon
