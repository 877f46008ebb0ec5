#include "rig/inclinometer/sim_inclinometer.h"

#include <fmt/format.h>

#include <cmath>
#include <string>

#include "core/uri_parameters.h"
#include "rig/inclinometer/adxl355.h"
#include "rig/inclinometer/tilt.h"

namespace glarecam::rig {

namespace {

constexpr std::string_view kUriName = "inclinometer URI sim:";
// The ADXL355's noise at the driver's default 15.6 Hz output data rate: 25 µg/√Hz over the
// ≈ 6 Hz noise bandwidth of its 3.9 Hz low-pass filter (datasheet) ≈ 60 µg.
constexpr double kDefaultNoiseG = 60e-6;
constexpr double kMaxSimTiltDeg = 180.0;
constexpr double kMaxSeed = 0x1p53;  // whole numbers a double holds exactly

// The simulator needs no real-time wait for data: a short bound keeps a never-ready fault quick.
constexpr std::chrono::milliseconds kSimDataReadyTimeout{200};

// The driver over the simulator, introduced as what it is.
class SimInclinometer final : public Inclinometer {
 public:
  SimInclinometer(std::unique_ptr<Inclinometer> driver, std::string uri)
      : driver_(std::move(driver)), info_(driver_->info()) {
    info_.uri = std::move(uri);
    info_.backend = "sim";
    info_.detail = "ADXL355 register simulator: " + info_.detail;
  }
  const InclinometerInfo& info() const override { return info_; }
  Result<AccelerationSample> read() override { return driver_->read(); }

 private:
  std::unique_ptr<Inclinometer> driver_;
  InclinometerInfo info_;
};

struct SimAttitude {
  AxisTilt tilt;
  AxisTilt mounting_offset;
};

Result<Adxl355SimulatorFault> parseFault(std::string_view value) {
  if (value == "none") return Adxl355SimulatorFault::kNone;
  if (value == "absent") return Adxl355SimulatorFault::kAbsent;
  if (value == "wrong-id") return Adxl355SimulatorFault::kWrongId;
  if (value == "zeros") return Adxl355SimulatorFault::kAllZero;
  if (value == "saturated") return Adxl355SimulatorFault::kSaturated;
  if (value == "never-ready") return Adxl355SimulatorFault::kNeverReady;
  return badInput(fmt::format(
      "{} fault={} is unknown (known: none, absent, wrong-id, zeros, saturated, never-ready)",
      kUriName, value));
}

Status applyParameter(std::string_view key, std::string_view value, SimAttitude& attitude,
                      Adxl355SimulatorOptions& options) {
  if (key == "fault") {
    GLARECAM_ASSIGN(options.fault, parseFault(value));
    return {};
  }
  double number = 0;
  GLARECAM_ASSIGN(number, parseUriNumber(value, key, kUriName));
  const auto within = [&](double min, double max) -> Status {
    if (number >= min && number <= max) return {};
    return badInput(
        fmt::format("{} {}={} is outside [{:g}, {:g}]", kUriName, key, value, min, max));
  };
  if (key == "roll_deg") {
    GLARECAM_CHECK(within(-90, 90));
    attitude.tilt.y_deg = number;
  } else if (key == "offset_x_deg" || key == "offset_y_deg") {
    GLARECAM_CHECK(within(-10, 10));
    (key == "offset_x_deg" ? attitude.mounting_offset.x_deg : attitude.mounting_offset.y_deg) =
        number;
  } else if (key == "noise_g") {
    GLARECAM_CHECK(within(0, 1));
    options.noise_g = number;
  } else if (key == "temperature_c") {
    GLARECAM_CHECK(within(-40, 125));  // the ADXL355's operating range (datasheet)
    options.temperature_c = number;
  } else if (key == "seed") {
    if (!(number >= 0 && number < kMaxSeed && number == std::floor(number)))
      return badInput(fmt::format("{} seed={} must be a whole number >= 0", kUriName, value));
    options.seed = static_cast<std::uint64_t>(number);
  } else {
    return badInput(fmt::format(
        "{} unknown key '{}' (known: roll_deg, offset_x_deg, offset_y_deg, noise_g, seed, "
        "temperature_c, fault)",
        kUriName, key));
  }
  return {};
}

}  // namespace

Result<Adxl355SimulatorOptions> parseSimInclinometerId(std::string_view id) {
  const auto comma = id.find(',');
  const std::string_view tilt_text = id.substr(0, comma);
  const std::string_view rest =
      comma == std::string_view::npos ? std::string_view{} : id.substr(comma + 1);
  SimAttitude attitude;
  if (tilt_text.empty())
    return badInput(fmt::format("{} needs the tilt in degrees first (sim:30)", kUriName));
  GLARECAM_ASSIGN(attitude.tilt.x_deg, parseUriNumber(tilt_text, "tilt", kUriName));
  if (std::abs(attitude.tilt.x_deg) > kMaxSimTiltDeg)
    return badInput(fmt::format("{} tilt {} is outside ±180°", kUriName, tilt_text));
  Adxl355SimulatorOptions options;
  options.noise_g = kDefaultNoiseG;
  GLARECAM_CHECK(forEachUriParameter(rest, kUriName, [&](std::string_view key, std::string_view v) {
    return applyParameter(key, v, attitude, options);
  }));
  const AccelerationSample g = mountedGravity(attitude.tilt, attitude.mounting_offset);
  options.x_g = g.x_g;
  options.y_g = g.y_g;
  options.z_g = g.z_g;
  return options;
}

Result<std::unique_ptr<Inclinometer>> openSimInclinometer(std::string_view id) {
  Adxl355SimulatorOptions options;
  GLARECAM_ASSIGN(options, parseSimInclinometerId(id));
  const std::uint8_t address = options.address;
  const std::string uri = "sim:" + std::string(id);
  options.bus_name = uri;  // errors then name the URI: "ADXL355 at 0x1d on sim:30,...: ..."
  Adxl355Options driver_options;
  driver_options.data_ready_timeout = kSimDataReadyTimeout;
  std::unique_ptr<Inclinometer> driver;
  GLARECAM_ASSIGN(driver, openAdxl355(std::make_unique<Adxl355Simulator>(options), address,
                                      driver_options, uri));
  return std::make_unique<SimInclinometer>(std::move(driver), uri);
}

}  // namespace glarecam::rig
