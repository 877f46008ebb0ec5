// What the status page shows, handed from glarecamd's event loop to the page's server thread
// (status_server.h) as one immutable value: the loop publishes a new snapshot whenever it has
// looked at the rig (each step), the server takes the latest. Neither waits on the other for more
// than a pointer's copy, so that no client of the page can ever slow capture or the watchdog.
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <mutex>
#include <optional>
#include <string>

#include "core/time.h"
#include "daemon/status/daemon_status.h"
#include "daemon/storage/disk_space.h"

namespace glarecam::daemon {

struct StatusSnapshot {
  DaemonState state;
  std::string schedule;  // "at α targets", "every 600 s", "on the button"
  std::string camera_uri;
  bool camera_open = false;
  std::string inclinometer_uri;     // empty: the rig has none
  bool clock_synchronised = false;  // rigClockStatus (simulated_rig.h), as glarecam doctor says
  bool simulated_time = false;      // the daemon's times are a time lapse's (glarecamd --simulate)
  std::filesystem::path output_root;
  std::uint64_t reserve_bytes = 0;
  std::string retention_policy;  // "stacks 30 days, results 365 days, 50.0 GiB", or "off"
  UtcTime now{};                 // the daemon's clock when this was taken
  std::string today;             // the site's solar day of `now` (day_products.h)
};

class StatusBoard {
 public:
  void publish(StatusSnapshot snapshot);
  // The latest snapshot, or nullptr before the first.
  std::shared_ptr<const StatusSnapshot> latest() const;

 private:
  mutable std::mutex mutex_;
  std::shared_ptr<const StatusSnapshot> latest_;
};

}  // namespace glarecam::daemon
