// A register-level ADXL355 behind the I2cBus seam: the real driver (adxl355.h) runs unchanged
// over it, in tests and behind the "sim:" inclinometer.
//
// It answers the transactions the part answers: a write whose first byte sets the register
// pointer and whose further bytes are written to successive registers (auto-increment), and a
// read after a repeated start that returns successive registers from the pointer. Writes reach
// FILTER, RANGE, POWER_CTL and RESET (0x52 restores the power-on register values); other
// registers are read-only here. The simulated gravity vector (in g, sensor frame) is encoded per
// the current RANGE as 20-bit left-justified two's complement, clamped to the full-scale codes;
// the temperature as the data sheet's 12-bit code.
//
// Timing: samples are produced only in measurement mode (POWER_CTL.STANDBY clear). By default
// time is virtual: a new sample becomes ready (STATUS.DATA_RDY set, data registers latched) when
// STATUS is read `status_reads_per_sample` times after the previous sample was consumed, so
// tests run at full speed and never depend on the wall clock. With `real_time` a new sample is
// ready once per period of the configured output data rate on the steady clock. Reading any of
// the data registers XDATA3..ZDATA1 clears DATA_RDY. Noise is drawn per produced sample from a
// generator seeded by `seed`: the sample sequence is the same on every run.
#pragma once

#include <array>
#include <chrono>
#include <cstdint>
#include <random>
#include <string>

#include "rig/inclinometer/i2c_bus.h"

namespace glarecam::rig {

enum class Adxl355SimulatorFault {
  kNone,
  kAbsent,      // nothing acknowledges at any address
  kWrongId,     // ID registers of another part (an ADXL345's 0xE5 at register 0x00)
  kAllZero,     // every data register reads 0
  kSaturated,   // X reads the positive full-scale code
  kNeverReady,  // DATA_RDY is never set
};

struct Adxl355SimulatorOptions {
  double x_g = 0.0, y_g = 0.0, z_g = 1.0;  // gravity's reaction in the sensor frame (flat: +Z up)
  double noise_g = 0.0;                    // 1σ white noise per sample and axis
  std::uint64_t seed = 1;
  double temperature_c = 25.0;
  std::uint8_t address = 0x1D;  // the ADXL355's address with ASEL low
  Adxl355SimulatorFault fault = Adxl355SimulatorFault::kNone;
  std::string bus_name = "sim-i2c";
  // Virtual time: STATUS reads that find no sample before the next one is ready (0: the first).
  int status_reads_per_sample = 0;
  bool real_time = false;  // pace samples at the configured output data rate instead
};

class Adxl355Simulator final : public I2cBus {
 public:
  explicit Adxl355Simulator(Adxl355SimulatorOptions options = {});

  const std::string& name() const override { return options_.bus_name; }
  Status transfer(std::uint8_t address, std::span<const std::uint8_t> write,
                  std::span<std::uint8_t> read) override;

  // Tilts the simulated sensor: the next sample produced uses this vector.
  void setGravity(double x_g, double y_g, double z_g);
  void setTemperature(double temperature_c) { options_.temperature_c = temperature_c; }

  // What a test inspects.
  int transactions() const { return transactions_; }  // every transfer(), acknowledged or not
  int resets() const { return resets_; }              // RESET writes of 0x52
  int samplesProduced() const { return samples_produced_; }
  int dataReads() const { return data_reads_; }  // reads touching XDATA3..ZDATA1
  bool measuring() const;                        // POWER_CTL.STANDBY clear
  int rangeG() const;                            // ±g of RANGE (0 for the reserved code)
  double outputDataRateHz() const;               // of FILTER.ODR_LPF
  std::uint8_t registerValue(std::uint8_t reg) const { return registers_[reg]; }

 private:
  void powerOnReset();
  void writeRegister(std::uint8_t reg, std::uint8_t value);
  void updateDataReady();
  void produceSample();
  double gaussian();

  Adxl355SimulatorOptions options_;
  std::array<std::uint8_t, 256> registers_{};
  std::uint8_t pointer_ = 0;
  std::mt19937_64 generator_;
  int status_reads_waiting_ = 0;
  std::chrono::steady_clock::time_point next_sample_time_{};
  int transactions_ = 0;
  int resets_ = 0;
  int samples_produced_ = 0;
  int data_reads_ = 0;
};

}  // namespace glarecam::rig
