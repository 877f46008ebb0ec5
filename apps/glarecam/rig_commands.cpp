// glarecam sun / alpha / inclinometer: the rig's sensors (rig/rig_geometry.h): the sun's
// position at a site and time, α from the config's geometry, and the inclinometer's readings and
// flip calibration.
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <chrono>
#include <climits>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <optional>
#include <string>

#include "apps/glarecam/commands.h"
#include "apps/glarecam/interruption.h"
#include "apps/glarecam/option_parsing.h"
#include "apps/glarecam/sample_progress.h"
#include "core/atomic_file.h"
#include "core/stack_manifest.h"
#include "daemon/daemon_config.h"
#include "rig/gpio/rig_io_registry.h"
#include "rig/gpio/status_led.h"
#include "rig/inclinometer/inclinometer_registry.h"
#include "rig/inclinometer/zero_offset_file.h"
#include "rig/rig_config.h"
#include "rig/rig_geometry.h"
#include "sun/clock_sync.h"
#include "sun/solar_position.h"
#include "sun/utc_time.h"

namespace glarecam::apps {
namespace {

// --time, else now (with a warning when the clock cannot be trusted).
Result<UtcTime> timeOption(const std::optional<std::string>& text) {
  if (text) return sun::parseIsoTime(*text);
  const sun::ClockStatus clock = sun::systemClockStatus();
  if (!clock.synchronised)
    spdlog::warn("the system clock is not synchronised: {}; a wrong clock is a wrong sun position",
                 clock.detail);
  return utcNow();
}

void printJson(const nlohmann::json& document) { std::fputs(jsonText(document).c_str(), stdout); }

// ---- sun -----------------------------------------------------------------------------------

struct SunArgs {
  std::optional<std::string> latitude, longitude, time, pressure, temperature, altitude;
  std::optional<std::string> delta_t, delta_ut1;
  bool json = false;
};

Result<sun::SiteLocation> siteFromArgs(const SunArgs& args) {
  sun::SiteLocation site;
  std::optional<double> value;
  GLARECAM_ASSIGN(value, parseOptionalNumber(args.latitude, "--lat"));
  site.latitude_deg = *value;
  GLARECAM_ASSIGN(value, parseOptionalNumber(args.longitude, "--lon"));
  site.longitude_deg = *value;
  GLARECAM_ASSIGN(value, parseOptionalNumber(args.altitude, "--altitude-m"));
  site.altitude_m = value.value_or(0.0);
  GLARECAM_ASSIGN(value, parseOptionalNumber(args.pressure, "--pressure-hpa"));
  site.pressure_hpa = value.value_or(rig::standardPressureHpa(site.altitude_m));
  GLARECAM_ASSIGN(value, parseOptionalNumber(args.temperature, "--temperature-c"));
  if (value) site.temperature_c = *value;
  GLARECAM_CHECK(sun::validate(site));
  return site;
}

nlohmann::json sunJson(const sun::SolarPosition& sun, const sun::SiteLocation& site, UtcTime time) {
  return {{"time", sun::formatIsoTime(time)},     {"latitude_deg", site.latitude_deg},
          {"longitude_deg", site.longitude_deg},  {"altitude_m", site.altitude_m},
          {"pressure_hpa", site.pressure_hpa},    {"temperature_c", site.temperature_c},
          {"elevation_deg", sun.elevation_deg},   {"zenith_deg", sun.zenith_deg},
          {"azimuth_deg", sun.azimuth_deg},       {"true_elevation_deg", sun.true_elevation_deg},
          {"refraction_deg", sun.refraction_deg}, {"declination_deg", sun.declination_deg},
          {"hour_angle_deg", sun.hour_angle_deg}, {"delta_t_s", sun.delta_t_s}};
}

Status runSun(const SunArgs& args) {
  sun::SiteLocation site;
  GLARECAM_ASSIGN(site, siteFromArgs(args));
  UtcTime time;
  GLARECAM_ASSIGN(time, timeOption(args.time));
  sun::SolarPositionOptions options;
  GLARECAM_ASSIGN(options.delta_t_s, parseOptionalNumber(args.delta_t, "--delta-t-s"));
  std::optional<double> delta_ut1;
  GLARECAM_ASSIGN(delta_ut1, parseOptionalNumber(args.delta_ut1, "--delta-ut1-s"));
  options.delta_ut1_s = delta_ut1.value_or(0.0);
  sun::SolarPosition sun;
  GLARECAM_ASSIGN(sun, sun::solarPosition(time, site, options));
  if (args.json) {
    printJson(sunJson(sun, site, time));
    return {};
  }
  std::printf(
      "%s at %.6f° %.6f°: elevation %.4f°, zenith %.4f°, azimuth %.4f° (apparent; "
      "refraction %.4f°)\n",
      sun::formatIsoTime(time).c_str(), site.latitude_deg, site.longitude_deg, sun.elevation_deg,
      sun.zenith_deg, sun.azimuth_deg, sun.refraction_deg);
  return {};
}

// ---- alpha ---------------------------------------------------------------------------------

struct AlphaArgs {
  std::string config = rig::kDefaultRigConfigPath;
  std::optional<std::string> time;
  bool json = false;
  bool no_progress = false;
};

// Opens the config's sensors and measures once, showing progress over the inclinometer samples.
Result<rig::RigGeometry> measureGeometry(rig::RigSensors& sensors, UtcTime time,
                                         bool time_from_clock, bool show_progress) {
  const auto& inclinometer = sensors.config().inclinometer;
  return withSampleProgress(inclinometer ? inclinometer->tilt.samples : 0,
                            show_progress && sensors.hasInclinometer(),
                            [&](const std::function<void()>& on_sample) {
                              return sensors.measure(time, on_sample, time_from_clock);
                            });
}

void printGeometry(const rig::RigGeometry& g) {
  std::printf("alpha %.3f° ± %.2g° (%s; from the tilt %.2g°", g.alpha_deg, g.alpha_uncertainty_deg,
              g.source == "sun" ? "the sun" : "a fixed source", g.alpha_uncertainty_tilt_deg);
  if (g.clock_error_unknown)
    std::printf(", from the clock: unknown, not synchronised");
  else if (g.clock)
    std::printf(", from the clock %.2g°", g.alpha_uncertainty_clock_deg);
  std::printf(")\n");
  if (g.tilt) {
    std::printf("module tilt %.3f° (inclinometer %s, σ %.4f° over %d samples), facing %.2f°\n",
                g.module.tilt_deg, g.inclinometer_uri.c_str(), g.tilt->tilt_std_deg,
                g.tilt->samples, g.module.azimuth_deg);
  } else {
    std::printf("module tilt %.3f° (fixed in the config), facing %.2f°\n", g.module.tilt_deg,
                g.module.azimuth_deg);
  }
  std::printf("%s elevation %.3f°, azimuth %.3f° at %s\n", g.source == "sun" ? "sun" : "source",
              g.source_direction.elevation_deg, g.source_direction.azimuth_deg,
              sun::formatIsoTime(g.time).c_str());
}

Status runAlpha(const AlphaArgs& args) {
  rig::RigConfig config;
  GLARECAM_ASSIGN(config, daemon::readRigConfig(args.config));
  UtcTime time;
  GLARECAM_ASSIGN(time, args.time ? sun::parseIsoTime(*args.time) : Result<UtcTime>(utcNow()));
  std::unique_ptr<rig::RigSensors> sensors;
  GLARECAM_ASSIGN(sensors, rig::RigSensors::open(config));
  rig::RigGeometry geometry;
  GLARECAM_ASSIGN(geometry, measureGeometry(*sensors, time, !args.time, !args.no_progress));
  for (const std::string& warning : geometry.warnings) spdlog::warn("alpha: {}", warning);
  if (args.json) {
    printJson(rig::geometryJson(geometry));
  } else {
    printGeometry(geometry);
  }
  return {};
}

// ---- inclinometer --------------------------------------------------------------------------

struct InclinometerArgs {
  std::optional<std::string> uri, config, calibration, out;
  std::optional<std::string> samples;
  std::vector<std::string> from;
  bool json = false;
  bool no_progress = false;
};

// The sensor to use: --inclinometer, else the config's; with the config's tilt options.
struct InclinometerChoice {
  std::string uri;
  rig::TiltOptions tilt;
  std::optional<std::filesystem::path> calibration;  // --calibration, else the config's
};

Result<InclinometerChoice> chooseInclinometer(const InclinometerArgs& args, const char* command) {
  InclinometerChoice choice;
  if (args.config) {
    rig::RigConfig config;
    GLARECAM_ASSIGN(config, daemon::readRigConfig(*args.config));
    if (config.inclinometer) {
      choice.uri = config.inclinometer->uri;
      choice.tilt = config.inclinometer->tilt;
    }
    choice.calibration = config.calibration;
  }
  if (args.uri) choice.uri = *args.uri;
  if (args.calibration) choice.calibration = *args.calibration;
  if (choice.uri.empty())
    return badInput(
        fmt::format("inclinometer {}: give --inclinometer URI, or --config with an "
                    "[inclinometer] uri",
                    command));
  if (args.samples) {
    std::uint64_t samples = 0;
    GLARECAM_ASSIGN(samples, parseUnsigned(*args.samples, "--samples"));
    choice.tilt.samples = static_cast<int>(std::min<std::uint64_t>(samples, INT_MAX));
  }
  GLARECAM_CHECK(choice.tilt.validate());  // the range, as for the config's
  return choice;
}

Result<rig::TiltReading> readTilt(rig::Inclinometer& sensor, const InclinometerChoice& choice,
                                  const rig::InclinometerZeroOffset& zero, bool show_progress) {
  return withSampleProgress(choice.tilt.samples, show_progress,
                            [&](const std::function<void()>& on_sample) {
                              return rig::measureTilt(sensor, choice.tilt, zero, on_sample);
                            });
}

void printReading(const rig::TiltReading& r) {
  std::printf("tilt x %.4f°, y %.4f°; module tilt %.4f° ± %.2g° (σ %.2g° over %d samples",
              r.tilt.x_deg, r.tilt.y_deg, r.module_tilt_deg, r.tilt_uncertainty_deg, r.tilt_std_deg,
              r.samples);
  if (r.mean.temperature_c) std::printf(", %.1f °C", *r.mean.temperature_c);
  std::printf(")\n");
}

Status runInclinometerRead(const InclinometerArgs& args) {
  GLARECAM_CHECK(requireNonEmptyPath(args.out, "--out"));
  InclinometerChoice choice;
  GLARECAM_ASSIGN(choice, chooseInclinometer(args, "read"));
  std::optional<rig::InclinometerZeroOffset> stored;
  std::error_code ec;
  if (choice.calibration && std::filesystem::exists(*choice.calibration, ec))
    GLARECAM_ASSIGN(stored, rig::readZeroOffset(*choice.calibration));
  const rig::InclinometerZeroOffset zero = stored.value_or(rig::InclinometerZeroOffset{});
  std::unique_ptr<rig::Inclinometer> sensor;
  GLARECAM_ASSIGN(sensor, rig::openInclinometer(choice.uri));
  rig::TiltReading reading;
  GLARECAM_ASSIGN(reading, readTilt(*sensor, choice, zero, !args.no_progress));
  nlohmann::json document = rig::tiltReadingJson(reading);
  document["uri"] = choice.uri;
  document["time"] = sun::formatIsoTime(utcNow());
  document["zero_offset_applied"] = stored.has_value();
  if (args.out) GLARECAM_CHECK(writeFileAtomic(*args.out, jsonText(document)));
  if (args.json) {
    printJson(document);
  } else {
    printReading(reading);
    if (stored)
      std::printf("zero offset x %.4f°, y %.4f° removed (from %s)\n", zero.offset.x_deg,
                  zero.offset.y_deg, choice.calibration->c_str());
    else
      std::printf("no zero offset removed (none stored: glarecam inclinometer flip)\n");
  }
  return {};
}

// One reading of the flip: the reading, its record as stored in the calibration file, the sensor.
struct FlipReading {
  rig::TiltReading reading;
  nlohmann::json record;
  std::string uri;
};

Result<FlipReading> readSavedReading(const std::string& path) {
  FlipReading flip;
  GLARECAM_ASSIGN(flip.record, readJsonFile(path));
  GLARECAM_ASSIGN(flip.reading, rig::parseTiltReading(flip.record, path));
  const auto uri = flip.record.find("uri");
  if (uri != flip.record.end() && uri->is_string()) flip.uri = uri->get<std::string>();
  return flip;
}

Result<std::pair<FlipReading, FlipReading>> savedFlipReadings(
    const std::vector<std::string>& from) {
  std::error_code ec;
  if (std::filesystem::equivalent(from[0], from[1], ec))
    return badInput("inclinometer flip: --from names the same reading twice (" + from[0] + ")");
  FlipReading first, second;
  GLARECAM_ASSIGN(first, readSavedReading(from[0]));
  GLARECAM_ASSIGN(second, readSavedReading(from[1]));
  if (first.record == second.record)
    return badInput(
        fmt::format("inclinometer flip: {} and {} hold the same reading", from[0], from[1]));
  if (!first.uri.empty() && !second.uri.empty() && !rig::sameInclinometer(first.uri, second.uri))
    spdlog::warn("inclinometer flip: the readings name different sensors ({} and {})", first.uri,
                 second.uri);
  return std::pair{first, second};
}

Result<FlipReading> liveFlipReading(rig::Inclinometer& sensor, const InclinometerChoice& choice,
                                    bool show_progress) {
  FlipReading flip;
  GLARECAM_ASSIGN(flip.reading, readTilt(sensor, choice, {}, show_progress));
  flip.uri = choice.uri;
  flip.record = rig::tiltReadingJson(flip.reading);
  flip.record["uri"] = choice.uri;
  flip.record["time"] = sun::formatIsoTime(utcNow());
  return flip;
}

// The flip needs a surface near level: its error is second order in the surface's tilt, and a
// reading beyond the plausible offset means the sensor is not on the surface it should be.
Status checkNearLevel(const rig::TiltReading& reading) {
  const double worst = std::max(std::abs(reading.raw_tilt.x_deg), std::abs(reading.raw_tilt.y_deg));
  if (worst <= rig::kMaxPlausibleZeroOffsetDeg) return {};
  return badInput(fmt::format(
      "inclinometer flip: the sensor reads tilt x {:.2f}°, y {:.2f}°; the flip needs a surface "
      "within a few degrees of level (at most {:g}°)",
      reading.raw_tilt.x_deg, reading.raw_tilt.y_deg, rig::kMaxPlausibleZeroOffsetDeg));
}

// The two readings taken now, the operator turning the sensor in between.
Result<std::pair<FlipReading, FlipReading>> liveFlipReadings(const InclinometerArgs& args,
                                                             const InclinometerChoice& choice) {
  std::unique_ptr<rig::Inclinometer> sensor;
  GLARECAM_ASSIGN(sensor, rig::openInclinometer(choice.uri));
  FlipReading first, second;
  GLARECAM_ASSIGN(first, liveFlipReading(*sensor, choice, !args.no_progress));
  GLARECAM_CHECK(checkNearLevel(first.reading));
  std::fprintf(stderr,
               "First reading: tilt x %.4f°, y %.4f°.\nTurn the frame with the sensor 180° on the "
               "surface, into the same outline; let it settle, then press Enter.\n",
               first.reading.raw_tilt.x_deg, first.reading.raw_tilt.y_deg);
  std::string line;
  if (!std::getline(std::cin, line))
    return badInput(
        "inclinometer flip: stdin closed before the second reading (to compute from "
        "saved readings: --from FIRST.json SECOND.json)");
  GLARECAM_ASSIGN(second, liveFlipReading(*sensor, choice, !args.no_progress));
  return std::pair{first, second};
}

Result<std::filesystem::path> flipCalibrationFile(const InclinometerArgs& args,
                                                  InclinometerChoice& choice) {
  if (args.from.empty()) {
    GLARECAM_ASSIGN(choice, chooseInclinometer(args, "flip"));
  } else if (args.calibration) {
    choice.calibration = *args.calibration;
  } else if (args.config) {
    rig::RigConfig config;
    GLARECAM_ASSIGN(config, daemon::readRigConfig(*args.config));
    choice.calibration = config.calibration;
    if (config.inclinometer) choice.uri = config.inclinometer->uri;
  }
  if (!args.from.empty() && args.uri) choice.uri = *args.uri;  // the sensor the readings are of
  if (!choice.calibration)
    return badInput(
        "inclinometer flip: give --calibration FILE (or a --config naming one) to "
        "store the zero offset in");
  // Before anybody turns a sensor: the file must be one the offset can be written into.
  GLARECAM_CHECK(rig::checkZeroOffsetWritable(*choice.calibration));
  return *choice.calibration;
}

Status runInclinometerFlip(const InclinometerArgs& args) {
  InclinometerChoice choice;
  std::filesystem::path calibration;
  GLARECAM_ASSIGN(calibration, flipCalibrationFile(args, choice));
  std::pair<FlipReading, FlipReading> readings;
  GLARECAM_ASSIGN(
      readings, args.from.empty() ? liveFlipReadings(args, choice) : savedFlipReadings(args.from));
  const rig::TiltReading& first = readings.first.reading;
  const rig::TiltReading& second = readings.second.reading;
  GLARECAM_CHECK(checkNearLevel(first));
  GLARECAM_CHECK(checkNearLevel(second));
  const rig::InclinometerZeroOffset zero = rig::flipZeroOffset(first, second);
  if (std::abs(zero.offset.x_deg) > rig::kMaxPlausibleZeroOffsetDeg ||
      std::abs(zero.offset.y_deg) > rig::kMaxPlausibleZeroOffsetDeg)
    return badInput(fmt::format(
        "inclinometer flip: the readings give a zero offset of ({:.2f}°, {:.2f}°), beyond the "
        "plausible {:g}°: the frame was not turned 180° on the surface, or the surface moved",
        zero.offset.x_deg, zero.offset.y_deg, rig::kMaxPlausibleZeroOffsetDeg));
  std::string uri = readings.first.uri.empty() ? readings.second.uri : readings.first.uri;
  if (uri.empty()) uri = choice.uri;
  if (!choice.uri.empty() && !rig::sameInclinometer(uri, choice.uri))
    spdlog::warn("inclinometer flip: the readings are of {}, the configured sensor is {}", uri,
                 choice.uri);
  const nlohmann::json provenance{{"method", "flip"},
                                  {"date", sun::formatIsoTime(utcNow())},
                                  {"uri", uri},
                                  {"readings", {readings.first.record, readings.second.record}}};
  GLARECAM_CHECK(rig::writeZeroOffset(calibration, zero, provenance));
  std::printf(
      "readings: tilt x %.4f°, y %.4f° and x %.4f°, y %.4f°; surface tilt x %.4f°, y %.4f°\n"
      "zero offset x %.4f°, y %.4f° (± %.2g°) written to %s\n",
      first.raw_tilt.x_deg, first.raw_tilt.y_deg, second.raw_tilt.x_deg, second.raw_tilt.y_deg,
      (first.raw_tilt.x_deg - second.raw_tilt.x_deg) / 2,
      (first.raw_tilt.y_deg - second.raw_tilt.y_deg) / 2, zero.offset.x_deg, zero.offset.y_deg,
      zero.uncertainty_deg, calibration.c_str());
  return {};
}

void addInclinometerSource(CLI::App* sub, InclinometerArgs& args) {
  sub->add_option("--inclinometer", args.uri,
                  "inclinometer URI: adxl355:/dev/i2c-1@0x1d, iio:iio:device0, or the simulator "
                  "sim:TILT_DEG[,roll_deg=,offset_x_deg=,offset_y_deg=,noise_g=,seed=,"
                  "temperature_c=,fault=] (docs/rig.md)");
  sub->add_option("--config", args.config, "rig config (TOML) naming the inclinometer");
  sub->add_option("--calibration", args.calibration,
                  "calibration file holding the zero offset (default: the config's)");
  sub->add_option("--samples", args.samples, "samples averaged per reading (default 50)");
  sub->add_flag("--no-progress", args.no_progress, "no progress on stderr");
}

// ---- gpio ----------------------------------------------------------------------------------

struct GpioArgs {
  std::string config = rig::kDefaultRigConfigPath;
  std::optional<std::string> led;
  double seconds = 5;
  std::optional<std::string> trigger;
  bool wait_button = false;
  double timeout_s = 30;
};

constexpr double kMaxGpioSeconds = 3600;  // a wiring check, not a service
constexpr std::uint64_t kMaxTriggerPulses = 10000;
constexpr auto kTriggerSpacing = std::chrono::milliseconds(100);  // 10 Hz: visible on a scope

Result<rig::RigState> parseLedState(const std::string& text) {
  if (text == "ready") return rig::RigState::ready();
  if (text == "capturing") return rig::RigState::capturing();
  for (const auto code : {rig::FaultCode::kCamera, rig::FaultCode::kInclinometer,
                          rig::FaultCode::kDisk, rig::FaultCode::kClock}) {
    if (text == "fault-" + std::string(rig::faultName(code))) return rig::RigState::faulted(code);
  }
  return badInput(
      fmt::format("gpio: --led {} is unknown (known: ready, capturing, fault-camera, "
                  "fault-inclinometer, fault-disk, fault-clock)",
                  text));
}

Status showLed(rig::RigIo& io, rig::RigState state, double seconds) {
  if (!io.hasLed()) return badInput("gpio: --led, but the config's [gpio] has no led line");
  rig::StatusLed led(io);
  led.setStatus(state);
  led.start();
  std::fprintf(stderr, "gpio: showing the LED pattern for %g s (Ctrl-C stops)\n", seconds);
  sleepUntil(std::chrono::steady_clock::now() +
             std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                 std::chrono::duration<double>(seconds)));
  GLARECAM_CHECK(led.stop());
  if (auto error = led.lastError()) return std::unexpected(*error);
  return {};
}

Status pulseTriggers(rig::RigIo& io, std::uint64_t count) {
  if (!io.hasTrigger())
    return badInput("gpio: --trigger, but the config's [gpio] has no trigger line");
  for (std::uint64_t i = 0; i < count; ++i) {
    if (i > 0) std::this_thread::sleep_for(kTriggerSpacing);
    GLARECAM_CHECK(io.pulseTrigger());
  }
  std::printf("trigger: %llu pulse(s)\n", static_cast<unsigned long long>(count));
  return {};
}

Status waitForButton(rig::RigIo& io, const rig::RigIoConfig& config, double timeout_s) {
  if (!io.hasButton())
    return badInput("gpio: --wait-button, but the config's [gpio] has no button line");
  std::fprintf(stderr, "gpio: press the button (waiting %g s)\n", timeout_s);
  const auto deadline = rig::RigClock::now() + std::chrono::duration_cast<rig::RigClock::duration>(
                                                   std::chrono::duration<double>(timeout_s));
  bool pressed = false;
  GLARECAM_ASSIGN(pressed, waitForButtonPress(io, config.debounce, deadline));
  if (stopRequested()) return fail(ErrorCode::kInternal, "gpio: interrupted");
  if (!pressed)
    return fail(ErrorCode::kHardware,
                fmt::format("gpio: no button press within {:g} s", timeout_s));
  std::printf("button: pressed\n");
  return {};
}

Status runGpio(const GpioArgs& args) {
  if (!(args.seconds > 0 && args.seconds <= kMaxGpioSeconds) ||
      !(args.timeout_s > 0 && args.timeout_s <= kMaxGpioSeconds))
    return badInput("gpio: --seconds and --timeout must be in (0, 3600]");
  std::optional<rig::RigState> led_state;
  if (args.led) GLARECAM_ASSIGN(led_state, parseLedState(*args.led));
  std::uint64_t pulses = 0;
  if (args.trigger) {
    GLARECAM_ASSIGN(pulses, parseUnsigned(*args.trigger, "--trigger"));
    if (pulses < 1 || pulses > kMaxTriggerPulses)
      return badInput("gpio: --trigger must be a count in [1, 10000]");
  }
  rig::RigConfig config;
  GLARECAM_ASSIGN(config, daemon::readRigConfig(args.config));
  if (!config.gpio) return badInput(args.config + ": no [gpio] section");
  std::unique_ptr<rig::RigIo> io;
  GLARECAM_ASSIGN(io, rig::openRigIo(*config.gpio));
  std::printf("%s\n", io->description().c_str());
  stopGracefullyOnSignals();  // Ctrl-C ends a pattern or a wait with the lines released
  if (led_state) GLARECAM_CHECK(showLed(*io, *led_state, args.seconds));
  if (stopRequested()) return fail(ErrorCode::kInternal, "gpio: interrupted");
  if (pulses > 0) GLARECAM_CHECK(pulseTriggers(*io, pulses));
  if (args.wait_button) GLARECAM_CHECK(waitForButton(*io, *config.gpio, args.timeout_s));
  if (!led_state && pulses == 0 && !args.wait_button && io->hasButton()) {
    bool pressed = false;
    GLARECAM_ASSIGN(pressed, io->buttonPressed());
    std::printf("button: %s\n", pressed ? "pressed" : "released");
  }
  return {};
}

}  // namespace

