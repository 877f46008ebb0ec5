#include "rig/gpio/gpio_errors.h"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <system_error>

namespace glarecam::rig {
namespace {

constexpr std::string_view kChipPrefix = "gpiochip";
constexpr std::string_view kPermissionHint =
    "add the user to the gpio group or install a udev rule giving it /dev/gpiochip* "
    "(docs/rig-gpio.md)";

std::string presentList(const std::vector<std::string>& present) {
  std::string text = "/dev/gpiochip* present: ";
  if (present.empty()) return text + "none";
  for (std::size_t i = 0; i < present.size(); ++i) text += (i ? ", " : "") + present[i];
  return text;
}

std::string errnoText(int error_number) { return std::strerror(error_number); }

}  // namespace

std::vector<std::string> presentGpioChips(const std::filesystem::path& dev_directory) {
  std::vector<std::string> chips;
  std::error_code ec;
  for (std::filesystem::directory_iterator it(dev_directory, ec), end; !ec && it != end;
       it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name.starts_with(kChipPrefix)) chips.push_back(name);
  }
  std::sort(chips.begin(), chips.end());
  return chips;
}

Error gpioChipOpenError(const std::string& chip, int error_number,
                        const std::vector<std::string>& present) {
  const std::string what = "GPIO chip " + chip;
  switch (error_number) {
    case ENOENT:
      return {ErrorCode::kHardware, what + " not found (" + presentList(present) + ")"};
    case EACCES:
    case EPERM:
      return {ErrorCode::kHardware, what + ": permission denied: " + std::string(kPermissionHint)};
    case ENOTTY:
    case ENODEV:
    case ENXIO:
    case EISDIR:
    case EINVAL:
      return {ErrorCode::kHardware, chip + " is not a GPIO chip (" + presentList(present) + ")"};
    default:
      return {ErrorCode::kHardware, what + ": " + errnoText(error_number)};
  }
}

Error gpioLineRequestError(const std::string& chip, const std::string& line, int error_number,
                           const std::string& consumer, bool pull_up) {
  const std::string what = line + " of " + chip;
  switch (error_number) {
    case EBUSY:
      return {
          ErrorCode::kHardware,
          what + " is used by " +
              (consumer.empty() ? std::string("another program or a kernel driver") : consumer)};
    case EACCES:
    case EPERM:
      return {ErrorCode::kHardware, what + ": permission denied: " + std::string(kPermissionHint)};
    case EINVAL:
    case EOPNOTSUPP:
      if (pull_up) {
        return {ErrorCode::kHardware,
                what + ": the kernel refused the pull-up (" + errnoText(error_number) +
                    "); kernels before 5.5 cannot bias lines: set button_pull_up = false and "
                    "fit an external pull-up"};
      }
      return {ErrorCode::kHardware, what + ": " + errnoText(error_number)};
    default:
      return {ErrorCode::kHardware, what + ": " + errnoText(error_number)};
  }
}

}  // namespace glarecam::rig
