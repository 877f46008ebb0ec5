// A file descriptor owned by exactly one object and closed once, at destruction, or earlier by
// close() where a failing close must be seen (a write's last error can surface there: NFS, a full
// disk). The one RAII wrapper of a descriptor: atomic files, stack reads, V4L2 devices, I2C buses,
// sysfs attributes. Move-only.
#pragma once

#include <unistd.h>

#include <utility>

namespace glarecam {

class UniqueFd {
 public:
  UniqueFd() = default;
  explicit UniqueFd(int fd) : fd_(fd) {}
  ~UniqueFd() {
    if (fd_ >= 0) ::close(fd_);
  }
  UniqueFd(UniqueFd&& other) noexcept : fd_(std::exchange(other.fd_, -1)) {}
  UniqueFd& operator=(UniqueFd&& other) noexcept {
    if (this != &other) {
      if (fd_ >= 0) ::close(fd_);
      fd_ = std::exchange(other.fd_, -1);
    }
    return *this;
  }
  UniqueFd(const UniqueFd&) = delete;
  UniqueFd& operator=(const UniqueFd&) = delete;

  int get() const { return fd_; }
  bool valid() const { return fd_ >= 0; }
  // Closes now; close(2)'s result (0, or -1 with errno set). Closing twice is a no-op.
  int close() { return fd_ >= 0 ? ::close(std::exchange(fd_, -1)) : 0; }

 private:
  int fd_ = -1;
};

}  // namespace glarecam
