#include "rig/inclinometer/iio_inclinometer.h"

#include <fcntl.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <optional>
#include <system_error>
#include <thread>
#include <vector>

#include "core/unique_fd.h"

namespace glarecam::rig {
namespace {

namespace fs = std::filesystem;

// Standard acceleration of gravity, 9.80665 m/s² exactly (3rd CGPM, 1901; BIPM SI Brochure): the
// IIO ABI's accelerations are in m/s², ours in g.
constexpr double kStandardGravityM_s2 = 9.80665;
// sysfs attributes are at most one page (PAGE_SIZE, 4096 on the targets we run on).
constexpr std::size_t kMaxAttributeBytes = 4096;
// in_temp_* are in milli degrees Celsius (sysfs-bus-iio, in_temp_raw).
constexpr double kMilliPerUnit = 1000.0;

constexpr std::array<std::string_view, 3> kAxes{"x", "y", "z"};

// The text of a sysfs attribute, trailing whitespace removed; nullopt when it does not exist.
Result<std::optional<std::string>> readAttribute(const fs::path& path) {
  UniqueFd fd(::open(path.c_str(), O_RDONLY | O_CLOEXEC));
  if (!fd.valid()) {
    const int error = errno;
    if (error == ENOENT) return std::optional<std::string>{};
    if (error == EACCES || error == EPERM) {
      return ioError(path.string() + ": permission denied");
    }
    return hardwareError(path.string() + ": " + std::system_category().message(error));
  }
  std::string text(kMaxAttributeBytes, '\0');
  ssize_t count = 0;
  do {
    count = ::read(fd.get(), text.data(), text.size());
  } while (count < 0 && errno == EINTR);
  if (count < 0) {
    // A driver that fails to talk to its chip returns the bus error here (EIO, ETIMEDOUT...).
    return hardwareError(path.string() + ": read failed: " + std::system_category().message(errno));
  }
  text.resize(static_cast<std::size_t>(count));
  text.erase(text.find_last_not_of(" \t\r\n") + 1);
  return std::optional<std::string>(std::move(text));
}

Result<double> parseNumber(const fs::path& path, const std::string& text) {
  if (text.empty()) return hardwareError(path.string() + ": empty");
  double value = 0.0;
  const auto* begin = text.data();
  const auto* end = text.data() + text.size();
  const auto [stop, error] = std::from_chars(begin, end, value);
  if (error != std::errc() || stop != end) {
    return hardwareError(path.string() + ": not a number: '" + text + "'");
  }
  if (!std::isfinite(value)) {
    return hardwareError(path.string() + ": not a finite number: '" + text + "'");
  }
  return value;
}

// A required number.
Result<double> readNumber(const fs::path& path) {
  std::optional<std::string> text;
  GLARECAM_ASSIGN(text, readAttribute(path));
  if (!text) return hardwareError(path.string() + ": missing");
  return parseNumber(path, *text);
}

// An optional number: the first of `paths` that exists, nullopt when none does.
Result<std::optional<double>> readOptionalNumber(std::initializer_list<fs::path> paths) {
  for (const auto& path : paths) {
    std::optional<std::string> text;
    GLARECAM_ASSIGN(text, readAttribute(path));
    if (!text) continue;
    double value = 0.0;
    GLARECAM_ASSIGN(value, parseNumber(path, *text));
    return std::optional<double>(value);
  }
  return std::optional<double>{};
}

class IioInclinometer final : public Inclinometer {
 public:
  IioInclinometer(fs::path directory, InclinometerInfo info,
                  std::chrono::steady_clock::duration sampling_period)
      : directory_(std::move(directory)),
        info_(std::move(info)),
        sampling_period_(sampling_period) {}

  const InclinometerInfo& info() const override { return info_; }
  Result<AccelerationSample> read() override;

 private:
  Result<double> readAxisM_s2(std::string_view axis);
  Result<std::optional<double>> readTemperatureC();

  // Waits until one sampling period has passed since the previous read.
  void pace();

