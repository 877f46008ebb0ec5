// The libgpiod backend's failure messages, apart from the backend so that they are tested on
// machines without GPIO chips (and without libgpiod). Each names the chip and, for a line, its
// role and offset, says what went wrong in words and, where the operator can fix it, how.
// All are kHardware errors.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "core/error.h"

namespace glarecam::rig {

// The GPIO chips' names in `dev_directory` ("gpiochip0", ...), sorted.
std::vector<std::string> presentGpioChips(const std::filesystem::path& dev_directory = "/dev");

// Opening `chip` (as configured) failed with errno `error_number`; `present` lists the chips there
// are: "GPIO chip gpiochip0 not found (/dev/gpiochip* present: none)".
Error gpioChipOpenError(const std::string& chip, int error_number,
                        const std::vector<std::string>& present);

// Requesting a line failed with errno `error_number`. `line` names it for the operator ("line 17
// (LED)"); `consumer` is the line's present user as the kernel reports it (may be empty):
// "line 17 (LED) of gpiochip0 is used by gpio-leds". `pull_up` says whether a bias was asked for,
// which kernels before 5.5 refuse.
Error gpioLineRequestError(const std::string& chip, const std::string& line, int error_number,
                           const std::string& consumer, bool pull_up = false);

}  // namespace glarecam::rig