void addGpioCommand(CLI::App& app, Action& action) {
  auto args = std::make_shared<GpioArgs>();
  CLI::App* sub = app.add_subcommand(
      "gpio",
      "Check the rig's GPIO wiring: show an LED pattern, pulse the trigger, wait for the button "
      "(the config's [gpio]; docs/rig.md)");
  sub->add_option("--config", args->config, "rig config (TOML)")->capture_default_str();
  sub->add_option("--led", args->led,
                  "show a status: ready, capturing, fault-camera, fault-inclinometer, fault-disk, "
                  "fault-clock");
  sub->add_option("--seconds", args->seconds, "how long --led shows it")->capture_default_str();
  sub->add_option("--trigger", args->trigger, "pulse the trigger line this many times (10 Hz)");
  sub->add_flag("--wait-button", args->wait_button, "wait for a debounced button press");
  sub->add_option("--timeout", args->timeout_s, "seconds --wait-button waits (exit 1 after)")
      ->capture_default_str();
  sub->callback([args, &action] { action = [args] { return runGpio(*args); }; });
}

void addSunCommand(CLI::App& app, Action& action) {
  auto args = std::make_shared<SunArgs>();
  CLI::App* sub = app.add_subcommand(
      "sun", "Print the apparent (refraction-corrected) sun position at a site (docs/rig.md)");
  sub->add_option("--lat", args->latitude, "latitude in degrees, north positive")->required();
  sub->add_option("--lon", args->longitude, "longitude in degrees, east positive")->required();
  sub->add_option(
      "--time", args->time,
      "ISO 8601 time with a zone, e.g. 2026-06-21T12:00:00Z or ...+02:00 (default now)");
  sub->add_option("--altitude-m", args->altitude, "altitude above sea level in metres (default 0)");
  sub->add_option("--pressure-hpa", args->pressure,
                  "air pressure for refraction (default: the standard atmosphere at the altitude)");
  sub->add_option("--temperature-c", args->temperature,
                  "air temperature for refraction (default 12)");
  sub->add_option("--delta-t-s", args->delta_t,
                  "ΔT = TT − UT1 in seconds (default: Espenak & Meeus's polynomial; 1 s moves the "
                  "sun 0.00001°)");
  sub->add_option("--delta-ut1-s", args->delta_ut1,
                  "UT1 − UTC in seconds, |x| < 1 (IERS Bulletin A; default 0; 1 s is 0.004°)");
  sub->add_flag("--json", args->json,
                "print JSON: elevation_deg, zenith_deg, azimuth_deg (clockwise from north), ...");
  sub->callback([args, &action] { action = [args] { return runSun(*args); }; });
}

