// glarecam sun: the apparent sun position at a site and time, by NREL SPA (sun/solar_position.h;
// docs/rig.md).
#include <cstdio>
#include <memory>
#include <optional>
#include <string>

#include "apps/glarecam/commands.h"
#include "apps/glarecam/option_parsing.h"
#include "core/time.h"
#include "sun/clock_sync.h"
#include "sun/solar_position.h"

namespace glarecam::apps {
namespace {

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
  site.pressure_hpa = value.value_or(sun::standardPressureHpa(site.altitude_m));
  GLARECAM_ASSIGN(value, parseOptionalNumber(args.temperature, "--temperature-c"));
  if (value) site.temperature_c = *value;
  GLARECAM_CHECK(sun::validate(site));
  return site;
}

Status runSun(const SunArgs& args) {
  sun::SiteLocation site;
  GLARECAM_ASSIGN(site, siteFromArgs(args));
  UtcTime time;
  GLARECAM_ASSIGN(time, sun::givenTimeOrNow(args.time));
  sun::SolarPositionOptions options;
  GLARECAM_ASSIGN(options.delta_t_s, parseOptionalNumber(args.delta_t, "--delta-t-s"));
  std::optional<double> delta_ut1;
  GLARECAM_ASSIGN(delta_ut1, parseOptionalNumber(args.delta_ut1, "--delta-ut1-s"));
  options.delta_ut1_s = delta_ut1.value_or(0.0);
  sun::SolarPosition sun;
  GLARECAM_ASSIGN(sun, sun::solarPosition(time, site, options));
  if (args.json) {
    printJson(sun::solarPositionJson(sun, site, time));
    return {};
  }
  std::printf(
      "%s at %.6f° %.6f°: elevation %.4f°, zenith %.4f°, azimuth %.4f° (apparent; "
      "refraction %.4f°)\n",
      formatIsoTime(time).c_str(), site.latitude_deg, site.longitude_deg, sun.elevation_deg,
      sun.zenith_deg, sun.azimuth_deg, sun.refraction_deg);
  return {};
}

}  // namespace

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

}  // namespace glarecam::apps
