#include "capture/v4l2/v4l2_device.h"

#include <fcntl.h>
#include <linux/videodev2.h>
#include <poll.h>
#include <sys/ioctl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <limits>
#include <system_error>
#include <utility>

#include "core/unique_fd.h"

namespace glarecam::capture {

static_assert(kV4l2FourccGrey == V4L2_PIX_FMT_GREY);
static_assert(kV4l2FourccY10 == V4L2_PIX_FMT_Y10);
static_assert(kV4l2FourccY12 == V4L2_PIX_FMT_Y12);
static_assert(kV4l2FourccY16 == V4L2_PIX_FMT_Y16);

std::string v4l2FourccName(std::uint32_t fourcc) {
  std::string name(4, ' ');
  for (int i = 0; i < 4; ++i) {
    const auto c = static_cast<char>((fourcc >> (8 * i)) & 0xff);
    name[static_cast<std::size_t>(i)] = (c >= 0x20 && c < 0x7f) ? c : '?';
  }
  name.erase(name.find_last_not_of(' ') + 1);  // "Y10 " → "Y10"
  return name;
}

std::string_view v4l2ControlName(V4l2Control control) {
  switch (control) {
    case V4l2Control::kExposureAuto:
      return "exposure_auto";
    case V4l2Control::kExposureAbsolute:
      return "exposure_absolute";
    case V4l2Control::kAutoGain:
      return "autogain";
    case V4l2Control::kAnalogueGain:
      return "analogue_gain";
    case V4l2Control::kGain:
      return "gain";
  }
  return "unknown control";
}

namespace {

constexpr auto kCaptureType = V4L2_BUF_TYPE_VIDEO_CAPTURE;

std::uint32_t controlId(V4l2Control control) {
  switch (control) {
    case V4l2Control::kExposureAuto:
      return V4L2_CID_EXPOSURE_AUTO;
    case V4l2Control::kExposureAbsolute:
      return V4L2_CID_EXPOSURE_ABSOLUTE;
    case V4l2Control::kAutoGain:
      return V4L2_CID_AUTOGAIN;
    case V4l2Control::kAnalogueGain:
      return V4L2_CID_ANALOGUE_GAIN;
    case V4l2Control::kGain:
      return V4L2_CID_GAIN;
  }
  return 0;
}

// ioctl() retried when a signal interrupts it; returns 0 or the errno.
int xioctl(int fd, unsigned long request, void* argument) {
  int result = 0;
  do {
    result = ::ioctl(fd, request, argument);
  } while (result == -1 && errno == EINTR);
  return result == -1 ? errno : 0;
}

std::unexpected<Error> ioctlError(std::string_view what, int error) {
  if (error == ENODEV) return hardwareError(std::string(what) + ": device lost (unplugged?)");
  return hardwareError(std::string(what) + ": " + errnoText(error));
}

std::string fixedString(const __u8* text, std::size_t size) {
  const auto* begin = reinterpret_cast<const char*>(text);
  return std::string(begin, strnlen(begin, size));
}

// One mmap'd buffer, unmapped once, at destruction.
class Mapping {
 public:
  Mapping(void* address, std::size_t length) : address_(address), length_(length) {}
  ~Mapping() {
    if (address_ != MAP_FAILED) ::munmap(address_, length_);
  }
  Mapping(Mapping&& other) noexcept
      : address_(std::exchange(other.address_, MAP_FAILED)), length_(other.length_) {}
  Mapping& operator=(Mapping&&) = delete;
  Mapping(const Mapping&) = delete;
  Mapping& operator=(const Mapping&) = delete;
  std::span<const std::byte> bytes() const {
    return {static_cast<const std::byte*>(address_), length_};
  }

 private:
  void* address_;
  std::size_t length_;
};

class FdV4l2Device final : public V4l2Device {
 public:
  explicit FdV4l2Device(int fd) : fd_(fd) {}
  ~FdV4l2Device() override {
    if (streaming_) (void)streamOff();
  }

