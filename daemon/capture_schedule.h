// When glarecamd takes its next scheduled stack ([schedule], daemon_config.h), as a plan over the
// daemon's two clocks (daemon_clock.h): the steady clock for timers, the wall clock for the sun.
//
//   interval      the first stack at once, then on the interval's grid; missed slots are not
//                 caught up
//   α targets     a stack when α crosses each target as the sun moves (alpha_schedule.h), from the
//                 module's measured orientation and the site; a target just taken is not taken
//                 again within kAlphaTargetRepeatGuard; when nothing can be planned (no module
//                 yet, no crossing within kAlphaPlanHorizon) it tries again in kReplanDelay
//   button        no scheduled slot: only the button and SIGUSR1 take stacks
//
// The plan keeps its α target's crossing in wall time, so that a wall clock that jumped (NTP's
// first synchronisation on a board without a clock) is seen and the plan made again. The
// schedule holds no hardware and does no I/O: the daemon measures the module and asks.
#pragma once

#include <chrono>
#include <map>
#include <optional>
#include <string>

#include "core/time.h"
#include "daemon/daemon_clock.h"
#include "daemon/daemon_config.h"
#include "sun/incidence_angle.h"
#include "sun/solar_position.h"

namespace glarecam::daemon {

// How far ahead the α targets are computed.
inline constexpr std::chrono::hours kAlphaPlanHorizon{24};
// When no α target can be planned, how soon it is tried again.
inline constexpr std::chrono::hours kReplanDelay{1};
// A wall clock that moved this much against the steady clock jumped: the schedule is replanned.
inline constexpr std::chrono::seconds kWallClockJump{5};

class CaptureSchedule {
 public:
  CaptureSchedule() = default;
  explicit CaptureSchedule(ScheduleConfig config) : config_(std::move(config)) {}

  const ScheduleConfig& config() const { return config_; }
  // A new [schedule] (a reload): what was planned and taken stays until the next plan().
  void reconfigure(ScheduleConfig config) { config_ = std::move(config); }
  // "every 600 s", "at 16 α targets", "on the button and SIGUSR1".
  std::string describe() const;

  // What α targets are planned from: the site and the module (nullopt: not measured yet).
  struct Geometry {
    std::optional<sun::SiteLocation> site;
    std::optional<sun::ModuleOrientation> module;
  };

  // Plans the next slot. `slot_taken`: the wall time at which the stack of the due slot began
  // (its α measured), once that stack is done (taken, or skipped for good): the next slot is
  // wanted, and an α target crossed since that time is still owed (due at once: a bracket that
  // took longer than the sun to reach the next target does not skip it). Without it the plan is
  // made again from now (a reload, a retry).
  void plan(const DaemonClock& clock, std::optional<UtcTime> slot_taken, const Geometry& geometry);
  // The due slot is used now: its α target is remembered against the repeat guard.
  void take(UtcTime now);

  // The next scheduled slot, in steady time (none: button mode, or nothing planned).
  std::optional<SteadyTime> next() const { return next_; }
  bool due(SteadyTime now) const { return next_ && now >= *next_; }
  // The α target of the next slot.
  std::optional<double> nextTargetDeg() const { return next_target_deg_; }
  // When the plan is made again because nothing could be planned, and why.
  std::optional<SteadyTime> replanAt() const { return replan_at_; }
  const std::string& unplannedReason() const { return unplanned_reason_; }
  // The next slot in wall time, as the status line shows it.
  std::optional<UtcTime> nextWallTime(const DaemonClock& clock) const;
  // Whether the wall clock moved by kWallClockJump or more against the planned α crossing.
  std::optional<std::chrono::nanoseconds> wallClockJump(const DaemonClock& clock) const;

 private:
  void planInterval(SteadyTime now, bool slot_taken);
  void planAlphaTargets(const DaemonClock& clock, UtcTime from, const Geometry& geometry);
  void unplanned(const DaemonClock& clock, std::string why);

  ScheduleConfig config_;
  std::optional<SteadyTime> next_;
  std::optional<double> next_target_deg_;
  std::optional<UtcTime> planned_crossing_;  // the next α target's crossing, in wall time
  std::optional<SteadyTime> replan_at_;
  std::string unplanned_reason_;
  std::map<double, UtcTime> taken_targets_;  // when each α target's slot was last used
};

}  // namespace glarecam::daemon
