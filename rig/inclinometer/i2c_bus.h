// The seam between inclinometer drivers and an I2C bus: one combined write-then-read transaction,
// as Linux i2c-dev's I2C_RDWR performs it (a repeated start between the two messages). The real
// bus is /dev/i2c-N; tests inject a register-level device simulator behind the same interface.
#pragma once

#include <array>
#include <cstdint>
#include <cstdio>
#include <memory>
#include <span>
#include <string>

#include "core/error.h"

namespace glarecam::rig {

// "0x1d": an address or a register value as the data sheets and i2cdetect write them.
inline std::string i2cHex(unsigned value) {
  std::array<char, 16> text{};
  std::snprintf(text.data(), text.size(), "0x%02x", value);
  return text.data();
}

class I2cBus {
 public:
  virtual ~I2cBus() = default;

  // The bus's name for messages: "/dev/i2c-1".
  virtual const std::string& name() const = 0;

  // Writes `write` to the 7-bit `address`, then (when `read` is not empty) reads read.size()
  // bytes after a repeated start. kHardware error naming the bus and address when the device does
  // not acknowledge or the transfer fails.
  virtual Status transfer(std::uint8_t address, std::span<const std::uint8_t> write,
                          std::span<std::uint8_t> read) = 0;
};

// Opens a Linux i2c-dev bus ("/dev/i2c-1"). kHardware error naming the path when it is absent
// (with a hint to enable I2C and load i2c-dev) or not accessible.
Result<std::unique_ptr<I2cBus>> openI2cDevBus(const std::string& path);

}  // namespace glarecam::rig
