// RigIo over the Linux GPIO character device through libgpiod 1.6 (its v1 C API): the only file
// that includes <gpiod.h>. The chip and each requested line are held in move-only wrappers that
// free them once; the lines are released before the chip is closed.
#include <gpiod.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cstring>
#include <filesystem>
#include <mutex>
#include <thread>
#include <utility>
#include <vector>

#include "rig/gpio/gpio_errors.h"
#include "rig/gpio/rig_io.h"

namespace glarecam::rig {
namespace {

constexpr const char* kConsumer = "glarecam";
constexpr int kInactive = 0;
constexpr int kActive = 1;

struct ChipCloser {
  void operator()(gpiod_chip* chip) const { gpiod_chip_close(chip); }
};
using ChipHandle = std::unique_ptr<gpiod_chip, ChipCloser>;

// A line requested from the kernel, released once on destruction. Its chip must outlive it.
class RequestedLine {
 public:
  RequestedLine() = default;
  explicit RequestedLine(gpiod_line* line) : line_(line) {}
  RequestedLine(RequestedLine&& other) noexcept : line_(std::exchange(other.line_, nullptr)) {}
  RequestedLine& operator=(RequestedLine&& other) noexcept {
    if (this != &other) {
      reset();
      line_ = std::exchange(other.line_, nullptr);
    }
    return *this;
  }
  RequestedLine(const RequestedLine&) = delete;
  RequestedLine& operator=(const RequestedLine&) = delete;
  ~RequestedLine() { reset(); }

  gpiod_line* get() const { return line_; }
  explicit operator bool() const { return line_ != nullptr; }

 private:
  void reset() {
    if (line_) gpiod_line_release(std::exchange(line_, nullptr));
  }
  gpiod_line* line_ = nullptr;
};

bool allDigits(const std::string& text) {
  return !text.empty() &&
         std::all_of(text.begin(), text.end(), [](char c) { return c >= '0' && c <= '9'; });
}

// The chips there are, with their labels where they can be opened: "gpiochip0 [pinctrl-bcm2711]".
std::vector<std::string> presentChipsWithLabels() {
  std::vector<std::string> chips = presentGpioChips();
  for (std::string& name : chips) {
    if (ChipHandle chip{gpiod_chip_open_by_name(name.c_str())}) {
      name += std::string(" [") + gpiod_chip_label(chip.get()) + "]";
    }
  }
  return chips;
}

// Opens the chip by path (contains '/'), by name (/dev/<name> exists), by number or by label, so
// that errno says what went wrong: gpiod_chip_open_lookup() tries each in turn and ends with the
// label lookup's ENOENT, also for a path that exists but is no chip.
Result<ChipHandle> openChip(const std::string& chip) {
  errno = 0;
  gpiod_chip* handle = nullptr;
  if (chip.find('/') != std::string::npos) {
    handle = gpiod_chip_open(chip.c_str());
  } else if (std::error_code ec; std::filesystem::exists("/dev/" + chip, ec)) {
    handle = gpiod_chip_open_by_name(chip.c_str());
  } else if (allDigits(chip)) {
    unsigned number = 0;
    const auto [end, parsed] = std::from_chars(chip.data(), chip.data() + chip.size(), number);
    errno = ENOENT;
    if (parsed == std::errc()) handle = gpiod_chip_open_by_number(number);
  } else {
    handle = gpiod_chip_open_by_label(chip.c_str());
  }
  if (!handle) {
    const int error_number = errno != 0 ? errno : ENOENT;
    return std::unexpected(gpioChipOpenError(chip, error_number, presentChipsWithLabels()));
  }
  return ChipHandle(handle);
}

class GpiodRigIo final : public RigIo {
 public:
  GpiodRigIo(ChipHandle chip, std::string chip_name, std::chrono::microseconds trigger_pulse)
      : chip_(std::move(chip)), chip_name_(std::move(chip_name)), trigger_pulse_(trigger_pulse) {}

  ~GpiodRigIo() override {
    // Outputs inactive before release: the kernel leaves a released line as it was.
    for (const Slot* output : {&led_, &trigger_}) {
      if (output->line) gpiod_line_set_value(output->line.get(), kInactive);
    }
  }

  // A requested line and its name in messages: "line 22 'STATUS_LED' (LED)".
  struct Slot {
    RequestedLine line;
    std::string label;
  };
  enum class Role { kTrigger, kLed, kButton };

  // Finds and requests one configured line.
  Status request(const GpioLine& config, Role role, bool pull_up) {
    const std::string_view role_name = roleName(role);
    gpiod_line* line = nullptr;
    GLARECAM_ASSIGN(line, find(config, role_name));
    const unsigned offset = gpiod_line_offset(line);
    const auto* name = std::get_if<std::string>(&config.line);
    const std::string numbered = std::to_string(offset) + (name ? " '" + *name + "'" : "");
    std::string label = "line " + numbered + " (" + std::string(role_name) + ")";
    for (const Slot* other : {&trigger_, &led_, &button_}) {
      if (other->line && gpiod_line_offset(other->line.get()) == offset) {
        return badInput(label + " of " + chip_name_ + " is also configured as " + other->label);
      }
    }

    const bool output = role != Role::kButton;
    gpiod_line_request_config request{};
    request.consumer = kConsumer;
    request.request_type =
        output ? GPIOD_LINE_REQUEST_DIRECTION_OUTPUT : GPIOD_LINE_REQUEST_DIRECTION_INPUT;
    request.flags = (config.active_low ? GPIOD_LINE_REQUEST_FLAG_ACTIVE_LOW : 0) |
                    (pull_up ? GPIOD_LINE_REQUEST_FLAG_BIAS_PULL_UP : 0);
    if (gpiod_line_request(line, &request, kInactive) != 0) {
      const int error_number = errno;
      gpiod_line_update(line);  // the consumer as it is now
      const char* consumer = gpiod_line_consumer(line);
      return std::unexpected(
          gpioLineRequestError(chip_name_, label, error_number, consumer ? consumer : "", pull_up));
    }
    Slot& slot = role == Role::kTrigger ? trigger_ : role == Role::kLed ? led_ : button_;
    slot = Slot{RequestedLine(line), std::move(label)};

    std::string entry = std::string(role_name) + " line " + numbered;
    if (config.active_low && pull_up) {
      entry += " (active-low, pull-up)";
    } else if (config.active_low || pull_up) {
      entry += config.active_low ? " (active-low)" : " (pull-up)";
    }
    description_parts_.push_back(std::move(entry));
    return {};
  }

