// The real I2cBus: a Linux i2c-dev character device, one I2C_RDWR ioctl per transaction.
#include <fcntl.h>
#include <linux/i2c-dev.h>
#include <linux/i2c.h>
#include <sys/ioctl.h>

#include <array>
#include <cerrno>
#include <cstdio>
#include <limits>
#include <system_error>

#include "core/unique_fd.h"
#include "rig/inclinometer/i2c_bus.h"

namespace glarecam::rig {
namespace {

// The largest 7-bit address (the I2C specification's address space).
constexpr std::uint8_t kMaxSevenBitAddress = 0x7f;

class I2cDevBus final : public I2cBus {
 public:
  I2cDevBus(std::string path, UniqueFd fd) : path_(std::move(path)), fd_(std::move(fd)) {}

  const std::string& name() const override { return path_; }

  Status transfer(std::uint8_t address, std::span<const std::uint8_t> write,
                  std::span<std::uint8_t> read) override {
    const std::string where = i2cHex(address) + " on " + path_;
    if (address > kMaxSevenBitAddress) {
      return badInput("I2C address " + i2cHex(address) + " on " + path_ +
                      " is not a 7-bit address");
    }
    // i2c_msg::len is 16 bits.
    constexpr std::size_t kMaxMessageBytes = std::numeric_limits<__u16>::max();
    if (write.size() > kMaxMessageBytes || read.size() > kMaxMessageBytes) {
      return badInput("I2C transfer to " + where + " is too long");
    }
    std::array<i2c_msg, 2> messages{};
    __u32 count = 0;
    if (!write.empty() || read.empty()) {
      // A zero-length write with no read is a plain address probe; the kernel takes it.
      messages[count++] = i2c_msg{address, 0, static_cast<__u16>(write.size()),
                                  const_cast<__u8*>(write.data())};  // the kernel only reads it
    }
    if (!read.empty()) {
      messages[count++] = i2c_msg{address, I2C_M_RD, static_cast<__u16>(read.size()), read.data()};
    }
    i2c_rdwr_ioctl_data data{messages.data(), count};
    int result = 0;
    do {
      result = ::ioctl(fd_.get(), I2C_RDWR, &data);
    } while (result < 0 && errno == EINTR);
    if (result >= 0) return {};

    const int error = errno;
    if (error == ENXIO || error == EREMOTEIO) {
      // i2c-dev reports a NACK of the address as ENXIO (most adapters) or EREMOTEIO.
      return hardwareError("no device answers at " + where + " (" + errnoText(error) + ")");
    }
    if (error == ENOTTY) {
      // Not an i2c-dev node at all: a regular file, /dev/null, another character device.
      return hardwareError(path_ + " is not an I2C bus (I2C_RDWR to " + i2cHex(address) + ": " +
                           errnoText(error) + ")");
    }
    if (error == ENODEV)
      return hardwareError(path_ + ": I2C adapter gone (" + errnoText(error) + ")");
    return hardwareError("I2C transfer to " + where + " failed: " + errnoText(error));
  }

 private:
  std::string path_;
  UniqueFd fd_;
};

}  // namespace

Result<std::unique_ptr<I2cBus>> openI2cDevBus(const std::string& path) {
  UniqueFd fd(::open(path.c_str(), O_RDWR | O_CLOEXEC));
  if (!fd.valid()) {
    const int error = errno;
    if (error == ENOENT || error == ENODEV || error == ENXIO) {
      return hardwareError(path +
                           ": no such I2C bus (enable I2C, e.g. dtparam=i2c_arm=on on a "
                           "Raspberry Pi, and load i2c-dev)");
    }
    if (error == EACCES || error == EPERM) {
      return hardwareError(path +
                           ": permission denied (add the user to the 'i2c' group: sudo "
                           "usermod -aG i2c $USER, then log in again, or add a udev rule "
                           "giving the group access to i2c-dev nodes)");
    }
    return hardwareError(path + ": cannot open I2C bus: " + errnoText(error));
  }
  return std::make_unique<I2cDevBus>(path, std::move(fd));
}

}  // namespace glarecam::rig
