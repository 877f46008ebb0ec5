// The status page's log: the newest entries, oldest first, whatever the logger's other sinks.
#include "daemon/status/log_ring.h"

#include <gtest/gtest.h>
#include <spdlog/logger.h>

#include <memory>

#include "daemon/daemon_test_support.h"

namespace glarecam::daemon {
namespace {

TEST(LogRing, KeepsTheNewestEntriesOldestFirst) {
  auto ring = std::make_shared<LogRing>(3);
  spdlog::logger logger("ring-test", ring);
  logger.set_level(spdlog::level::info);
  logger.debug("not kept: below the logger's level");
  for (int i = 1; i <= 5; ++i) logger.info("entry {}", i);
  logger.error("the error");
  const auto entries = ring->entries();
  ASSERT_EQ(entries.size(), 3u);
  EXPECT_EQ(entries[0].text, "entry 4");
  EXPECT_EQ(entries[1].text, "entry 5");
  EXPECT_EQ(entries[2].text, "the error");
  EXPECT_EQ(entries[0].level, "info");
  EXPECT_EQ(entries[2].level, "error");
  EXPECT_LE(entries[0].time, entries[2].time);
}

TEST(LogRing, HoldsTheStatusPagesFifty) {
  auto ring = std::make_shared<LogRing>();
  spdlog::logger logger("ring-test", ring);
  for (int i = 0; i < 120; ++i) logger.warn("w{}", i);
  const auto entries = ring->entries();
  ASSERT_EQ(entries.size(), kStatusLogEntries);
  EXPECT_EQ(entries.front().text, "w70");
  EXPECT_EQ(entries.back().text, "w119");
}

// On glarecamd --simulate the page's log mixed the machine's times with the simulated clock's:
// each entry keeps the machine's time, and the simulated clock's beside it.
TEST(LogRing, OnASimulatedClockEachEntryCarriesItsTimeToo) {
  testing::ManualClock machine(testing::utc("2026-12-06T04:00:00Z"));
  const TimeLapseClock simulated(testing::utc("2026-06-21T05:25:00Z"), 120.0, machine);
  auto ring = std::make_shared<LogRing>(kStatusLogEntries, &simulated);
  spdlog::logger logger("ring-test", ring);
  machine.advance(std::chrono::seconds(10));
  logger.info("captured");
  const auto entries = ring->entries();
  ASSERT_EQ(entries.size(), 1u);
  EXPECT_EQ(entries[0].simulated_time, testing::utc("2026-06-21T05:45:00Z"));
}

}  // namespace
}  // namespace glarecam::daemon