  void finishDescription() {
    description_ = chip_name_ + " [" + gpiod_chip_label(chip_.get()) + "]: ";
    if (description_parts_.empty()) description_ += "no lines";
    for (std::size_t i = 0; i < description_parts_.size(); ++i) {
      description_ += (i ? ", " : "") + description_parts_[i];
    }
  }

  const std::string& description() const override { return description_; }
  bool hasTrigger() const override { return static_cast<bool>(trigger_.line); }
  bool hasLed() const override { return static_cast<bool>(led_.line); }
  bool hasButton() const override { return static_cast<bool>(button_.line); }

  Status setLed(bool on) override {
    if (!led_.line) return {};
    std::lock_guard lock(mutex_);
    return set(led_, on ? kActive : kInactive);
  }

  Status pulseTrigger() override {
    if (!trigger_.line) return {};
    std::lock_guard lock(mutex_);
    const Status asserted = set(trigger_, kActive);
    if (asserted) std::this_thread::sleep_for(trigger_pulse_);
    const Status released = set(trigger_, kInactive);  // also after a failed assert
    return asserted ? released : asserted;
  }

  Result<bool> buttonPressed() override {
    if (!button_.line) return false;
    std::lock_guard lock(mutex_);
    const int value = gpiod_line_get_value(button_.line.get());
    if (value < 0) {
      return hardwareError(button_.label + " of " + chip_name_ +
                           ": cannot read: " + std::strerror(errno));
    }
    return value == kActive;
  }

 private:
  Result<gpiod_line*> find(const GpioLine& config, std::string_view role) {
    if (const auto* offset = std::get_if<unsigned>(&config.line)) {
      const unsigned count = gpiod_chip_num_lines(chip_.get());
      if (*offset >= count) {
        return hardwareError("line " + std::to_string(*offset) + " (" + std::string(role) +
                             ") is beyond " + chip_name_ + "'s " + std::to_string(count) +
                             " lines (0.." + std::to_string(count == 0 ? 0 : count - 1) + ")");
      }
      gpiod_line* line = gpiod_chip_get_line(chip_.get(), *offset);
      if (!line) {
        return hardwareError("line " + std::to_string(*offset) + " (" + std::string(role) +
                             ") of " + chip_name_ + ": " + std::strerror(errno));
      }
      return line;
    }
    const std::string& name = std::get<std::string>(config.line);
    errno = 0;
    gpiod_line* line = gpiod_chip_find_line(chip_.get(), name.c_str());
    if (!line) {
      const std::string what = "line '" + name + "' (" + std::string(role) + ")";
      if (errno == ENOENT || errno == 0) {
        return hardwareError(what + " not found on " + chip_name_ + " (`gpioinfo " + chip_name_ +
                             "` lists the line names)");
      }
      return hardwareError(what + " of " + chip_name_ + ": " + std::strerror(errno));
    }
    return line;
  }

  static std::string_view roleName(Role role) {
    switch (role) {
      case Role::kTrigger:
        return "trigger";
      case Role::kLed:
        return "LED";
      case Role::kButton:
        return "button";
    }
    return "line";
  }

  Status set(const Slot& slot, int value) {
    if (gpiod_line_set_value(slot.line.get(), value) != 0) {
      return hardwareError(slot.label + " of " + chip_name_ + ": cannot set to " +
                           (value == kActive ? "active" : "inactive") + ": " +
                           std::strerror(errno));
    }
    return {};
  }

  // Declared before the lines: destroyed after them.
  ChipHandle chip_;
  std::string chip_name_;
  std::chrono::microseconds trigger_pulse_;
  std::string description_;
  std::vector<std::string> description_parts_;
  std::mutex mutex_;  // one line operation at a time (the LED has its own thread)
  Slot trigger_;
  Slot led_;
  Slot button_;
};

}  // namespace

Result<std::unique_ptr<RigIo>> openGpiodRigIo(const RigIoConfig& config) {
  GLARECAM_CHECK(config.validate());
  ChipHandle chip;
  GLARECAM_ASSIGN(chip, openChip(config.chip));
  const std::string chip_name = gpiod_chip_name(chip.get());
  auto io = std::make_unique<GpiodRigIo>(std::move(chip), chip_name, config.trigger_pulse);
  using Role = GpiodRigIo::Role;
  if (config.trigger) GLARECAM_CHECK(io->request(*config.trigger, Role::kTrigger, false));
  if (config.led) GLARECAM_CHECK(io->request(*config.led, Role::kLed, false));
  if (config.button) {
    GLARECAM_CHECK(io->request(*config.button, Role::kButton, config.button_pull_up));
  }
  io->finishDescription();
  return io;
}

}  // namespace glarecam::rig
