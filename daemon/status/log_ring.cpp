#include "daemon/status/log_ring.h"

namespace glarecam::daemon {

std::vector<LogEntry> LogRing::entries() {
  const std::lock_guard lock(mutex_);
  return {entries_.begin(), entries_.end()};
}

void LogRing::sink_it_(const spdlog::details::log_msg& message) {
  if (capacity_ == 0) return;
  if (entries_.size() == capacity_) entries_.pop_front();
  const auto level = spdlog::level::to_string_view(message.level);
  entries_.push_back(
      {.time = message.time,
       .simulated_time = simulated_ ? std::optional(simulated_->utcNow()) : std::nullopt,
       .level = std::string(level.data(), level.size()),
       .text = std::string(message.payload.data(), message.payload.size())});
}

}  // namespace glarecam::daemon
