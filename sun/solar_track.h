// The sun's direction at many evenly spaced instants, fast: a day or a year of a glare-hazard
// calculation (hazard/), where full SPA (solar_position.h, ~5 µs a position) would cost 2.7 s of
// one core for a year of minutes before any glare test.
//
// Method: SPA's geocentric terms (the Earth's heliocentric position and radius, nutation, the
// obliquity, ΔT, hence the sun's geocentric right ascension and declination and the nutation
// part of the sidereal time) change slowly, so they are computed by full SPA at nodes
// kSolarTrackNodeS apart and interpolated linearly (right ascension unwrapped); the fast part is
// exact at every step: the mean sidereal time from the Julian day, the hour angle, the parallax
// (topocentric), elevation, refraction (SPA's equation 42) and the direction. Linear
// interpolation over an hour is off by (1 h)²/8 times the terms' second derivatives, under
// 10⁻⁶° for right ascension and declination.
//
// Accuracy: within kSolarTrackToleranceDeg of solarPosition() in apparent elevation and azimuth
// (as a direction) at every step; solar_track_test checks a year at two sites.
#pragma once

#include <chrono>
#include <span>
#include <vector>

#include "core/error.h"
#include "sun/solar_position.h"

namespace glarecam::sun {

inline constexpr double kSolarTrackToleranceDeg = 0.0005;
inline constexpr double kSolarTrackNodeS = 3600;

// Unit vector toward the sun's centre, topocentric and apparent (refraction as in options), in
// local east–north–up; the elevation is asin(up).
struct SunDirection {
  double east = 0, north = 0, up = 0;
};

// Directions at first_utc + k·step, k in [0, count). kBadInput for an invalid site or option, a
// step that is not positive, or an instant outside SPA's years (solarPosition's messages).
Result<std::vector<SunDirection>> solarTrack(
    std::chrono::sys_time<std::chrono::microseconds> first_utc, std::chrono::microseconds step,
    std::size_t count, const SiteLocation& site, const SolarPositionOptions& options = {});
// The same into a caller's buffer (count = directions.size()), to reuse it day after day.
Status solarTrack(std::chrono::sys_time<std::chrono::microseconds> first_utc,
                  std::chrono::microseconds step, std::span<SunDirection> directions,
                  const SiteLocation& site, const SolarPositionOptions& options = {});

}  // namespace glarecam::sun
