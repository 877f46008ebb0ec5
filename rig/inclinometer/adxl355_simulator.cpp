#include "rig/inclinometer/adxl355_simulator.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "rig/inclinometer/adxl355.h"

namespace glarecam::rig {
namespace {

using namespace adxl355;

// FIFO_SAMPLES (0x29) resets to 0x60 (data sheet register summary); kept for a faithful dump.
constexpr std::uint8_t kRegFifoSamples = 0x29;
constexpr std::uint8_t kFifoSamplesResetValue = 0x60;
// Writable bits: FILTER bits 6:0, RANGE bits 7, 6, 1:0, POWER_CTL bits 2:0 (data sheet).
constexpr std::uint8_t kFilterWritableMask = 0x7F;
constexpr std::uint8_t kRangeWritableMask = 0xC3;
constexpr std::uint8_t kPowerCtlWritableMask = 0x07;
// What the wrong_id fault answers: an ADXL345's DEVID (0xE5 at register 0x00, ADXL345 data sheet).
constexpr std::uint8_t kOtherPartDevId = 0xE5;

void encodeAxis(std::int32_t code, std::uint8_t* registers) {
  const auto bits = static_cast<std::uint32_t>(code) & 0xFFFFFu;
  registers[0] = static_cast<std::uint8_t>(bits >> 12);
  registers[1] = static_cast<std::uint8_t>((bits >> 4) & 0xFF);
  registers[2] = static_cast<std::uint8_t>((bits & 0x0F) << 4);
}

}  // namespace

Adxl355Simulator::Adxl355Simulator(Adxl355SimulatorOptions options)
    : options_(std::move(options)), generator_(options_.seed) {
  powerOnReset();
}

void Adxl355Simulator::powerOnReset() {
  registers_.fill(0);
  if (options_.fault == Adxl355SimulatorFault::kWrongId) {
    registers_[kRegDevIdAd] = kOtherPartDevId;
  } else {
    registers_[kRegDevIdAd] = kDevIdAd;
    registers_[kRegDevIdMst] = kDevIdMst;
    registers_[kRegPartId] = kPartId;
  }
  registers_[kRegRevId] = kRevIdResetValue;
  registers_[kRegFilter] = kFilterResetValue;
  registers_[kRegFifoSamples] = kFifoSamplesResetValue;
  registers_[kRegRange] = kRangeResetValue;
  registers_[kRegPowerCtl] = kPowerCtlResetValue;
  status_reads_waiting_ = options_.status_reads_per_sample;
}

bool Adxl355Simulator::measuring() const { return !(registers_[kRegPowerCtl] & kPowerCtlStandby); }

int Adxl355Simulator::rangeG() const { return rangeOfCode(registers_[kRegRange]); }

double Adxl355Simulator::outputDataRateHz() const {
  const int code = registers_[kRegFilter] & kFilterOdrMask;
  // Codes above 10 are reserved; the simulator runs them at the slowest rate.
  return adxl355::outputDataRateHz(std::min(code, kOdrCodeCount - 1));
}

void Adxl355Simulator::setGravity(double x_g, double y_g, double z_g) {
  options_.x_g = x_g;
  options_.y_g = y_g;
  options_.z_g = z_g;
}

double Adxl355Simulator::gaussian() {
  // Box–Muller on 53-bit uniforms: std::mt19937_64 is fully specified by the standard, unlike
  // std::normal_distribution, so the sequence is the same with every standard library.
  constexpr double kTwoToMinus53 = 0x1p-53;
  const double u1 = (static_cast<double>(generator_() >> 11) + 1.0) * kTwoToMinus53;  // (0, 1]
  const double u2 = static_cast<double>(generator_() >> 11) * kTwoToMinus53;          // [0, 1)
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * std::numbers::pi * u2);
}

