// When will the sun stand at a given angle of incidence α on the module? For the "alpha-targets"
// schedule: a stack each time α(t), between the module's normal and the sun's apparent direction
// (NREL SPA, solar_position.h), crosses one of the targets (5°, 10°, ... 80°) while the sun is up.
// α(t) is scanned every kAlphaScanStep and each crossing refined by bisection to
// kAlphaCrossingTolerance: a target touched only between two scan points (α's minimum at noon
// within 0.05° of a target) can be missed; the nearest crossing is then the day's closest approach,
// which is not a crossing.
#pragma once

#include <chrono>
#include <span>
#include <vector>

#include "core/error.h"
#include "core/time.h"
#include "sun/incidence_angle.h"
#include "sun/solar_position.h"

namespace glarecam::daemon {

inline constexpr std::chrono::seconds kAlphaScanStep{120};
inline constexpr std::chrono::milliseconds kAlphaCrossingTolerance{500};
// A target just taken is not taken again this soon: each stack re-measures the tilt, and the
// inclinometer's noise (0.004°) moves the predicted crossing by a second or so.
inline constexpr std::chrono::minutes kAlphaTargetRepeatGuard{5};

struct AlphaCrossing {
  UtcTime time;
  double target_deg = 0.0;
  bool rising = false;  // α increasing (afternoon on a fixed module), else decreasing
};

// α at `time` for a module at `site`, and whether the sun is above the horizon then.
struct SunIncidence {
  double alpha_deg = 0.0;
  bool sun_up = false;
};
Result<SunIncidence> sunIncidence(const sun::SiteLocation& site,
                                  const sun::ModuleOrientation& module, UtcTime time);

// The crossings of `targets_deg` in [from, from + horizon), sorted by time.
Result<std::vector<AlphaCrossing>> alphaCrossings(const sun::SiteLocation& site,
                                                  const sun::ModuleOrientation& module,
                                                  UtcTime from, std::chrono::seconds horizon,
                                                  std::span<const double> targets_deg);

}  // namespace glarecam::daemon