  fs::path directory_;
  InclinometerInfo info_;
  std::chrono::steady_clock::duration sampling_period_;  // zero: unknown, reads not paced
  std::optional<std::chrono::steady_clock::time_point> last_read_;
};

void IioInclinometer::pace() {
  const auto now = std::chrono::steady_clock::now();
  if (last_read_ && sampling_period_ > std::chrono::steady_clock::duration::zero())
    std::this_thread::sleep_until(*last_read_ + sampling_period_);
  last_read_ = std::max(now, last_read_ ? *last_read_ + sampling_period_ : now);
}

Result<double> IioInclinometer::readAxisM_s2(std::string_view axis) {
  const std::string channel = "in_accel_" + std::string(axis);
  double raw = 0.0;
  GLARECAM_ASSIGN(raw, readNumber(directory_ / (channel + "_raw")));
  std::optional<double> scale;
  GLARECAM_ASSIGN(scale, readOptionalNumber(
                             {directory_ / (channel + "_scale"), directory_ / "in_accel_scale"}));
  if (!scale) {
    return hardwareError((directory_ / "in_accel_scale").string() + ": missing (nor " + channel +
                         "_scale): the raw value cannot be converted to m/s²");
  }
  std::optional<double> offset;
  GLARECAM_ASSIGN(offset, readOptionalNumber({directory_ / (channel + "_offset"),
                                              directory_ / "in_accel_offset"}));
  return (raw + offset.value_or(0.0)) * *scale;
}

Result<std::optional<double>> IioInclinometer::readTemperatureC() {
  std::optional<double> processed;
  GLARECAM_ASSIGN(processed, readOptionalNumber({directory_ / "in_temp_input"}));
  if (processed) return std::optional<double>(*processed / kMilliPerUnit);
  std::optional<double> raw;
  GLARECAM_ASSIGN(raw, readOptionalNumber({directory_ / "in_temp_raw"}));
  if (!raw) return std::optional<double>{};
  std::optional<double> scale;
  std::optional<double> offset;
  GLARECAM_ASSIGN(scale, readOptionalNumber({directory_ / "in_temp_scale"}));
  GLARECAM_ASSIGN(offset, readOptionalNumber({directory_ / "in_temp_offset"}));
  return std::optional<double>((*raw + offset.value_or(0.0)) * scale.value_or(1.0) / kMilliPerUnit);
}

Result<AccelerationSample> IioInclinometer::read() {
  pace();
  std::array<double, 3> m_s2{};
  for (std::size_t i = 0; i < kAxes.size(); ++i) {
    GLARECAM_ASSIGN(m_s2[i], readAxisM_s2(kAxes[i]));
  }
  if (m_s2[0] == 0.0 && m_s2[1] == 0.0 && m_s2[2] == 0.0) {
    return hardwareError(directory_.string() +
                         ": in_accel_{x,y,z} all read exactly 0 (sensor dead or unpowered)");
  }
  AccelerationSample sample;
  sample.x_g = m_s2[0] / kStandardGravityM_s2;
  sample.y_g = m_s2[1] / kStandardGravityM_s2;
  sample.z_g = m_s2[2] / kStandardGravityM_s2;
  GLARECAM_ASSIGN(sample.temperature_c, readTemperatureC());
  return sample;
}

// Enough digits for an IIO scale such as 0.000038245 (IIO_VAL_INT_PLUS_NANO).
std::string formatNumber(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.9g", value);
  return text;
}

std::string devicesPresent(const fs::path& root) {
  std::error_code error;
  std::vector<std::string> names;
  for (fs::directory_iterator it(root, error), end; !error && it != end; it.increment(error)) {
    const std::string name = it->path().filename().string();
    if (name.starts_with("iio:device")) names.push_back(name);
  }
  if (names.empty()) return "no devices present";
  std::sort(names.begin(), names.end());
  std::string list = "devices present: ";
  for (std::size_t i = 0; i < names.size(); ++i) list += (i ? ", " : "") + names[i];
  return list;
}

}  // namespace

Result<std::unique_ptr<Inclinometer>> openIioInclinometer(std::string_view device,
                                                          const fs::path& sysfs_root,
                                                          std::string uri) {
  if (uri.empty()) uri = "iio:" + std::string(device);
  if (device.empty() || device.find('/') != std::string_view::npos || device == "." ||
      device == "..") {
    return badInput(uri + ": expected an IIO device name such as iio:device0");
  }
  const fs::path directory = sysfs_root / std::string(device);
  std::error_code error;
  if (!fs::is_directory(directory, error)) {
    return hardwareError("no IIO device " + std::string(device) + " under " + sysfs_root.string() +
                         " (" + devicesPresent(sysfs_root) + ")");
  }

  std::optional<std::string> name;
  GLARECAM_ASSIGN(name, readAttribute(directory / "name"));
  InclinometerInfo info;
  info.uri = std::move(uri);
  info.backend = "iio";
  info.model = name.value_or("");
  const std::string described =
      std::string(device) + (info.model.empty() ? "" : " (" + info.model + ")");

  for (const auto axis : kAxes) {
    const fs::path raw = directory / ("in_accel_" + std::string(axis) + "_raw");
    if (!fs::exists(raw, error)) {
      return hardwareError(described + " is not an accelerometer: no " + raw.string());
    }
  }

  std::optional<double> frequency_hz;
  GLARECAM_ASSIGN(frequency_hz, readOptionalNumber({directory / "in_accel_sampling_frequency",
                                                    directory / "sampling_frequency"}));
  std::optional<double> scale;
  GLARECAM_ASSIGN(scale, readOptionalNumber({directory / "in_accel_scale"}));
  info.detail = described;
  if (scale) info.detail += ", scale " + formatNumber(*scale) + " m/s² per LSB";
  if (frequency_hz) info.detail += ", sampling frequency " + formatNumber(*frequency_hz) + " Hz";
  // The period of the driver's sampling frequency; a nonsensical one (0, negative) paces nothing.
  std::chrono::steady_clock::duration period{0};
  if (frequency_hz && *frequency_hz > 0)
    period = std::chrono::duration_cast<std::chrono::steady_clock::duration>(
        std::chrono::duration<double>(1.0 / *frequency_hz));
  return std::unique_ptr<Inclinometer>(
      std::make_unique<IioInclinometer>(directory, std::move(info), period));
}

}  // namespace glarecam::rig
