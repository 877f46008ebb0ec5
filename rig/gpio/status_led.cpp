#include "rig/gpio/status_led.h"

#include <utility>

namespace glarecam::rig {
namespace {

using std::chrono::nanoseconds;

nanoseconds phaseOf(const RigState& state, nanoseconds since_start) {
  const nanoseconds period = patternPeriod(state);
  if (since_start < nanoseconds::zero()) return nanoseconds::zero();
  return since_start % period;
}

}  // namespace

std::string_view faultName(FaultCode fault) {
  switch (fault) {
    case FaultCode::kCamera:
      return "camera";
    case FaultCode::kInclinometer:
      return "inclinometer";
    case FaultCode::kDisk:
      return "disk";
    case FaultCode::kClock:
      return "clock";
  }
  return "unknown";
}

std::chrono::milliseconds patternPeriod(const RigState& state) {
  switch (state.status) {
    case RigStatus::kReady:
      return kReadyLit + kReadyDark;
    case RigStatus::kCapturing:
      return kCapturingLit + kCapturingDark;
    case RigStatus::kFault:
      return static_cast<int>(state.fault) * (kFaultBlinkLit + kFaultBlinkDark) + kFaultPause;
  }
  return kReadyLit + kReadyDark;
}

bool ledLevelAt(const RigState& state, nanoseconds since_start) {
  const nanoseconds phase = phaseOf(state, since_start);
  switch (state.status) {
    case RigStatus::kReady:
      return phase < kReadyLit;
    case RigStatus::kCapturing:
      return phase < kCapturingLit;
    case RigStatus::kFault: {
      const nanoseconds blink = kFaultBlinkLit + kFaultBlinkDark;
      if (phase >= static_cast<int>(state.fault) * blink) return false;  // the pause
      return phase % blink < kFaultBlinkLit;
    }
  }
  return false;
}

StatusLed::StatusLed(RigIo& io, RigClockFunction clock)
    : io_(io), clock_(std::move(clock)), pattern_start_(clock_()) {}

StatusLed::~StatusLed() { (void)stop(); }

void StatusLed::setStatus(RigState state) {
  const RigClock::time_point now = clock_();
  std::lock_guard lock(mutex_);
  if (state == state_) return;
  state_ = state;
  pattern_start_ = now;
}

RigState StatusLed::status() const {
  std::lock_guard lock(mutex_);
  return state_;
}

Status StatusLed::tick(RigClock::time_point now) {
  std::lock_guard lock(mutex_);
  if (stopped_) return {};
  const bool level = ledLevelAt(state_, now - pattern_start_);
  if (written_ == level) return {};
  Status written = io_.setLed(level);
  if (written) {
    written_ = level;
  } else {
    written_.reset();
    last_error_ = written.error();
  }
  return written;
}

void StatusLed::start() {
  {
    std::lock_guard lock(mutex_);
    stopped_ = false;
  }
  if (thread_.joinable()) return;
  thread_ = std::jthread([this](std::stop_token stop) {
    while (!stop.stop_requested()) {
      (void)tick(clock_());  // a failure is kept for lastError()
      std::unique_lock lock(wait_mutex_);
      wake_.wait_for(lock, stop, kStatusLedTick, [] { return false; });
    }
  });
}

Status StatusLed::stop() {
  if (thread_.joinable()) {
    thread_.request_stop();
    thread_.join();
  }
  std::lock_guard lock(mutex_);
  if (stopped_) return {};
  stopped_ = true;
  Status darkened = io_.setLed(false);
  written_.reset();
  if (!darkened) last_error_ = darkened.error();
  return darkened;
}

std::optional<Error> StatusLed::lastError() const {
  std::lock_guard lock(mutex_);
  return last_error_;
}

}  // namespace glarecam::rig
