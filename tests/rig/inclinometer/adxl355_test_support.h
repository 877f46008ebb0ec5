// The ADXL355 driver over its register simulator (rig/inclinometer/adxl355_simulator.h), for the
// tests of the driver, the simulator and the i2c-dev bus: the driver with an observer pointer to
// its simulator, the simulator's options in one call, and text checks.
#pragma once

#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <string_view>

#include "rig/inclinometer/adxl355.h"
#include "rig/inclinometer/adxl355_simulator.h"

namespace glarecam::testing {

inline constexpr std::uint8_t kAddress = 0x1D;
inline constexpr std::string_view kSimUri = "adxl355:sim-i2c@0x1d";

// Writes `text` to `path`, creating its parent directories.
inline void writeFile(const std::filesystem::path& path, const std::string& text) {
  std::filesystem::create_directories(path.parent_path());
  std::ofstream(path) << text;
}

inline bool contains(const std::string& text, std::string_view part) {
  return text.find(part) != std::string::npos;
}

// The driver over a simulator the test keeps an observer pointer to.
struct SimulatedAdxl355 {
  rig::Adxl355Simulator* simulator = nullptr;  // owned by `inclinometer`
  std::unique_ptr<rig::Inclinometer> inclinometer;
};

inline Result<SimulatedAdxl355> openSimulated(
    const rig::Adxl355SimulatorOptions& simulator_options = {},
    const rig::Adxl355Options& options = {}, std::uint8_t address = kAddress) {
  auto bus = std::make_unique<rig::Adxl355Simulator>(simulator_options);
  SimulatedAdxl355 result;
  result.simulator = bus.get();
  GLARECAM_ASSIGN(result.inclinometer,
                  rig::openAdxl355(std::move(bus), address, options, std::string(kSimUri)));
  return result;
}

inline SimulatedAdxl355 openSimulatedOrFail(
    const rig::Adxl355SimulatorOptions& simulator_options = {},
    const rig::Adxl355Options& options = {}) {
  auto opened = openSimulated(simulator_options, options);
  EXPECT_TRUE(opened.has_value()) << opened.error().message;
  return opened ? std::move(*opened) : SimulatedAdxl355{};
}

inline rig::Adxl355SimulatorOptions gravity(double x_g, double y_g, double z_g) {
  rig::Adxl355SimulatorOptions options;
  options.x_g = x_g;
  options.y_g = y_g;
  options.z_g = z_g;
  return options;
}

inline rig::Adxl355Options rangeOf(int range_g) {
  rig::Adxl355Options options;
  options.range_g = range_g;
  return options;
}

inline rig::Adxl355SimulatorOptions withFault(rig::Adxl355SimulatorFault fault) {
  rig::Adxl355SimulatorOptions options;
  options.fault = fault;
  return options;
}

}  // namespace glarecam::testing
