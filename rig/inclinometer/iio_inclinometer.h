// A Linux IIO accelerometer read through sysfs (/sys/bus/iio/devices/iio:deviceN), for boards
// whose accelerometer has a kernel driver (including the ADXL355 under drivers/iio/accel).
//
// Per the IIO sysfs ABI (Documentation/ABI/testing/sysfs-bus-iio): in_accel_{x,y,z}_raw are
// integers; the acceleration in m/s² is (raw + offset) × scale, with the scale from
// in_accel_{x,y,z}_scale or the shared in_accel_scale, and the offset from in_accel_{x,y,z}_offset
// or in_accel_offset (0 when absent). It is converted to g with standard gravity. The die
// temperature, when the driver exposes in_temp_input or in_temp_raw (+ in_temp_offset,
// in_temp_scale), is in milli °C by the same rule.
//
// sysfs has no data-ready flag: two reads in quick succession may return the same conversion
// (the driver decides). So reads are paced by the driver's in_accel_sampling_frequency (or
// sampling_frequency), when it has one: each read() comes at least one sampling period after the
// previous one, and a reading's samples are distinct conversions whose scatter means something.
// Set that frequency low (tens of Hz: docs/rig.md), or the sensor's noise at kHz rates makes a
// still rig look like a moving one.
//
// Errors name the file: no such device (listing the devices present), not an accelerometer (no
// in_accel_x_raw), and an empty, unparsable or non-finite value ("nan") are kHardware; all three
// axes exactly 0 is an error as for every backend.
#pragma once

#include <filesystem>
#include <memory>
#include <string>
#include <string_view>

#include "core/error.h"
#include "rig/inclinometer/inclinometer.h"

namespace glarecam::rig {

inline constexpr std::string_view kIioSysfsRoot = "/sys/bus/iio/devices";

// Opens `device` ("iio:device0") under `sysfs_root`; `uri` (default "iio:" + device) goes into
// info(). Checks the device and its accel channels exist; values are read by read().
Result<std::unique_ptr<Inclinometer>> openIioInclinometer(
    std::string_view device, const std::filesystem::path& sysfs_root = kIioSysfsRoot,
    std::string uri = {});

}  // namespace glarecam::rig
