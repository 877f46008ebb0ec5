// The rig's geometry at one moment: the module's orientation (tilt from the inclinometer or the
// config, facing azimuth from the config), the light source's direction (the sun at the site and
// time, or a fixed lab lamp) and the angle of incidence α between them, with α's standard
// uncertainty from the tilt's (inclinometer noise + zero offset) and the clock's. This is what a
// capture records in its manifest's `geometry` block and `glarecam alpha` prints.
#pragma once

#include <chrono>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/time.h"
#include "rig/inclinometer/inclinometer.h"
#include "rig/inclinometer/tilt.h"
#include "rig/rig_config.h"
#include "sun/clock_sync.h"
#include "sun/incidence_angle.h"
#include "sun/solar_position.h"

namespace glarecam::rig {

// Where the light comes from: the sun at the config's [site], or a lab lamp fixed at [source].
enum class GeometrySource { kSun, kFixed };
// "sun" or "fixed", as the geometry block records it.
const char* geometrySourceName(GeometrySource source);

struct RigGeometry {
  UtcTime time;
  GeometrySource source = GeometrySource::kSun;
  sun::ModuleOrientation module;
  sun::SkyDirection source_direction;
  std::optional<sun::SolarPosition> sun;  // when the source is the sun
  double alpha_deg = 0.0;
  double alpha_uncertainty_deg = 0.0;
  double alpha_uncertainty_tilt_deg = 0.0;   // the tilt's share
  double alpha_uncertainty_clock_deg = 0.0;  // the clock's share
  bool clock_error_unknown = false;  // the clock is not synchronised: its share is not known
  std::optional<TiltReading> tilt;   // when an inclinometer measured the tilt
  std::string inclinometer_uri;
  std::optional<InclinometerZeroOffset> zero_offset;  // removed from the tilt, when stored
  std::optional<sun::ClockStatus> clock;  // when the source is the sun and the time the clock's
  std::vector<std::string> warnings;      // sun below the horizon or behind the module, ...
};

// α from the config and, when given, a tilt reading (else the config's fixed module tilt).
// `clock`: the system clock's state when `time` was read from it (its error then widens α's
// uncertainty); nullopt for a time given by the user. kBadInput when the config cannot give α
// (no [site] nor [source], no tilt).
Result<RigGeometry> computeRigGeometry(const RigConfig& config,
                                       const std::optional<TiltReading>& tilt, UtcTime time,
                                       const std::optional<sun::ClockStatus>& clock);

// The manifest's `geometry` block (stack-format.md): module_tilt_deg, module_azimuth_deg,
// sun_elevation_deg, sun_azimuth_deg, inclinometer {x_g, y_g, z_g, temperature_c}, and the
// provenance of α.
nlohmann::json geometryJson(const RigGeometry& geometry);

// The rig's sensors as a capture uses them: the inclinometer named in the config (opened once)
// with its zero offset from the calibration file. measure() reads the tilt and computes α; what
// is wrong with the setup (no zero offset stored, one measured with another sensor) is repeated
// in every geometry's warnings, so that each stack records it.
class RigSensors {
 public:
  // kBadInput when the config cannot give α; the inclinometer's errors when it cannot be opened.
  static Result<std::unique_ptr<RigSensors>> open(const RigConfig& config);

  // `time_from_clock`: `time` is the system clock's now (false: the user's, no clock error).
  Result<RigGeometry> measure(UtcTime time, const std::function<void()>& on_sample = {},
                              bool time_from_clock = true);
  // The same with the state of the clock `time` was read from (nullopt: a time the user gave).
  Result<RigGeometry> measureWithClock(UtcTime time, const std::optional<sun::ClockStatus>& clock,
                                       const std::function<void()>& on_sample = {});
  // The same reading at another time (the sun moved; the module did not): for α at the middle
  // of a bracket that followed the reading.
  Result<RigGeometry> retime(const RigGeometry& measured, UtcTime time) const;
  // measureWithClock() with a progress line over the inclinometer's samples on stderr.
  Result<RigGeometry> measureShowingProgress(UtcTime time,
                                             const std::optional<sun::ClockStatus>& clock,
                                             bool show_progress);

  const RigConfig& config() const { return config_; }
  const std::optional<InclinometerZeroOffset>& zeroOffset() const { return zero_; }
  bool hasInclinometer() const { return inclinometer_ != nullptr; }

 private:
  Result<RigGeometry> geometryAt(const std::optional<TiltReading>& tilt, UtcTime time,
                                 const std::optional<sun::ClockStatus>& clock) const;

  RigSensors(RigConfig config, std::unique_ptr<Inclinometer> inclinometer,
             std::optional<InclinometerZeroOffset> zero,
             std::vector<std::string> standing_warnings);

  RigConfig config_;
  std::unique_ptr<Inclinometer> inclinometer_;
  std::optional<InclinometerZeroOffset> zero_;
  std::vector<std::string> standing_warnings_;
};

}  // namespace glarecam::rig
