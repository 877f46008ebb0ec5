// The Analog Devices ADXL355: a low-noise 3-axis MEMS accelerometer with a 20-bit ADC, read over
// I2C (any I2cBus: /dev/i2c-N, or the register-level simulator in adxl355_simulator.h).
//
// Opening checks the three ID registers, soft-resets the part, sets the range (±2/4/8 g) and the
// output data rate (its low-pass filter corner is ODR/4, high-pass off), reads both back and
// enters measurement mode. read() polls STATUS.DATA_RDY (bounded by a timeout, sleeping a
// fraction of the sample period between polls), then reads temperature and X/Y/Z in one burst
// so that they belong to the same sample, and converts codes to g with the datasheet's typical
// sensitivity (no per-unit calibration). A read is an error when all three axes are exactly 0
// (a dead or unpowered part reads zeros) or any axis sits at a full-scale code (saturated).
//
// Numbers come from the ADXL354/ADXL355 data sheet (Analog Devices, Rev. D,
// https://www.analog.com/media/en/technical-documentation/data-sheets/adxl354_adxl355.pdf),
// cross-checked against Linux drivers/iio/accel/adxl355_core.c and Analog Devices' no-OS
// drivers/accel/adxl355 driver; each constant says where it is from.
//
// URI: "adxl355:/dev/i2c-1@0x1d": the bus's device node, then the 7-bit address (0x1d with ASEL
// low, 0x53 with ASEL high; 0x1d when "@..." is omitted).
#pragma once

#include <chrono>
#include <cstdint>
#include <memory>
#include <string>
#include <string_view>

#include "core/error.h"
#include "rig/inclinometer/i2c_bus.h"
#include "rig/inclinometer/inclinometer.h"

