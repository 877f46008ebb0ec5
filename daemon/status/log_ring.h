// The last log entries glarecamd wrote, kept in memory for the status page: an spdlog sink beside
// the journal's (or the console's) that holds the newest `capacity` entries and drops the oldest.
// Logging into it costs a string copy under its own mutex; the page copies the entries out.
#pragma once

#include <spdlog/sinks/base_sink.h>

#include <chrono>
#include <cstddef>
#include <deque>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "core/time.h"
#include "daemon/daemon_clock.h"

namespace glarecam::daemon {

// The status page's "last 50 log entries".
inline constexpr std::size_t kStatusLogEntries = 50;

struct LogEntry {
  std::chrono::system_clock::time_point time;  // the machine's clock
  std::optional<UtcTime> simulated_time{};     // the simulated clock's (glarecamd --simulate)
  std::string level;                           // spdlog's: "info", "warning", "error", ...
  std::string text;
};

class LogRing final : public spdlog::sinks::base_sink<std::mutex> {
 public:
  // `simulated`: the daemon's clock when it is a simulated one (DaemonClock::simulated()), whose
  // time each entry records beside the machine's.
  explicit LogRing(std::size_t capacity = kStatusLogEntries, const DaemonClock* simulated = nullptr)
      : capacity_(capacity), simulated_(simulated) {}
  // Oldest first.
  std::vector<LogEntry> entries();

 protected:
  void sink_it_(const spdlog::details::log_msg& message) override;
  void flush_() override {}

 private:
  std::size_t capacity_;
  const DaemonClock* simulated_;
  std::deque<LogEntry> entries_;  // guarded by base_sink's mutex_
};

}  // namespace glarecam::daemon