void addAlphaCommand(CLI::App& app, Action& action) {
  auto args = std::make_shared<AlphaArgs>();
  CLI::App* sub = app.add_subcommand(
      "alpha",
      "Measure the angle of incidence α now from the rig's config: inclinometer tilt, module "
      "azimuth, sun or fixed source; with its uncertainty (docs/rig.md)");
  sub->add_option("--config", args->config, "rig config (TOML)")->capture_default_str();
  sub->add_option("--time", args->time, "ISO 8601 time with a zone (default now)");
  sub->add_flag("--json", args->json, "print the geometry block a capture records, as JSON");
  sub->add_flag("--no-progress", args->no_progress, "no progress on stderr");
  sub->callback([args, &action] { action = [args] { return runAlpha(*args); }; });
}

void addInclinometerCommand(CLI::App& app, Action& action) {
  CLI::App* sub = app.add_subcommand(
      "inclinometer", "Read the inclinometer, or calibrate its zero offset (docs/rig.md)");
  sub->require_subcommand(1);
  auto read_args = std::make_shared<InclinometerArgs>();
  CLI::App* read = sub->add_subcommand(
      "read", "Average a tilt reading (the stored zero offset removed) and print it");
  addInclinometerSource(read, *read_args);
  read->add_flag("--json", read_args->json, "print the reading as JSON");
  read->add_option("--out", read_args->out, "also write the reading (JSON) to this file");
  read->callback(
      [read_args, &action] { action = [read_args] { return runInclinometerRead(*read_args); }; });
  auto flip_args = std::make_shared<InclinometerArgs>();
  CLI::App* flip = sub->add_subcommand(
      "flip",
      "Zero-offset calibration by the flip method: a reading, then you turn the frame 180° "
      "on the surface and press Enter, a second reading; stores the offset in the "
      "calibration file (docs/rig.md)");
  addInclinometerSource(flip, *flip_args);
  flip->add_option("--from", flip_args->from,
                   "compute from two saved readings (inclinometer read --out) instead")
      ->expected(2);
  flip->callback(
      [flip_args, &action] { action = [flip_args] { return runInclinometerFlip(*flip_args); }; });
}

}  // namespace glarecam::apps
