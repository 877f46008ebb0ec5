// The status LED's blink codes and the StatusLed that plays them on a RigIo's LED.
//
//   ready       lit, with a 100 ms dark blink every 2 s: a heartbeat, so that a LED steadily lit
//               or steadily dark always means glarecam is not running (or hung)
//   capturing   fast blink, 5 Hz (100 ms lit, 100 ms dark)
//   fault N     N short blinks (200 ms lit, 300 ms dark), then 1.5 s dark, repeating; N is the
//               FaultCode (2 camera, 3 inclinometer, 4 disk, 5 clock): easy to count in sunlight
//
// A pattern starts lit at the moment the status changes and repeats with patternPeriod().
// ledLevelAt() is the pattern as a pure function of time. StatusLed holds the present status
// (setStatus() from any thread) and writes the LED when the pattern's level changes: tick(now)
// does one step, start() runs a std::jthread that ticks every kStatusLedTick, and stop() (also
// the destructor) joins it and leaves the LED dark.
#pragma once

#include <chrono>
#include <condition_variable>
#include <mutex>
#include <optional>
#include <stop_token>
#include <string_view>
#include <thread>

#include "rig/gpio/rig_io.h"

namespace glarecam::rig {

enum class RigStatus { kReady, kCapturing, kFault };

// What failed, as the number of blinks of the fault code. No code is 1 blink: a single blink is
// too easily mistaken for a heartbeat.
enum class FaultCode { kCamera = 2, kInclinometer = 3, kDisk = 4, kClock = 5 };

std::string_view faultName(FaultCode fault);  // "camera", ...

// The status the LED shows; `fault` matters only for kFault.
struct RigState {
  RigStatus status = RigStatus::kReady;
  FaultCode fault = FaultCode::kCamera;

  static constexpr RigState ready() { return {RigStatus::kReady, FaultCode::kCamera}; }
  static constexpr RigState capturing() { return {RigStatus::kCapturing, FaultCode::kCamera}; }
  static constexpr RigState faulted(FaultCode fault) { return {RigStatus::kFault, fault}; }

  friend constexpr bool operator==(const RigState& a, const RigState& b) {
    return a.status == b.status && (a.status != RigStatus::kFault || a.fault == b.fault);
  }
};

// The patterns' timings.
inline constexpr std::chrono::milliseconds kReadyLit{1'900};
inline constexpr std::chrono::milliseconds kReadyDark{100};
inline constexpr std::chrono::milliseconds kCapturingLit{100};
inline constexpr std::chrono::milliseconds kCapturingDark{100};
inline constexpr std::chrono::milliseconds kFaultBlinkLit{200};
inline constexpr std::chrono::milliseconds kFaultBlinkDark{300};
inline constexpr std::chrono::milliseconds kFaultPause{1'500};  // after the last blink's dark
// How often StatusLed's thread ticks: an edge is late by at most this.
inline constexpr std::chrono::milliseconds kStatusLedTick{10};

// One repetition of the state's pattern.
std::chrono::milliseconds patternPeriod(const RigState& state);

// Whether the LED is lit `since_start` into the state's pattern (repeating; a negative time is the
// pattern's start).
bool ledLevelAt(const RigState& state, std::chrono::nanoseconds since_start);

class StatusLed {
 public:
  // Shows ready once ticked. `io` must outlive this; a rig without a LED makes every write a no-op.
  explicit StatusLed(RigIo& io, RigClockFunction clock = RigClock::now);
  ~StatusLed();  // stop()
  StatusLed(const StatusLed&) = delete;
  StatusLed& operator=(const StatusLed&) = delete;

  // Shows `state` from now on, its pattern restarted when the state changed (setting the same
  // state again does not restart it). Thread-safe.
  void setStatus(RigState state);
  RigState status() const;

  // Writes the LED's level at `now` when it differs from the last level written (or the last
  // write failed). Returns the write's status; a failure is also kept for lastError().
  // Thread-safe; does nothing after stop() until start().
  Status tick(RigClock::time_point now);

  // Ticks from a background thread every kStatusLedTick (on the injected clock's time). No-op
  // when already running.
  void start();
  // Joins the thread (if running) and darkens the LED; the write's status. Idempotent.
  Status stop();

  // The last write that failed, from tick() or the thread; cleared by none (for the log).
  std::optional<Error> lastError() const;

 private:
  RigIo& io_;
  RigClockFunction clock_;

  mutable std::mutex mutex_;
  RigState state_ = RigState::ready();
  RigClock::time_point pattern_start_;
  std::optional<bool> written_;  // the level last written successfully
  std::optional<Error> last_error_;
  bool stopped_ = false;

  std::mutex wait_mutex_;
  std::condition_variable_any wake_;
  std::jthread thread_;  // last: joined before the members it uses are destroyed
};

}  // namespace glarecam::rig
