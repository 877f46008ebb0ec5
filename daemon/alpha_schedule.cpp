#include "daemon/alpha_schedule.h"

#include <algorithm>

namespace glarecam::daemon {

namespace {

// Bisects [a, b] (α(a) - target and α(b) - target of opposite signs) to the tolerance.
Result<UtcTime> refineCrossing(const sun::SiteLocation& site, const sun::ModuleOrientation& module,
                               UtcTime a, UtcTime b, double alpha_a, double target_deg) {
  while (b - a > kAlphaCrossingTolerance) {
    const UtcTime middle = a + (b - a) / 2;
    SunIncidence at;
    GLARECAM_ASSIGN(at, sunIncidence(site, module, middle));
    if ((at.alpha_deg - target_deg) * (alpha_a - target_deg) > 0) {
      a = middle;
      alpha_a = at.alpha_deg;
    } else {
      b = middle;
    }
  }
  return a + (b - a) / 2;
}

}  // namespace

Result<SunIncidence> sunIncidence(const sun::SiteLocation& site,
                                  const sun::ModuleOrientation& module, UtcTime time) {
  sun::SolarPosition sun;
  GLARECAM_ASSIGN(sun, sun::solarPosition(time, site));
  return SunIncidence{
      .alpha_deg = sun::incidenceAngleDeg(module, {sun.elevation_deg, sun.azimuth_deg}),
      .sun_up = sun.elevation_deg > 0.0};
}

Result<std::vector<AlphaCrossing>> alphaCrossings(const sun::SiteLocation& site,
                                                  const sun::ModuleOrientation& module,
                                                  UtcTime from, std::chrono::seconds horizon,
                                                  std::span<const double> targets_deg) {
  std::vector<AlphaCrossing> crossings;
  SunIncidence previous;
  GLARECAM_ASSIGN(previous, sunIncidence(site, module, from));
  for (UtcTime t0 = from; t0 < from + horizon; t0 += kAlphaScanStep) {
    const UtcTime t1 = t0 + kAlphaScanStep;
    SunIncidence next;
    GLARECAM_ASSIGN(next, sunIncidence(site, module, t1));
    for (const double target : targets_deg) {
      // A crossing in (t0, t1]: α - target changes sign there (or reaches zero at t1).
      const double d0 = previous.alpha_deg - target, d1 = next.alpha_deg - target;
      const bool crosses = d0 != 0 && (d1 == 0 || (d0 < 0) != (d1 < 0));
      if (!crosses || !previous.sun_up || !next.sun_up) continue;
      UtcTime at;
      GLARECAM_ASSIGN(at, refineCrossing(site, module, t0, t1, previous.alpha_deg, target));
      if (at >= from + horizon) continue;
      crossings.push_back({.time = at, .target_deg = target, .rising = d1 > d0});
    }
    previous = next;
  }
  std::sort(crossings.begin(), crossings.end(),
            [](const AlphaCrossing& a, const AlphaCrossing& b) { return a.time < b.time; });
  return crossings;
}

}  // namespace glarecam::daemon
