#include "daemon/capture_schedule.h"

#include <fmt/format.h>

#include <algorithm>

#include "daemon/alpha_schedule.h"

namespace glarecam::daemon {

std::string CaptureSchedule::describe() const {
  switch (config_.mode) {
    case ScheduleMode::kInterval:
      return fmt::format("every {} s", config_.interval.count());
    case ScheduleMode::kAlphaTargets:
      return fmt::format("at {} α targets", config_.alpha_targets_deg.size());
    case ScheduleMode::kButton:
      break;
  }
  return "on the button and SIGUSR1";
}

void CaptureSchedule::plan(const DaemonClock& clock, std::optional<UtcTime> slot_taken,
                           const Geometry& geometry) {
  replan_at_.reset();
  unplanned_reason_.clear();
  next_target_deg_.reset();
  switch (config_.mode) {
    case ScheduleMode::kInterval:
      planInterval(clock.now(), slot_taken.has_value());
      break;
    case ScheduleMode::kAlphaTargets:
      planAlphaTargets(clock, std::min(slot_taken.value_or(clock.utcNow()), clock.utcNow()),
                       geometry);
      break;
    case ScheduleMode::kButton:
      next_.reset();
      break;
  }
}

void CaptureSchedule::planInterval(SteadyTime now, bool slot_taken) {
  if (!next_)
    next_ = now;
  else if (slot_taken)
    *next_ += config_.interval;
  if (*next_ < now) next_ = now + config_.interval;
  if (!slot_taken) next_ = std::min(*next_, now + config_.interval);
}

void CaptureSchedule::planAlphaTargets(const DaemonClock& clock, UtcTime from,
                                       const Geometry& geometry) {
  next_.reset();
  planned_crossing_.reset();
  if (!geometry.site || !geometry.module)
    return unplanned(clock, "α targets need the module's tilt");
  const auto crossings = alphaCrossings(*geometry.site, *geometry.module, from, kAlphaPlanHorizon,
                                        config_.alpha_targets_deg);
  if (!crossings) return unplanned(clock, crossings.error().message);
  for (const AlphaCrossing& crossing : *crossings) {
    const auto taken = taken_targets_.find(crossing.target_deg);
    if (taken != taken_targets_.end() && crossing.time - taken->second < kAlphaTargetRepeatGuard)
      continue;
    next_ = clock.steadyAt(crossing.time);
    planned_crossing_ = crossing.time;
    next_target_deg_ = crossing.target_deg;
    return;
  }
  unplanned(clock, "no α target is crossed in the next 24 h");
}

void CaptureSchedule::unplanned(const DaemonClock& clock, std::string why) {
  replan_at_ = clock.now() + kReplanDelay;
  unplanned_reason_ = std::move(why);
}

void CaptureSchedule::take(UtcTime now) {
  if (next_target_deg_) taken_targets_[*next_target_deg_] = now;
}

std::optional<UtcTime> CaptureSchedule::nextWallTime(const DaemonClock& clock) const {
  if (!next_) return std::nullopt;
  return clock.utcNow() +
         std::chrono::duration_cast<std::chrono::microseconds>(*next_ - clock.now());
}

std::optional<std::chrono::nanoseconds> CaptureSchedule::wallClockJump(
    const DaemonClock& clock) const {
  if (!planned_crossing_ || !next_) return std::nullopt;
  const auto moved = clock.steadyAt(*planned_crossing_) - *next_;
  if (std::chrono::abs(moved) < kWallClockJump) return std::nullopt;
  return -moved;
}

}  // namespace glarecam::daemon
