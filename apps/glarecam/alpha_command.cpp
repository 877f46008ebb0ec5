// glarecam alpha: the angle of incidence α now, from the rig's config, with its uncertainty
// (rig/rig_geometry.h; docs/rig.md).
#include <spdlog/spdlog.h>

#include <cstdio>
#include <memory>
#include <optional>
#include <string>

#include "apps/glarecam/commands.h"
#include "core/time.h"
#include "daemon/daemon_config.h"
#include "rig/rig_config.h"
#include "rig/rig_geometry.h"
#include "sun/clock_sync.h"

namespace glarecam::apps {
namespace {

struct AlphaArgs {
  std::string config = rig::kDefaultRigConfigPath;
  std::optional<std::string> time;
  bool json = false;
  bool no_progress = false;
};

void printGeometry(const rig::RigGeometry& g) {
  const bool from_sun = g.source == rig::GeometrySource::kSun;
  std::printf("alpha %.3f° ± %.2g° (%s; from the tilt %.2g°", g.alpha_deg, g.alpha_uncertainty_deg,
              from_sun ? "the sun" : "a fixed source", g.alpha_uncertainty_tilt_deg);
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
  std::printf("%s elevation %.3f°, azimuth %.3f° at %s\n", from_sun ? "sun" : "source",
              g.source_direction.elevation_deg, g.source_direction.azimuth_deg,
              formatIsoTime(g.time).c_str());
}

Status runAlpha(const AlphaArgs& args) {
  rig::RigConfig config;
  GLARECAM_ASSIGN(config, daemon::readRigConfig(args.config));
  UtcTime time;
  GLARECAM_ASSIGN(time, args.time ? parseIsoTime(*args.time) : Result<UtcTime>(utcNow()));
  // A time the user gave has no clock error.
  const auto clock = args.time ? std::nullopt : std::optional(sun::systemClockStatus());
  std::unique_ptr<rig::RigSensors> sensors;
  GLARECAM_ASSIGN(sensors, rig::RigSensors::open(config));
  rig::RigGeometry geometry;
  GLARECAM_ASSIGN(geometry, sensors->measureShowingProgress(time, clock, !args.no_progress));
  for (const std::string& warning : geometry.warnings) spdlog::warn("alpha: {}", warning);
  if (args.json) {
    printJson(rig::geometryJson(geometry));
  } else {
    printGeometry(geometry);
  }
  return {};
}

}  // namespace

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

}  // namespace glarecam::apps