void Adxl355Simulator::produceSample() {
  const int range_g = rangeG() != 0 ? rangeG() : 2;  // reserved code 00: as ±2 g
  const double sensitivity = sensitivityLsbPerG(range_g);
  const std::array<double, 3> gravity{options_.x_g, options_.y_g, options_.z_g};
  std::array<std::int32_t, 3> codes{};
  for (std::size_t axis = 0; axis < 3; ++axis) {
    const double noisy_g = gravity[axis] + options_.noise_g * gaussian();
    const double code =
        std::clamp(std::round(noisy_g * sensitivity), double{kMinCode}, double{kMaxCode});
    codes[axis] = static_cast<std::int32_t>(code);
  }
  if (options_.fault == Adxl355SimulatorFault::kAllZero) codes = {0, 0, 0};
  if (options_.fault == Adxl355SimulatorFault::kSaturated) codes[0] = kMaxCode;
  encodeAxis(codes[0], &registers_[kRegXData3]);
  encodeAxis(codes[1], &registers_[kRegYData3]);
  encodeAxis(codes[2], &registers_[kRegZData3]);

  const double temp_code =
      std::clamp(std::round(kTempInterceptLsb +
                            kTempSlopeLsbPerC * (options_.temperature_c - kTempInterceptC)),
                 0.0, double{kTempMaxCode});
  const auto temp = static_cast<unsigned>(temp_code);
  registers_[kRegTemp2] = static_cast<std::uint8_t>(temp >> 8);
  registers_[kRegTemp1] = static_cast<std::uint8_t>(temp & 0xFF);

  registers_[kRegStatus] |= kStatusDataReady;
  ++samples_produced_;
}

void Adxl355Simulator::updateDataReady() {
  if (!measuring() || options_.fault == Adxl355SimulatorFault::kNeverReady) return;
  if (registers_[kRegStatus] & kStatusDataReady) return;
  if (options_.real_time) {
    const auto now = std::chrono::steady_clock::now();
    if (now < next_sample_time_) return;
    const auto period = std::chrono::duration_cast<std::chrono::steady_clock::duration>(
        std::chrono::duration<double>(1.0 / outputDataRateHz()));
    // The next sample on the grid of the rate (samples missed while nobody looked are dropped).
    while (next_sample_time_ <= now) next_sample_time_ += period;
    produceSample();
    return;
  }
  if (status_reads_waiting_ > 0) {
    --status_reads_waiting_;
    return;
  }
  produceSample();
}

void Adxl355Simulator::writeRegister(std::uint8_t reg, std::uint8_t value) {
  switch (reg) {
    case kRegFilter:
      registers_[reg] = value & kFilterWritableMask;
      break;
    case kRegRange:
      registers_[reg] = value & kRangeWritableMask;
      break;
    case kRegPowerCtl: {
      const bool was_measuring = measuring();
      registers_[reg] = value & kPowerCtlWritableMask;
      if (!was_measuring && measuring()) {
        // The first sample is one period (or status_reads_per_sample) after entering measurement.
        next_sample_time_ = std::chrono::steady_clock::now() +
                            std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                std::chrono::duration<double>(1.0 / outputDataRateHz()));
        status_reads_waiting_ = options_.status_reads_per_sample;
      }
      break;
    }
    case kRegReset:
      if (value == kResetCode) {
        powerOnReset();
        ++resets_;
      }
      break;
    default:
      break;  // read-only, or a register the simulator does not model
  }
}

Status Adxl355Simulator::transfer(std::uint8_t address, std::span<const std::uint8_t> write,
                                  std::span<std::uint8_t> read) {
  ++transactions_;
  if (options_.fault == Adxl355SimulatorFault::kAbsent || address != options_.address) {
    return hardwareError("no device answers at " + i2cHex(address) + " on " + options_.bus_name +
                         " (simulated NACK)");
  }
  if (!write.empty()) {
    pointer_ = write[0];
    for (std::size_t i = 1; i < write.size(); ++i) writeRegister(pointer_++, write[i]);
  }
  bool read_data = false;
  for (auto& byte : read) {
    if (pointer_ == kRegStatus) updateDataReady();
    if (pointer_ >= kRegXData3 && pointer_ <= kRegZData1) read_data = true;
    byte = registers_[pointer_++];
  }
  if (read_data) {
    registers_[kRegStatus] &= static_cast<std::uint8_t>(~kStatusDataReady);
    status_reads_waiting_ = options_.status_reads_per_sample;
    ++data_reads_;
  }
  return {};
}

}  // namespace glarecam::rig
