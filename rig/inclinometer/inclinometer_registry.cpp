#include "rig/inclinometer/inclinometer_registry.h"

#include <fmt/format.h>

#include <string>

#include "rig/inclinometer/adxl355.h"
#include "rig/inclinometer/i2c_bus.h"
#include "rig/inclinometer/iio_inclinometer.h"
#include "rig/inclinometer/sim_inclinometer.h"

namespace glarecam::rig {

namespace {

Result<std::unique_ptr<Inclinometer>> openAdxl355Uri(std::string_view id, std::string uri) {
  Adxl355Uri where;
  GLARECAM_ASSIGN(where, parseAdxl355Id(id));
  std::unique_ptr<I2cBus> bus;
  GLARECAM_ASSIGN(bus, openI2cDevBus(where.bus_path));
  return openAdxl355(std::move(bus), where.address, Adxl355Options{}, std::move(uri));
}

}  // namespace

Result<std::unique_ptr<Inclinometer>> openInclinometer(std::string_view uri) {
  const auto colon = uri.find(':');
  const std::string_view scheme = uri.substr(0, colon);
  const std::string_view id =
      colon == std::string_view::npos ? std::string_view{} : uri.substr(colon + 1);
  if (colon != std::string_view::npos && scheme == "adxl355")
    return openAdxl355Uri(id, std::string(uri));
  if (colon != std::string_view::npos && scheme == "iio") {
    if (id.empty()) return badInput("inclinometer URI iio: needs a device (iio:iio:device0)");
    return openIioInclinometer(id, kIioSysfsRoot, std::string(uri));
  }
  if (colon != std::string_view::npos && scheme == "sim") return openSimInclinometer(id);
  return badInput(fmt::format(
      "inclinometer URI '{}' is not SCHEME:ID with a known scheme (adxl355:/dev/i2c-1@0x1d, "
      "iio:iio:device0, sim:TILT_DEG)",
      uri));
}

bool sameInclinometer(std::string_view a, std::string_view b) {
  constexpr std::string_view kSimScheme = "sim:";
  return a == b || (a.starts_with(kSimScheme) && b.starts_with(kSimScheme));
}

}  // namespace glarecam::rig
