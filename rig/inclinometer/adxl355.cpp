#include "rig/inclinometer/adxl355.h"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <thread>

namespace glarecam::rig {

namespace adxl355 {

namespace {
// Typical sensitivity at ±2 g (data sheet Table 1: 256000 LSB/g = 3.9 µg/LSB); it halves with
// each doubling of the range.
constexpr double kSensitivityAt2gLsbPerG = 256000.0;
constexpr int kRangesG[] = {2, 4, 8};
// ODR steps are matched within this (the data sheet rounds 7.8125 to 7.813 and 3.90625 to 3.906).
constexpr double kOdrMatchToleranceHz = 1e-3;
}  // namespace

double sensitivityLsbPerG(int range_g) {
  switch (range_g) {
    case 2:
      return kSensitivityAt2gLsbPerG;
    case 4:
      return kSensitivityAt2gLsbPerG / 2;
    case 8:
      return kSensitivityAt2gLsbPerG / 4;
    default:
      return 0.0;
  }
}

std::uint8_t rangeCode(int range_g) {
  switch (range_g) {
    case 2:
      return 0x01;
    case 4:
      return 0x02;
    case 8:
      return 0x03;
    default:
      return 0x00;
  }
}

int rangeOfCode(std::uint8_t code) {
  switch (code & kRangeMask) {
    case 0x01:
      return 2;
    case 0x02:
      return 4;
    case 0x03:
      return 8;
    default:
      return 0;
  }
}

double outputDataRateHz(int odr_code) { return kMaxOutputDataRateHz / std::ldexp(1.0, odr_code); }

int odrCode(double output_data_rate_hz) {
  for (int code = 0; code < kOdrCodeCount; ++code) {
    if (std::abs(outputDataRateHz(code) - output_data_rate_hz) <= kOdrMatchToleranceHz) {
      return code;
    }
  }
  return -1;
}

}  // namespace adxl355

namespace {

using namespace adxl355;
using Clock = std::chrono::steady_clock;

// After a soft reset the part reloads its trim from NVM (STATUS.NVM_BUSY); the data sheet gives
// no figure, so this bound is generous: a part still busy after it is broken.
constexpr std::chrono::milliseconds kNvmLoadTimeout{100};
constexpr std::chrono::microseconds kNvmPollInterval{500};
// DATA_RDY polls are a quarter of a sample period apart (so a sample is picked up within a
// quarter period of its arrival), but never closer than this, to leave the bus to others.
constexpr int kPollsPerSamplePeriod = 4;
constexpr std::chrono::microseconds kMinPollInterval{100};
// The longest data_ready_timeout accepted: read() must not look like a hang.
constexpr std::chrono::milliseconds kMaxDataReadyTimeout{60'000};
// Burst from TEMP2 to ZDATA1: temperature and the three axes of one sample.
constexpr std::size_t kBurstBytes = kRegZData1 - kRegTemp2 + 1;

std::int32_t decodeAxis(const std::uint8_t* bytes) {
  const std::uint32_t raw = (std::uint32_t{bytes[0]} << 12) | (std::uint32_t{bytes[1]} << 4) |
                            (std::uint32_t{bytes[2]} >> 4);
  // Sign-extend 20 bits.
  return static_cast<std::int32_t>(raw ^ 0x80000u) - 0x80000;
}

class Adxl355 final : public Inclinometer {
 public:
  Adxl355(std::unique_ptr<I2cBus> bus, std::uint8_t address, const Adxl355Options& options,
          std::string uri)
      : bus_(std::move(bus)), address_(address), options_(options) {
    info_.uri = std::move(uri);
    info_.backend = "adxl355";
    info_.model = "ADXL355";
    info_.full_scale_g = options.range_g;
    const double period_s = 1.0 / options.output_data_rate_hz;
    poll_interval_ = std::max(kMinPollInterval,
                              std::chrono::duration_cast<std::chrono::microseconds>(
                                  std::chrono::duration<double>(period_s / kPollsPerSamplePeriod)));
  }

  const InclinometerInfo& info() const override { return info_; }

  Status setUp();
  Result<AccelerationSample> read() override;

 private:
  std::string where() const { return "ADXL355 at " + i2cHex(address_) + " on " + bus_->name(); }
  Result<std::uint8_t> readRegister(std::uint8_t reg);
  Status readRegisters(std::uint8_t first, std::span<std::uint8_t> values);
  Status writeRegister(std::uint8_t reg, std::uint8_t value);

  std::unique_ptr<I2cBus> bus_;
  std::uint8_t address_;
  Adxl355Options options_;
  InclinometerInfo info_;
  std::chrono::microseconds poll_interval_{};
};

Status Adxl355::readRegisters(std::uint8_t first, std::span<std::uint8_t> values) {
  const std::array<std::uint8_t, 1> pointer{first};
  return bus_->transfer(address_, pointer, values);
}

Result<std::uint8_t> Adxl355::readRegister(std::uint8_t reg) {
  std::array<std::uint8_t, 1> value{};
  GLARECAM_CHECK(readRegisters(reg, value));
  return value[0];
}

Status Adxl355::writeRegister(std::uint8_t reg, std::uint8_t value) {
  const std::array<std::uint8_t, 2> bytes{reg, value};
  return bus_->transfer(address_, bytes, {});
}

Status Adxl355::setUp() {
  std::array<std::uint8_t, 4> ids{};  // DEVID_AD, DEVID_MST, PARTID, REVID
  GLARECAM_CHECK(readRegisters(kRegDevIdAd, ids));
  if (ids[0] != kDevIdAd || ids[1] != kDevIdMst || ids[2] != kPartId) {
    return hardwareError(
        "device at " + i2cHex(address_) + " on " + bus_->name() + " is not an ADXL355 (DEVID_AD " +
        i2cHex(ids[0]) + ", DEVID_MST " + i2cHex(ids[1]) + ", PARTID " + i2cHex(ids[2]) +
        "; expected " + i2cHex(kDevIdAd) + ", " + i2cHex(kDevIdMst) + ", " + i2cHex(kPartId) + ")");
  }

  GLARECAM_CHECK(writeRegister(kRegReset, kResetCode));
  const auto nvm_deadline = Clock::now() + kNvmLoadTimeout;
  for (;;) {
    std::uint8_t status = 0;
    GLARECAM_ASSIGN(status, readRegister(kRegStatus));
    if (!(status & kStatusNvmBusy)) break;
    if (Clock::now() >= nvm_deadline) {
      return hardwareError(where() + ": still loading its NVM (STATUS.NVM_BUSY) " +
                           std::to_string(kNvmLoadTimeout.count()) + " ms after a soft reset");
    }
    std::this_thread::sleep_for(kNvmPollInterval);
  }

  // Reset left the part in standby, where RANGE and FILTER may be written.
  std::uint8_t range = 0;
  GLARECAM_ASSIGN(range, readRegister(kRegRange));
  const std::uint8_t range_wanted =
      static_cast<std::uint8_t>((range & ~kRangeMask) | rangeCode(options_.range_g));
  GLARECAM_CHECK(writeRegister(kRegRange, range_wanted));
  const int odr_code = odrCode(options_.output_data_rate_hz);
  const auto filter_wanted = static_cast<std::uint8_t>(odr_code);  // high-pass off
  GLARECAM_CHECK(writeRegister(kRegFilter, filter_wanted));

  // Read back what the part applied.
  std::uint8_t range_applied = 0;
  std::uint8_t filter_applied = 0;
  GLARECAM_ASSIGN(range_applied, readRegister(kRegRange));
  GLARECAM_ASSIGN(filter_applied, readRegister(kRegFilter));
  if ((range_applied & kRangeMask) != rangeCode(options_.range_g) ||
      filter_applied != filter_wanted) {
    return hardwareError(where() + ": settings did not take (RANGE " + i2cHex(range_applied) +
                         ", FILTER " + i2cHex(filter_applied) + "; wrote " + i2cHex(range_wanted) +
                         ", " + i2cHex(filter_wanted) + ")");
  }

  // Measurement mode, temperature on, DRDY pin on.
  GLARECAM_CHECK(writeRegister(kRegPowerCtl, 0x00));
  std::uint8_t power = 0;
  GLARECAM_ASSIGN(power, readRegister(kRegPowerCtl));
  if (power & kPowerCtlStandby) {
    return hardwareError(where() + ": stays in standby (POWER_CTL " + i2cHex(power) + ")");
  }

  char odr_text[32];
  std::snprintf(odr_text, sizeof odr_text, "%g", outputDataRateHz(odr_code));
  info_.detail = "±" + std::to_string(options_.range_g) + " g, ODR " + odr_text +
                 " Hz (low-pass ODR/4, high-pass off), " + i2cHex(address_) + " on " +
                 bus_->name() + ", REVID " + i2cHex(ids[3]);
  return {};
}

Result<AccelerationSample> Adxl355::read() {
  const auto deadline = Clock::now() + options_.data_ready_timeout;
  for (;;) {
    std::uint8_t status = 0;
    GLARECAM_ASSIGN(status, readRegister(kRegStatus));
    if (status & kStatusDataReady) break;
    const auto now = Clock::now();
    if (now >= deadline) {
      return hardwareError(where() + ": no new sample within " +
                           std::to_string(options_.data_ready_timeout.count()) +
                           " ms (STATUS.DATA_RDY never set)");
    }
    std::this_thread::sleep_for(std::min<Clock::duration>(poll_interval_, deadline - now));
  }

  std::array<std::uint8_t, kBurstBytes> burst{};
  GLARECAM_CHECK(readRegisters(kRegTemp2, burst));
  const auto at = [&](std::uint8_t reg) { return burst.data() + (reg - kRegTemp2); };
  const std::array<std::int32_t, 3> codes{decodeAxis(at(kRegXData3)), decodeAxis(at(kRegYData3)),
                                          decodeAxis(at(kRegZData3))};
  if (codes[0] == 0 && codes[1] == 0 && codes[2] == 0) {
    return hardwareError(where() + ": all three axes read exactly 0 (sensor dead or unpowered)");
  }
  constexpr std::array<char, 3> kAxisNames{'X', 'Y', 'Z'};
  for (std::size_t axis = 0; axis < codes.size(); ++axis) {
    if (codes[axis] == kMaxCode || codes[axis] == kMinCode) {
      return hardwareError(where() + ": " + kAxisNames[axis] + " axis saturated (code " +
                           std::to_string(codes[axis]) + ", beyond ±" +
                           std::to_string(options_.range_g) + " g)");
    }
  }

  const double sensitivity = sensitivityLsbPerG(options_.range_g);
  AccelerationSample sample;
  sample.x_g = codes[0] / sensitivity;
  sample.y_g = codes[1] / sensitivity;
  sample.z_g = codes[2] / sensitivity;
  const int temp_code = ((*at(kRegTemp2) & 0x0F) << 8) | *at(kRegTemp1);
  sample.temperature_c = kTempInterceptC + (temp_code - kTempInterceptLsb) / kTempSlopeLsbPerC;
  return sample;
}

}  // namespace

Status Adxl355Options::validate() const {
  if (adxl355::sensitivityLsbPerG(range_g) == 0.0) {
    return badInput("ADXL355 range ±" + std::to_string(range_g) + " g: must be ±2, ±4 or ±8 g");
  }
  if (!std::isfinite(output_data_rate_hz) || adxl355::odrCode(output_data_rate_hz) < 0) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", output_data_rate_hz);
    return badInput(std::string("ADXL355 output data rate ") + text +
                    " Hz: must be one of 4000, 2000, 1000, 500, 250, 125, 62.5, 31.25, 15.625, "
                    "7.813, 3.906 Hz");
  }
  // The period of the data sheet's step (3.906 Hz is 4000/1024 Hz: 256 ms).
  const auto period = std::chrono::duration<double>(
      1.0 / adxl355::outputDataRateHz(adxl355::odrCode(output_data_rate_hz)));
  if (data_ready_timeout < period || data_ready_timeout > kMaxDataReadyTimeout) {
    return badInput("ADXL355 data-ready timeout " + std::to_string(data_ready_timeout.count()) +
                    " ms: must lie between one sample period (" +
                    std::to_string(static_cast<int>(std::ceil(period.count() * 1000))) +
                    " ms) and " + std::to_string(kMaxDataReadyTimeout.count()) + " ms");
  }
  return {};
}

namespace {
// 7-bit addresses 0x00..0x02 and 0x78..0x7F are reserved by the I2C specification (NXP UM10204,
// "Reserved addresses").
constexpr unsigned kFirstI2cAddress = 0x03;
constexpr unsigned kLastI2cAddress = 0x77;
}  // namespace

Result<std::uint8_t> parseI2cAddress(std::string_view text) {
  const auto bad = [&] {
    return badInput("bad I2C address '" + std::string(text) +
                    "' (expected a 7-bit address 0x03..0x77, e.g. 0x1d or 0x53)");
  };
  std::string_view digits = text;
  int base = 10;
  if (digits.size() > 2 && digits[0] == '0' && (digits[1] == 'x' || digits[1] == 'X')) {
    digits.remove_prefix(2);
    base = 16;
  }
  if (digits.empty()) return bad();
  unsigned value = 0;
  const auto [end, error] =
      std::from_chars(digits.data(), digits.data() + digits.size(), value, base);
  if (error != std::errc() || end != digits.data() + digits.size()) return bad();
  if (value < kFirstI2cAddress || value > kLastI2cAddress) return bad();
  return static_cast<std::uint8_t>(value);
}

Result<Adxl355Uri> parseAdxl355Id(std::string_view id) {
  const std::string uri = "adxl355:" + std::string(id);
  const std::string expected = " (expected adxl355:/dev/i2c-N or adxl355:/dev/i2c-N@0x1d)";
  Adxl355Uri parsed;
  std::string_view path = id;
  if (const auto at = id.rfind('@'); at != std::string_view::npos) {
    path = id.substr(0, at);
    auto address = parseI2cAddress(id.substr(at + 1));
    if (!address) return std::unexpected(withContext(address.error(), uri));
    parsed.address = *address;
  }
  if (path.empty()) return badInput(uri + ": missing the I2C bus device" + expected);
  if (path.front() != '/') {
    return badInput(uri + ": the I2C bus must be an absolute device path" + expected);
  }
  parsed.bus_path = std::string(path);
  return parsed;
}

Result<std::unique_ptr<Inclinometer>> openAdxl355(std::unique_ptr<I2cBus> bus, std::uint8_t address,
                                                  const Adxl355Options& options, std::string uri) {
  GLARECAM_CHECK(options.validate());
  if (!bus) return badInput(uri + ": no I2C bus");
  auto device = std::make_unique<Adxl355>(std::move(bus), address, options, std::move(uri));
  GLARECAM_CHECK(device->setUp());
  return std::unique_ptr<Inclinometer>(std::move(device));
}

}  // namespace glarecam::rig