namespace glarecam::rig {

// The register map and field values the driver and the simulator share.
namespace adxl355 {

// Register addresses: data sheet Table "Register Summary" (= adxl355_core.c ADXL355_*_REG).
inline constexpr std::uint8_t kRegDevIdAd = 0x00;
inline constexpr std::uint8_t kRegDevIdMst = 0x01;
inline constexpr std::uint8_t kRegPartId = 0x02;
inline constexpr std::uint8_t kRegRevId = 0x03;
inline constexpr std::uint8_t kRegStatus = 0x04;
inline constexpr std::uint8_t kRegTemp2 = 0x06;   // TEMP[11:8] in bits 3:0
inline constexpr std::uint8_t kRegTemp1 = 0x07;   // TEMP[7:0]
inline constexpr std::uint8_t kRegXData3 = 0x08;  // X[19:12]; XDATA2 X[11:4]; XDATA1 X[3:0] << 4
inline constexpr std::uint8_t kRegYData3 = 0x0B;
inline constexpr std::uint8_t kRegZData3 = 0x0E;
inline constexpr std::uint8_t kRegZData1 = 0x10;
inline constexpr std::uint8_t kRegFilter = 0x28;
inline constexpr std::uint8_t kRegRange = 0x2C;
inline constexpr std::uint8_t kRegPowerCtl = 0x2D;
inline constexpr std::uint8_t kRegReset = 0x2F;

// ID register contents: data sheet register descriptions (= adxl355_core.c *_VAL).
inline constexpr std::uint8_t kDevIdAd = 0xAD;   // Analog Devices ID
inline constexpr std::uint8_t kDevIdMst = 0x1D;  // Analog Devices MEMS ID
inline constexpr std::uint8_t kPartId = 0xED;    // ADXL355 (the ADXL359 reads 0xE9)

// STATUS bits: data sheet STATUS register (bit 0 DATA_RDY, bit 4 NVM_BUSY).
inline constexpr std::uint8_t kStatusDataReady = 0x01;
inline constexpr std::uint8_t kStatusNvmBusy = 0x10;

// FILTER: ODR_LPF in bits 3:0 (code 0 = 4000 Hz, each step halves it, code 10 = 3.906 Hz),
// HPF_CORNER in bits 6:4 (0 = off): data sheet FILTER register, adxl355_core.c
// ADXL355_FILTER_ODR_MSK / adxl355_odr_table.
inline constexpr std::uint8_t kFilterOdrMask = 0x0F;
inline constexpr int kOdrCodeCount = 11;
inline constexpr double kMaxOutputDataRateHz = 4000.0;

// RANGE: bits 1:0 = 01 ±2 g, 10 ±4 g, 11 ±8 g; bit 7 I2C_HS, bit 6 INT_POL (data sheet RANGE
// register; same codes in no-OS adxl355.h enum adxl355_range). Reset value 0x81.
inline constexpr std::uint8_t kRangeMask = 0x03;
inline constexpr std::uint8_t kRangeResetValue = 0x81;

// POWER_CTL: bit 0 STANDBY (1 = standby, the reset state), bit 1 TEMP_OFF, bit 2 DRDY_OFF.
inline constexpr std::uint8_t kPowerCtlStandby = 0x01;
inline constexpr std::uint8_t kPowerCtlResetValue = 0x01;

// Writing this code to RESET resets the part like a power-on (data sheet RESET register;
// adxl355_core.c ADXL355_RESET_CODE).
inline constexpr std::uint8_t kResetCode = 0x52;

// Other reset values the simulator reproduces (data sheet register summary, Reset column).
inline constexpr std::uint8_t kRevIdResetValue = 0x01;
inline constexpr std::uint8_t kFilterResetValue = 0x00;

// Acceleration data: 20-bit two's complement, left-justified in three bytes. Full-scale codes.
inline constexpr std::int32_t kMaxCode = 0x7FFFF;   // +524287
inline constexpr std::int32_t kMinCode = -0x80000;  // −524288 (register pattern 0x80000)

// Temperature: 12-bit unsigned; nominal intercept 1885 LSB at 25 °C, slope −9.05 LSB/°C (data
// sheet Table 1, "Temperature Sensor"; quoted in adxl355_core.c's IIO_TEMP scale comment).
inline constexpr double kTempInterceptLsb = 1885.0;
inline constexpr double kTempInterceptC = 25.0;
inline constexpr double kTempSlopeLsbPerC = -9.05;
inline constexpr std::int32_t kTempMaxCode = 0xFFF;

// Typical sensitivity in LSB/g at ±2/±4/±8 g: 256000/128000/64000, i.e. 3.9/7.8/15.6 µg/LSB
// (data sheet Table 1, "Sensitivity"; adxl355_core.c: "3.9ug/LSB" at ±2 g, no-OS: ×2 and ×4
// for ±4 g and ±8 g).
double sensitivityLsbPerG(int range_g);
// RANGE bits 1:0 for ±range_g (1, 2, 3), 0 for an unsupported range.
std::uint8_t rangeCode(int range_g);
// ±g of a RANGE bits 1:0 code, 0 for the reserved code 00.
int rangeOfCode(std::uint8_t code);
// ODR_LPF code of an output data rate (4000 Hz → 0 ... 3.906 Hz → 10), -1 when not one of them.
int odrCode(double output_data_rate_hz);
// The output data rate of an ODR_LPF code (4000 / 2^code Hz, for code 0..10).
double outputDataRateHz(int odr_code);

}  // namespace adxl355

// The I2C addresses the ADXL355 answers at: ASEL pin low / high (data sheet, "I2C Protocol").
inline constexpr std::uint8_t kAdxl355AddressAselLow = 0x1D;
inline constexpr std::uint8_t kAdxl355AddressAselHigh = 0x53;

struct Adxl355Options {
  int range_g = 2;  // ±2, ±4 or ±8 g; a tilt sensor wants ±2 g (finest resolution)
  // One of the data sheet's steps 4000, 2000, ..., 15.625, 7.813, 3.906 Hz. The low-pass corner
  // is a quarter of it, so 15.625 Hz averages out vibration of the rig without lagging a tilt.
  double output_data_rate_hz = 15.625;
  // The longest read() waits for DATA_RDY; at least one sample period of the chosen rate.
  std::chrono::milliseconds data_ready_timeout{1000};

  // The first problem in words (a range, a rate not on the data sheet's list, a timeout).
  Status validate() const;
};

// "0x1d", "0X53", "29": a 7-bit I2C device address in 0x03..0x77 (the ones not reserved by the
// I2C specification); badInput otherwise.
Result<std::uint8_t> parseI2cAddress(std::string_view text);

struct Adxl355Uri {
  std::string bus_path;  // "/dev/i2c-1"
  std::uint8_t address = kAdxl355AddressAselLow;
};

// Parses the part of an inclinometer URI after "adxl355:": "/dev/i2c-1@0x1d" or "/dev/i2c-1".
// badInput naming the whole URI for an empty or relative path or a bad address.
Result<Adxl355Uri> parseAdxl355Id(std::string_view id);

// Opens the ADXL355 at `address` on `bus` (which it then owns). `uri` is recorded in info().
// kHardware when nothing answers, the IDs are not an ADXL355's, or a setting does not read back;
// kBadInput for invalid options.
Result<std::unique_ptr<Inclinometer>> openAdxl355(std::unique_ptr<I2cBus> bus, std::uint8_t address,
                                                  const Adxl355Options& options, std::string uri);

}  // namespace glarecam::rig
