#include "daemon/status/status_board.h"

namespace glarecam::daemon {

void StatusBoard::publish(StatusSnapshot snapshot) {
  auto next = std::make_shared<const StatusSnapshot>(std::move(snapshot));
  const std::lock_guard lock(mutex_);
  latest_.swap(next);  // the old one is released outside the lock, below, with `next`
}

std::shared_ptr<const StatusSnapshot> StatusBoard::latest() const {
  const std::lock_guard lock(mutex_);
  return latest_;
}

}  // namespace glarecam::daemon
