#include "daemon/service_notifier.h"

#include <spdlog/spdlog.h>
#include <systemd/sd-daemon.h>

#include "core/error.h"

namespace glarecam::daemon {

namespace {

class SystemdNotifier final : public ServiceNotifier {
 public:
  SystemdNotifier() {
    std::uint64_t usec = 0;
    if (sd_watchdog_enabled(0, &usec) > 0 && usec > 0) watchdog_ = std::chrono::microseconds(usec);
  }

  void notify(const std::string& message) override {
    const int sent = sd_notify(0, message.c_str());
    if (sent < 0 && !warned_) {  // once: a broken socket would otherwise flood the log
      spdlog::warn("glarecamd: sd_notify: {}", errnoText(-sent));
      warned_ = true;
    }
  }

  std::optional<std::chrono::microseconds> watchdogInterval() const override { return watchdog_; }

 private:
  std::optional<std::chrono::microseconds> watchdog_;
  bool warned_ = false;
};

}  // namespace

std::unique_ptr<ServiceNotifier> makeSystemdNotifier() {
  return std::make_unique<SystemdNotifier>();
}

}  // namespace glarecam::daemon
