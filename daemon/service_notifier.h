// The service manager's side of the daemon: systemd's notify protocol (sd_notify(3)). READY=1
// once the hardware is open, STATUS= lines for `systemctl status`, WATCHDOG=1 heartbeats and
// STOPPING=1. Outside systemd (no NOTIFY_SOCKET) every call is a no-op, so glarecamd runs the same
// by hand. Tests record the messages instead, or point NOTIFY_SOCKET at a socket they read.
#pragma once

#include <chrono>
#include <memory>
#include <optional>
#include <string>

namespace glarecam::daemon {

class ServiceNotifier {
 public:
  virtual ~ServiceNotifier() = default;
  // One notify message: newline-separated assignments ("READY=1\nSTATUS=capturing").
  virtual void notify(const std::string& message) = 0;
  // WATCHDOG_USEC when the watchdog is enabled for this process (WATCHDOG_PID is ours or unset).
  virtual std::optional<std::chrono::microseconds> watchdogInterval() const = 0;
};

// sd_notify() to $NOTIFY_SOCKET; its watchdog from $WATCHDOG_USEC / $WATCHDOG_PID.
std::unique_ptr<ServiceNotifier> makeSystemdNotifier();

}  // namespace glarecam::daemon
