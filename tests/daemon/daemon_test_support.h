// Test doubles for glarecamd's core (daemon/): a manual clock that jumps to each deadline
// and runs scheduled alarms (signals, presses, a disk filling up) at exact times, a notifier that
// records every sd_notify message with its time, a scripted disk, and a camera that fails or
// wedges on cue. With them a daemon runs hours of schedule in one thread, in milliseconds,
// without sleeping.
#pragma once

#include <atomic>
#include <condition_variable>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "capture/camera.h"
#include "core/time.h"
#include "daemon/capture_daemon.h"
#include "daemon/daemon_clock.h"
#include "daemon/service_notifier.h"
#include "daemon/storage/disk_space.h"

namespace glarecam::testing {

using daemon::SteadyTime;

// A time the test names in ISO 8601.
inline UtcTime utc(const char* text) { return *parseIsoTime(text); }

class ManualClock final : public daemon::DaemonClock {
 public:
  explicit ManualClock(UtcTime start);

  SteadyTime now() const override;
  UtcTime utcNow() const override;
  sun::ClockStatus clockStatus() const override;
  SteadyTime steadyAt(UtcTime utc) const override;
  // Never waits while anything is ready; otherwise time jumps to the first alarm due by
  // `deadline` (which runs, without the lock) or to the deadline. A loop that keeps asking to
  // wait until now (a busy loop: no time passes, so no alarm ever comes) aborts the test.
  void waitUntil(std::unique_lock<std::mutex>& lock, std::condition_variable& wake,
                 SteadyTime deadline, const std::function<bool()>& ready) override;

  // Runs `action` when time reaches start + `offset` (alarms at one time run in order).
  void at(std::chrono::nanoseconds offset, std::function<void()> action);
  void advance(std::chrono::nanoseconds by);
  void setClockStatus(sun::ClockStatus status);
  // What the wall clock read at the start (before anything used the clock).
  void setUtcStart(UtcTime start);
  std::chrono::nanoseconds elapsed() const;  // since the start

 private:
  mutable std::mutex mutex_;
  SteadyTime start_steady_;
  UtcTime start_utc_;
  SteadyTime now_;
  sun::ClockStatus status_{.synchronised = true, .detail = "test clock"};
  std::multimap<SteadyTime, std::function<void()>> alarms_;
  int stalled_waits_ = 0;  // waits in a row that neither moved time nor ran an alarm
};

struct Notification {
  std::chrono::nanoseconds at;  // since the clock's start
  std::string message;
};

class RecordingNotifier final : public daemon::ServiceNotifier {
 public:
  RecordingNotifier(const ManualClock& clock,
                    std::optional<std::chrono::microseconds> watchdog = std::nullopt)
      : clock_(clock), watchdog_(watchdog) {}
  void notify(const std::string& message) override;
  std::optional<std::chrono::microseconds> watchdogInterval() const override { return watchdog_; }

  std::vector<Notification> messages() const;
  std::vector<Notification> matching(const std::string& prefix) const;  // "STATUS="
  std::size_t count(const std::string& message) const;

 private:
  const ManualClock& clock_;
  std::optional<std::chrono::microseconds> watchdog_;
  mutable std::mutex mutex_;
  std::vector<Notification> messages_;
};

class ScriptedDisk final : public daemon::DiskProbe {
 public:
  Result<daemon::DiskState> probe(const std::filesystem::path& path) override;
  void set(daemon::DiskState state);
  int probes() const { return probes_; }

 private:
  std::mutex mutex_;
  daemon::DiskState state_{.free_bytes = 100ull << 30, .total_bytes = 200ull << 30};
  int probes_ = 0;
};

// Opens sim: cameras whose capture() calls can be made to fail (the camera lost) or to block
// (a wedged camera) on cue; opens themselves can be made to fail.
class ScriptedCameras {
 public:
  daemon::CameraOpener opener();

  // Every capture() call from the `call`th (counting from 1 over all cameras) fails, and so does
  // every open after it, until heal().
  void loseAtCall(int call);
  // Every open fails until heal() (a camera absent at start).
  void failOpens();
  void heal();
  // The `call`th capture() blocks until release().
  void wedgeAtCall(int call);
  void waitUntilWedged();
  void release();
  // Every capture() advances `clock` by the exposures it was asked for, as a real camera takes
  // them (the sim camera returns at once).
  void takeExposureTime(ManualClock& clock);
  // Every capture() advances `clock` by `per_capture` besides: a slow bracket (a loaded machine,
  // a large scene to draw).
  void takeCaptureTime(ManualClock& clock, std::chrono::nanoseconds per_capture);
  // `hook` runs at the start of every capture() call, on the capturing thread.
  void onCapture(std::function<void()> hook);

  int opens() const { return opens_; }
  int captureCalls() const { return calls_; }

 private:
  friend class ScriptedCamera;
  std::optional<Error> beforeCapture(std::span<const capture::ExposureRequest> requests);

  std::mutex mutex_;
  std::condition_variable changed_;
  std::atomic<int> opens_{0};
  std::atomic<int> calls_{0};
  std::optional<int> lose_from_;
  bool opens_fail_ = false;  // set by failOpens() or once a call reached lose_from_
  std::optional<int> wedge_at_;
  bool wedged_ = false;
  bool released_ = false;
  ManualClock* exposure_clock_ = nullptr;
  std::chrono::nanoseconds capture_time_{};
  std::function<void()> capture_hook_;
};

// "sim:size=160x128,fov=30,seed=N": small and fast.
inline constexpr const char* kSmallSimCamera = "sim:size=160x128,fov=30";

}  // namespace glarecam::testing