  Result<V4l2Capabilities> queryCapabilities() override;
  Result<std::vector<std::uint32_t>> enumerateFormats() override;
  Result<V4l2FrameSize> largestFrameSize(std::uint32_t fourcc) override;
  Result<V4l2Format> setFormat(const V4l2Format& requested) override;
  Result<std::optional<V4l2ControlRange>> queryControl(V4l2Control control) override;
  Status setControls(std::span<const V4l2ControlValue> values) override;
  Result<std::vector<V4l2ControlValue>> getControls(std::span<const V4l2Control> controls) override;
  Result<int> requestBuffers(int count) override;
  std::span<const std::byte> bufferData(int index) const override;
  Status queueBuffer(int index) override;
  Result<std::optional<V4l2Buffer>> dequeueBuffer() override;
  Status streamOn() override;
  Status streamOff() override;
  Result<bool> waitForFrame(std::chrono::milliseconds timeout) override;

 private:
  Result<v4l2_format> currentFormat();
  Status mapBuffer(int index);

  UniqueFd fd_;
  std::vector<Mapping> mappings_;  // declared after fd_: unmapped before the fd closes
  bool streaming_ = false;
};

Result<V4l2Capabilities> FdV4l2Device::queryCapabilities() {
  v4l2_capability caps{};
  if (const int error = xioctl(fd_.get(), VIDIOC_QUERYCAP, &caps)) {
    if (error == ENOTTY) return badInput("not a V4L2 device (VIDIOC_QUERYCAP not supported)");
    return ioctlError("VIDIOC_QUERYCAP", error);
  }
  const auto node_caps =
      (caps.capabilities & V4L2_CAP_DEVICE_CAPS) ? caps.device_caps : caps.capabilities;
  return V4l2Capabilities{
      fixedString(caps.driver, sizeof caps.driver), fixedString(caps.card, sizeof caps.card),
      fixedString(caps.bus_info, sizeof caps.bus_info), (node_caps & V4L2_CAP_VIDEO_CAPTURE) != 0,
      (node_caps & V4L2_CAP_STREAMING) != 0};
}

Result<std::vector<std::uint32_t>> FdV4l2Device::enumerateFormats() {
  std::vector<std::uint32_t> formats;
  for (__u32 index = 0;; ++index) {
    v4l2_fmtdesc description{};
    description.index = index;
    description.type = kCaptureType;
    const int error = xioctl(fd_.get(), VIDIOC_ENUM_FMT, &description);
    if (error == EINVAL) break;  // past the last format
    if (error) return ioctlError("VIDIOC_ENUM_FMT", error);
    formats.push_back(description.pixelformat);
  }
  return formats;
}

Result<v4l2_format> FdV4l2Device::currentFormat() {
  v4l2_format format{};
  format.type = kCaptureType;
  if (const int error = xioctl(fd_.get(), VIDIOC_G_FMT, &format)) {
    return ioctlError("VIDIOC_G_FMT", error);
  }
  return format;
}

Result<V4l2FrameSize> FdV4l2Device::largestFrameSize(std::uint32_t fourcc) {
  V4l2FrameSize largest;
  for (__u32 index = 0;; ++index) {
    v4l2_frmsizeenum size{};
    size.index = index;
    size.pixel_format = fourcc;
    const int error = xioctl(fd_.get(), VIDIOC_ENUM_FRAMESIZES, &size);
    if (error == EINVAL || error == ENOTTY) break;
    if (error) return ioctlError("VIDIOC_ENUM_FRAMESIZES", error);
    if (size.type != V4L2_FRMSIZE_TYPE_DISCRETE) {
      return V4l2FrameSize{static_cast<int>(size.stepwise.max_width),
                           static_cast<int>(size.stepwise.max_height)};
    }
    const auto width = static_cast<int>(size.discrete.width);
    const auto height = static_cast<int>(size.discrete.height);
    if (1LL * width * height > 1LL * largest.width * largest.height) largest = {width, height};
  }
  if (largest.width > 0) return largest;
  v4l2_format format;
  GLARECAM_ASSIGN(format, currentFormat());
  return V4l2FrameSize{static_cast<int>(format.fmt.pix.width),
                       static_cast<int>(format.fmt.pix.height)};
}

Result<V4l2Format> FdV4l2Device::setFormat(const V4l2Format& requested) {
  v4l2_format format;
  GLARECAM_ASSIGN(format, currentFormat());
  format.fmt.pix.pixelformat = requested.fourcc;
  format.fmt.pix.width = static_cast<__u32>(requested.width);
  format.fmt.pix.height = static_cast<__u32>(requested.height);
  format.fmt.pix.field = V4L2_FIELD_NONE;
  format.fmt.pix.bytesperline = 0;  // let the driver choose the stride
  if (const int error = xioctl(fd_.get(), VIDIOC_S_FMT, &format)) {
    return ioctlError("VIDIOC_S_FMT " + v4l2FourccName(requested.fourcc), error);
  }
  return V4l2Format{format.fmt.pix.pixelformat, static_cast<int>(format.fmt.pix.width),
                    static_cast<int>(format.fmt.pix.height),
                    static_cast<int>(format.fmt.pix.bytesperline), format.fmt.pix.sizeimage};
}

Result<std::optional<V4l2ControlRange>> FdV4l2Device::queryControl(V4l2Control control) {
  v4l2_query_ext_ctrl query{};
  query.id = controlId(control);
  const int error = xioctl(fd_.get(), VIDIOC_QUERY_EXT_CTRL, &query);
  if (error == EINVAL) return std::nullopt;  // the device has no such control
  if (error)
    return ioctlError("VIDIOC_QUERY_EXT_CTRL " + std::string(v4l2ControlName(control)), error);
  if (query.flags & (V4L2_CTRL_FLAG_DISABLED | V4L2_CTRL_FLAG_READ_ONLY)) return std::nullopt;
  return V4l2ControlRange{query.minimum, query.maximum,
                          std::max<std::int64_t>(1, static_cast<std::int64_t>(query.step)),
                          query.default_value};
}

Status FdV4l2Device::setControls(std::span<const V4l2ControlValue> values) {
  std::vector<v4l2_ext_control> controls(values.size());
  for (std::size_t i = 0; i < values.size(); ++i) {
    controls[i].id = controlId(values[i].control);
    controls[i].value = static_cast<__s32>(std::clamp<std::int64_t>(
        values[i].value, std::numeric_limits<__s32>::min(), std::numeric_limits<__s32>::max()));
  }
  v4l2_ext_controls request{};
  request.which = V4L2_CTRL_WHICH_CUR_VAL;  // controls of any class in one call
  request.count = static_cast<__u32>(controls.size());
  request.controls = controls.data();
  if (const int error = xioctl(fd_.get(), VIDIOC_S_EXT_CTRLS, &request)) {
    const std::string which = request.error_idx < values.size()
                                  ? std::string(v4l2ControlName(values[request.error_idx].control))
                                  : std::string("controls");
    return ioctlError("VIDIOC_S_EXT_CTRLS " + which, error);
  }
  return {};
}

Result<std::vector<V4l2ControlValue>> FdV4l2Device::getControls(
    std::span<const V4l2Control> wanted) {
  std::vector<v4l2_ext_control> controls(wanted.size());
  for (std::size_t i = 0; i < wanted.size(); ++i) controls[i].id = controlId(wanted[i]);
  v4l2_ext_controls request{};
  request.which = V4L2_CTRL_WHICH_CUR_VAL;
  request.count = static_cast<__u32>(controls.size());
  request.controls = controls.data();
  if (const int error = xioctl(fd_.get(), VIDIOC_G_EXT_CTRLS, &request)) {
    return ioctlError("VIDIOC_G_EXT_CTRLS", error);
  }
  std::vector<V4l2ControlValue> values;
  for (std::size_t i = 0; i < wanted.size(); ++i) values.push_back({wanted[i], controls[i].value});
  return values;
}

Status FdV4l2Device::mapBuffer(int index) {
  v4l2_buffer buffer{};
  buffer.type = kCaptureType;
  buffer.memory = V4L2_MEMORY_MMAP;
  buffer.index = static_cast<__u32>(index);
  if (const int error = xioctl(fd_.get(), VIDIOC_QUERYBUF, &buffer)) {
    return ioctlError("VIDIOC_QUERYBUF", error);
  }
  void* address = ::mmap(nullptr, buffer.length, PROT_READ | PROT_WRITE, MAP_SHARED, fd_.get(),
                         buffer.m.offset);
  if (address == MAP_FAILED) return hardwareError("mmap of buffer failed: " + errnoText(errno));
  mappings_.emplace_back(address, buffer.length);
  return {};
}

Result<int> FdV4l2Device::requestBuffers(int count) {
  mappings_.clear();
  v4l2_requestbuffers request{};
  request.count = static_cast<__u32>(count);
  request.type = kCaptureType;
  request.memory = V4L2_MEMORY_MMAP;
  if (const int error = xioctl(fd_.get(), VIDIOC_REQBUFS, &request)) {
    if (error == EINVAL) return hardwareError("the device does not support mmap streaming");
    return ioctlError("VIDIOC_REQBUFS", error);
  }
  for (int index = 0; index < static_cast<int>(request.count); ++index) {
    GLARECAM_CHECK(mapBuffer(index));
  }
  return static_cast<int>(request.count);
}

std::span<const std::byte> FdV4l2Device::bufferData(int index) const {
  if (index < 0 || index >= static_cast<int>(mappings_.size())) return {};
  return mappings_[static_cast<std::size_t>(index)].bytes();
}

Status FdV4l2Device::queueBuffer(int index) {
  v4l2_buffer buffer{};
  buffer.type = kCaptureType;
  buffer.memory = V4L2_MEMORY_MMAP;
  buffer.index = static_cast<__u32>(index);
  if (const int error = xioctl(fd_.get(), VIDIOC_QBUF, &buffer)) {
    return ioctlError("VIDIOC_QBUF", error);
  }
  return {};
}

Result<std::optional<V4l2Buffer>> FdV4l2Device::dequeueBuffer() {
  v4l2_buffer buffer{};
  buffer.type = kCaptureType;
  buffer.memory = V4L2_MEMORY_MMAP;
  const int error = xioctl(fd_.get(), VIDIOC_DQBUF, &buffer);
  if (error == EAGAIN) return std::nullopt;
  if (error) return ioctlError("VIDIOC_DQBUF", error);
  const auto timestamp_ns = static_cast<std::uint64_t>(buffer.timestamp.tv_sec) * 1'000'000'000u +
                            static_cast<std::uint64_t>(buffer.timestamp.tv_usec) * 1'000u;
  return V4l2Buffer{static_cast<int>(buffer.index), buffer.sequence, timestamp_ns, buffer.bytesused,
                    (buffer.flags & V4L2_BUF_FLAG_ERROR) != 0};
}

Status FdV4l2Device::streamOn() {
  int type = kCaptureType;
  if (const int error = xioctl(fd_.get(), VIDIOC_STREAMON, &type)) {
    return ioctlError("VIDIOC_STREAMON", error);
  }
  streaming_ = true;
  return {};
}

Status FdV4l2Device::streamOff() {
  int type = kCaptureType;
  streaming_ = false;
  if (const int error = xioctl(fd_.get(), VIDIOC_STREAMOFF, &type)) {
    return ioctlError("VIDIOC_STREAMOFF", error);
  }
  return {};
}

Result<bool> FdV4l2Device::waitForFrame(std::chrono::milliseconds timeout) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  for (;;) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
        deadline - std::chrono::steady_clock::now());
    pollfd descriptor{fd_.get(), POLLIN, 0};
    const int ready =
        ::poll(&descriptor, 1, static_cast<int>(std::max<long long>(0, left.count())));
    if (ready == -1 && errno == EINTR) continue;
    if (ready == -1) return hardwareError("poll: " + errnoText(errno));
    if (ready == 0) return false;
    if (descriptor.revents & POLLIN) return true;
    return hardwareError("poll: stream error (device lost or not streaming)");
  }
}

}  // namespace

Result<std::unique_ptr<V4l2Device>> openV4l2Device(const std::string& path) {
  struct stat status {};
  if (::stat(path.c_str(), &status) == 0 && !S_ISCHR(status.st_mode)) {
    return badInput("not a V4L2 device (not a character device)");
  }
  const int fd = ::open(path.c_str(), O_RDWR | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) {
    const int error = errno;
    if (error == ENOENT || error == ENXIO || error == ENODEV)
      return hardwareError("no such device");
    if (error == EACCES || error == EPERM) {
      return ioError(
          "permission denied (add the user to the 'video' group: sudo usermod -aG video $USER, "
          "then log in again)");
    }
    return hardwareError("cannot open: " + errnoText(error));
  }
  auto device = std::make_unique<FdV4l2Device>(fd);
  GLARECAM_CHECK(device->queryCapabilities());  // "not a V4L2 device" for other char devices
  return device;
}

}  // namespace glarecam::capture
