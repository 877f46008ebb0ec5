#include "rig/rig_geometry.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <functional>

#include "core/time.h"
#include "rig/inclinometer/inclinometer_registry.h"
#include "rig/inclinometer/sample_progress.h"
#include "rig/inclinometer/zero_offset_file.h"

namespace glarecam::rig {

const char* geometrySourceName(GeometrySource source) {
  return source == GeometrySource::kSun ? "sun" : "fixed";
}

namespace {

// Step of the numerical derivative of α over time: small against the minutes α varies over,
// large against double rounding.
constexpr std::chrono::seconds kTimeStep{1};

// |dα/dx| from one-sided differences on both sides: the central difference vanishes at α's
// minimum (the sun passing the normal), where α still changes.
double slope(const std::function<double(double)>& alpha_at, double x, double step) {
  const double centre = alpha_at(x);
  return std::max(std::abs(alpha_at(x + step) - centre), std::abs(alpha_at(x - step) - centre)) /
         step;
}

Result<sun::SkyDirection> sunDirection(const sun::SiteLocation& site, UtcTime time,
                                       std::optional<sun::SolarPosition>* position = nullptr) {
  sun::SolarPosition sun;
  GLARECAM_ASSIGN(sun, sun::solarPosition(time, site));
  if (position) *position = sun;
  return sun::SkyDirection{sun.elevation_deg, sun.azimuth_deg};
}

Status checkHasSource(const RigConfig& config) {
  if (config.site || config.fixed_source) return {};
  return badInput(config.path.string() +
                  ": cannot compute α: give [site] (the sun) or [source] (a fixed lamp)");
}

std::unexpected<Error> noTiltError(const RigConfig& config) {
  return badInput(config.path.string() +
                  ": no module tilt: configure [inclinometer] uri, or [module] tilt_deg");
}

// From the inclinometer's attitude when there is a reading, else the config's fixed tilt.
Result<sun::ModuleOrientation> moduleOrientationOf(const RigConfig& config,
                                                   const std::optional<TiltReading>& tilt) {
  const double facing_deg = config.module_azimuth_deg.value_or(0.0);
  if (tilt) return moduleOrientation(tilt->tilt, facing_deg);
  if (config.module_tilt_deg) return sun::ModuleOrientation{*config.module_tilt_deg, facing_deg};
  return noTiltError(config);
}

void addWarnings(RigGeometry& g) {
  if (g.sun && g.sun->elevation_deg < 0)
    g.warnings.push_back(
        fmt::format("the sun is below the horizon (elevation {:.2f}°)", g.sun->elevation_deg));
  if (g.alpha_deg > 90)
    g.warnings.push_back(
        fmt::format("the source is behind the module (α {:.2f}° > 90°)", g.alpha_deg));
  if (g.clock_error_unknown)
    g.warnings.push_back("the system clock is not synchronised: " + g.clock->detail +
                         "; α is only as good as the clock, whose error is unknown (its "
                         "uncertainty leaves it out)");
}

}  // namespace

Result<RigGeometry> computeRigGeometry(const RigConfig& config,
                                       const std::optional<TiltReading>& tilt, UtcTime time,
                                       const std::optional<sun::ClockStatus>& clock) {
  GLARECAM_CHECK(checkHasSource(config));
  RigGeometry g;
  g.time = time;
  g.tilt = tilt;
  GLARECAM_ASSIGN(g.module, moduleOrientationOf(config, tilt));
  if (config.site) {
    g.source = GeometrySource::kSun;
    g.clock = clock;
    GLARECAM_ASSIGN(g.source_direction, sunDirection(*config.site, time, &g.sun));
  } else {
    g.source = GeometrySource::kFixed;
    g.source_direction = *config.fixed_source;
  }
  g.alpha_deg = sun::incidenceAngleDeg(g.module, g.source_direction);

  // The reading's uncertainty is the same in every direction (per-direction scatter), and α is
  // the angle from the normal to the source, whose gradient over the normal's direction has
  // unit size: α inherits it one for one, whichever way the error points.
  g.alpha_uncertainty_tilt_deg = tilt ? tilt->tilt_uncertainty_deg : 0.0;
  if (config.site && clock) {
    // α moves with the sun: the clock's error in seconds times dα/dt.
    const auto alpha_at_offset_s = [&](double offset_s) {
      const auto shifted = time + std::chrono::round<std::chrono::microseconds>(
                                      std::chrono::duration<double>(offset_s));
      const auto direction = sunDirection(*config.site, shifted);
      return direction ? sun::incidenceAngleDeg(g.module, *direction) : g.alpha_deg;
    };
    const double step_s = std::chrono::duration<double>(kTimeStep).count();
    const std::optional<double> clock_sigma_s = clock->uncertaintyS();
    if (clock_sigma_s)
      g.alpha_uncertainty_clock_deg = slope(alpha_at_offset_s, 0.0, step_s) * *clock_sigma_s;
    g.clock_error_unknown = !clock_sigma_s;
  }
  g.alpha_uncertainty_deg = std::hypot(g.alpha_uncertainty_tilt_deg, g.alpha_uncertainty_clock_deg);
  addWarnings(g);
  return g;
}

nlohmann::json geometryJson(const RigGeometry& g) {
  nlohmann::json block{{"module_tilt_deg", g.module.tilt_deg},
                       {"module_azimuth_deg", g.module.azimuth_deg},
                       {"alpha_deg", g.alpha_deg},
                       {"alpha_uncertainty_deg", g.alpha_uncertainty_deg},
                       {"source", geometrySourceName(g.source)},
                       {"time", formatIsoTime(g.time)}};
  if (g.sun) {
    block["sun_elevation_deg"] = g.sun->elevation_deg;
    block["sun_azimuth_deg"] = g.sun->azimuth_deg;
    block["sun_zenith_deg"] = g.sun->zenith_deg;
  } else {
    block["source_elevation_deg"] = g.source_direction.elevation_deg;
    block["source_azimuth_deg"] = g.source_direction.azimuth_deg;
  }
  if (g.clock) block["clock_synchronised"] = g.clock->synchronised;
  if (g.clock_error_unknown) block["alpha_uncertainty_excludes_clock"] = true;
  if (g.tilt) {
    nlohmann::json inclinometer{
        {"x_g", g.tilt->mean.x_g},          {"y_g", g.tilt->mean.y_g},
        {"z_g", g.tilt->mean.z_g},          {"uri", g.inclinometer_uri},
        {"samples", g.tilt->samples},       {"tilt_std_deg", g.tilt->tilt_std_deg},
        {"tilt_x_deg", g.tilt->tilt.x_deg}, {"tilt_y_deg", g.tilt->tilt.y_deg}};
    if (g.tilt->mean.temperature_c) inclinometer["temperature_c"] = *g.tilt->mean.temperature_c;
    // x_g, y_g, z_g are as read; tilt_x_deg and tilt_y_deg have this offset removed.
    if (g.zero_offset) {
      inclinometer["zero_offset_x_deg"] = g.zero_offset->offset.x_deg;
      inclinometer["zero_offset_y_deg"] = g.zero_offset->offset.y_deg;
    } else {
      inclinometer["zero_offset_x_deg"] = nullptr;
      inclinometer["zero_offset_y_deg"] = nullptr;
    }
    block["inclinometer"] = inclinometer;
  }
  if (!g.warnings.empty()) block["warnings"] = g.warnings;
  return block;
}

RigSensors::RigSensors(RigConfig config, std::unique_ptr<Inclinometer> inclinometer,
                       std::optional<InclinometerZeroOffset> zero,
                       std::vector<std::string> standing_warnings)
    : config_(std::move(config)),
      inclinometer_(std::move(inclinometer)),
      zero_(std::move(zero)),
      standing_warnings_(std::move(standing_warnings)) {}

namespace {

// The zero offset the config's calibration file holds for `uri`, and what is wrong with it as
// warnings (none stored yet, stored for another sensor): a rig still measures without one.
Result<std::optional<InclinometerZeroOffset>> storedZeroOffset(const RigConfig& config,
                                                               const std::string& uri,
                                                               std::vector<std::string>& warnings) {
  const std::string flip_hint =
      "tilts are not corrected for the sensor's mounting (run `glarecam "
      "inclinometer flip`)";
  std::error_code ec;
  if (!config.calibration || !std::filesystem::exists(*config.calibration, ec)) {
    warnings.push_back(
        config.calibration
            ? fmt::format("no inclinometer zero offset: {} (the config's calibration) does not "
                          "exist yet; {}",
                          config.calibration->string(), flip_hint)
            : fmt::format("no inclinometer zero offset: {} names no calibration file; {}",
                          config.path.string(), flip_hint));
    return std::nullopt;
  }
  std::optional<InclinometerZeroOffset> zero;
  GLARECAM_ASSIGN(zero, readZeroOffset(*config.calibration));
  if (!zero) {
    warnings.push_back(fmt::format("no inclinometer zero offset in {}; {}",
                                   config.calibration->string(), flip_hint));
  } else if (!zero->measured_with.empty() && !sameInclinometer(zero->measured_with, uri)) {
    warnings.push_back(fmt::format("the zero offset in {} was measured with {}, not {}",
                                   config.calibration->string(), zero->measured_with, uri));
  }
  return zero;
}

}  // namespace

Result<std::unique_ptr<RigSensors>> RigSensors::open(const RigConfig& config) {
  GLARECAM_CHECK(checkHasSource(config));
  if (!config.inclinometer && !config.module_tilt_deg) return noTiltError(config);
  std::unique_ptr<Inclinometer> inclinometer;
  std::optional<InclinometerZeroOffset> zero;
  std::vector<std::string> warnings;
  if (config.inclinometer) {
    auto opened = openInclinometer(config.inclinometer->uri);
    if (!opened && opened.error().code == ErrorCode::kBadInput)
      return std::unexpected(
          withContext(opened.error(), config.path.string() + ": [inclinometer] uri"));
    if (!opened) return std::unexpected(opened.error());
    inclinometer = std::move(*opened);
    GLARECAM_ASSIGN(zero, storedZeroOffset(config, config.inclinometer->uri, warnings));
  }
  return std::unique_ptr<RigSensors>(
      new RigSensors(config, std::move(inclinometer), std::move(zero), std::move(warnings)));
}

Result<RigGeometry> RigSensors::measure(UtcTime time, const std::function<void()>& on_sample,
                                        bool time_from_clock) {
  return measureWithClock(
      time, time_from_clock ? std::optional(sun::systemClockStatus()) : std::nullopt, on_sample);
}

Result<RigGeometry> RigSensors::measureWithClock(UtcTime time,
                                                 const std::optional<sun::ClockStatus>& clock,
                                                 const std::function<void()>& on_sample) {
  std::optional<TiltReading> tilt;
  if (inclinometer_) {
    GLARECAM_ASSIGN(tilt, measureTilt(*inclinometer_, config_.inclinometer->tilt,
                                      zero_.value_or(InclinometerZeroOffset{}), on_sample));
  }
  return geometryAt(tilt, time, clock);
}

Result<RigGeometry> RigSensors::measureShowingProgress(UtcTime time,
                                                       const std::optional<sun::ClockStatus>& clock,
                                                       bool show_progress) {
  return withSampleProgress(inclinometer_ ? config_.inclinometer->tilt.samples : 0,
                            show_progress && inclinometer_,
                            [&](const std::function<void()>& on_sample) {
                              return measureWithClock(time, clock, on_sample);
                            });
}

Result<RigGeometry> RigSensors::retime(const RigGeometry& measured, UtcTime time) const {
  return geometryAt(measured.tilt, time, measured.clock);
}

Result<RigGeometry> RigSensors::geometryAt(const std::optional<TiltReading>& tilt, UtcTime time,
                                           const std::optional<sun::ClockStatus>& clock) const {
  RigGeometry geometry;
  GLARECAM_ASSIGN(geometry, computeRigGeometry(config_, tilt, time, clock));
  if (inclinometer_) {
    geometry.inclinometer_uri = inclinometer_->info().uri;
    geometry.zero_offset = zero_;
  }
  geometry.warnings.insert(geometry.warnings.begin(), standing_warnings_.begin(),
                           standing_warnings_.end());
  return geometry;
}

}  // namespace glarecam::rig
