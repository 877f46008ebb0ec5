#include "daemon/daemon_events.h"

namespace glarecam::daemon {

void EventQueue::post(DaemonEvent event) {
  {
    const std::lock_guard lock(mutex_);
    events_.push_back(std::move(event));
  }
  wake_.notify_one();
}

std::optional<DaemonEvent> EventQueue::waitPop(SteadyTime deadline) {
  std::unique_lock lock(mutex_);
  clock_.waitUntil(lock, wake_, deadline, [this] { return !events_.empty(); });
  if (events_.empty()) return std::nullopt;
  DaemonEvent event = std::move(events_.front());
  events_.pop_front();
  return event;
}

std::optional<DaemonEvent> EventQueue::tryPop() {
  const std::lock_guard lock(mutex_);
  if (events_.empty()) return std::nullopt;
  DaemonEvent event = std::move(events_.front());
  events_.pop_front();
  return event;
}

}  // namespace glarecam::daemon
