#include "sun/solar_track.h"

#include <algorithm>
#include <cmath>

#include "core/angles.h"

namespace glarecam::sun {
namespace {

constexpr double kSiderealDegPerDay = 360.98564736629;  // SPA equation 28's rate

// The geocentric terms at a node; angles continuous across nodes (unwrapped).
struct Node {
  double right_ascension_deg = 0;
  double declination_deg = 0;
  double radius_vector_au = 0;
  double sidereal_offset_deg = 0;  // ν − 360.98564736629°·(JD − J2000): slow (nutation, jc²)
};

// `angle` moved by whole turns to within 180° of `near`.
double unwrapNear(double angle_deg, double near_deg) {
  return angle_deg - 360.0 * std::round((angle_deg - near_deg) / 360.0);
}

Node nodeAt(double julian_day, const SiteLocation& site, const SolarPositionOptions& options,
            const Node* previous) {
  const detail::SpaTerms terms =
      detail::spaTerms(julian_day, detail::deltaTFor(julian_day, options), site, false);
  Node node;
  node.declination_deg = terms.declination_deg;
  node.radius_vector_au = terms.radius_vector_au;
  node.right_ascension_deg = terms.right_ascension_deg;
  node.sidereal_offset_deg =
      terms.apparent_sidereal_time_deg - kSiderealDegPerDay * (julian_day - detail::kJ2000);
  node.sidereal_offset_deg = unwrapNear(node.sidereal_offset_deg, 0.0);
  if (previous != nullptr) {
    node.right_ascension_deg = unwrapNear(node.right_ascension_deg, previous->right_ascension_deg);
    node.sidereal_offset_deg = unwrapNear(node.sidereal_offset_deg, previous->sidereal_offset_deg);
  }
  return node;
}

}  // namespace

Status solarTrack(std::chrono::sys_time<std::chrono::microseconds> first_utc,
                  std::chrono::microseconds step, std::span<SunDirection> directions,
                  const SiteLocation& site, const SolarPositionOptions& options) {
  GLARECAM_CHECK(validate(site));
  GLARECAM_CHECK(validate(options));
  if (step.count() <= 0) {
    return badInput("solar track: step " + std::to_string(step.count()) + " µs is not positive");
  }
  if (directions.empty()) return {};
  const std::size_t count = directions.size();
  GLARECAM_CHECK(detail::checkInstant(first_utc));
  GLARECAM_CHECK(detail::checkInstant(first_utc + step * static_cast<std::int64_t>(count - 1)));

  const double first_jd = detail::julianDayUt1(first_utc, options);
  const double step_days = static_cast<double>(step.count()) / 86400e6;
  const double node_days = kSolarTrackNodeS / 86400.0;
  const double span_days = step_days * static_cast<double>(count - 1);
  const std::size_t node_count = static_cast<std::size_t>(std::ceil(span_days / node_days)) + 2;
  std::vector<Node> nodes;
  nodes.reserve(node_count);
  for (std::size_t k = 0; k < node_count; ++k) {
    nodes.push_back(nodeAt(first_jd + static_cast<double>(k) * node_days, site, options,
                           nodes.empty() ? nullptr : &nodes.back()));
  }

  const detail::Parallax parallax = detail::Parallax::of(site);
  const double phi = radians(site.latitude_deg);
  const double sin_phi = std::sin(phi), cos_phi = std::cos(phi);
  for (std::size_t i = 0; i < count; ++i) {
    const double offset_days = static_cast<double>(i) * step_days;
    const double jd = first_jd + offset_days;
    const double position = offset_days / node_days;
    const std::size_t k = std::min(static_cast<std::size_t>(position), node_count - 2);
    const double t = position - static_cast<double>(k);
    const Node& a = nodes[k];
    const Node& b = nodes[k + 1];
    auto lerp = [t](double x, double y) { return x + (y - x) * t; };
    const double right_ascension_deg = lerp(a.right_ascension_deg, b.right_ascension_deg);
    const double declination_deg = lerp(a.declination_deg, b.declination_deg);
    const double sidereal_deg = kSiderealDegPerDay * (jd - detail::kJ2000) +
                                lerp(a.sidereal_offset_deg, b.sidereal_offset_deg);
    // SPA 3.11–3.12: the hour angle, then the parallax.
    const double hour_angle_deg = sidereal_deg + site.longitude_deg - right_ascension_deg;
    const detail::TopocentricShift shift = parallax.shift(
        hour_angle_deg, declination_deg, lerp(a.radius_vector_au, b.radius_vector_au));
    const double h = radians(hour_angle_deg - shift.right_ascension_deg);
    const double delta = radians(shift.declination_deg);
    const double sin_delta = std::sin(delta), cos_delta = std::cos(delta);
    const double cos_h = std::cos(h);
    // The direction from the hour angle and declination: the same as SPA's equations 41–46.
    SunDirection direction{.east = -cos_delta * std::sin(h),
                           .north = cos_phi * sin_delta - sin_phi * cos_delta * cos_h,
                           .up = sin_phi * sin_delta + cos_phi * cos_delta * cos_h};
    if (options.refraction) {
      const double true_elevation_deg = degrees(std::asin(std::clamp(direction.up, -1.0, 1.0)));
      const double refraction_deg =
          detail::refractionDeg(true_elevation_deg, site.pressure_hpa, site.temperature_c);
      if (refraction_deg != 0) {
        const double elevation = radians(true_elevation_deg + refraction_deg);
        const double horizontal = std::hypot(direction.east, direction.north);
        if (horizontal > 0) {
          const double scale = std::cos(elevation) / horizontal;
          direction.east *= scale;
          direction.north *= scale;
          direction.up = std::sin(elevation);
        }
      }
    }
    directions[i] = direction;
  }
  return {};
}

Result<std::vector<SunDirection>> solarTrack(
    std::chrono::sys_time<std::chrono::microseconds> first_utc, std::chrono::microseconds step,
    std::size_t count, const SiteLocation& site, const SolarPositionOptions& options) {
  std::vector<SunDirection> directions(count);
  GLARECAM_CHECK(solarTrack(first_utc, step, directions, site, options));
  return directions;
}

}  // namespace glarecam::sun
