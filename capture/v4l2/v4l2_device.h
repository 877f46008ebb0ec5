// The seam between the V4L2 camera backend and the kernel: one video node, reduced to the few
// operations the backend needs (capabilities, mono formats, controls, mmap'd buffers, streaming,
// waiting for a frame), in our own small structs so that this header does not include
// <linux/videodev2.h>. openV4l2Device() is the real thing over a file descriptor; tests implement
// V4l2Device to simulate a sensor. Error messages do not name the device: the caller prefixes the
// camera's URI.
#pragma once

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "core/error.h"

namespace glarecam::capture {

// V4L2 pixel format codes (fourcc), as defined by v4l2_fourcc() in <linux/videodev2.h>.
constexpr std::uint32_t v4l2Fourcc(char a, char b, char c, char d) {
  return static_cast<std::uint32_t>(static_cast<unsigned char>(a)) |
         static_cast<std::uint32_t>(static_cast<unsigned char>(b)) << 8 |
         static_cast<std::uint32_t>(static_cast<unsigned char>(c)) << 16 |
         static_cast<std::uint32_t>(static_cast<unsigned char>(d)) << 24;
}
inline constexpr std::uint32_t kV4l2FourccGrey = v4l2Fourcc('G', 'R', 'E', 'Y');  // 8-bit mono
inline constexpr std::uint32_t kV4l2FourccY10 = v4l2Fourcc('Y', '1', '0', ' ');   // 10 in 16 LE
inline constexpr std::uint32_t kV4l2FourccY12 = v4l2Fourcc('Y', '1', '2', ' ');   // 12 in 16 LE
inline constexpr std::uint32_t kV4l2FourccY16 = v4l2Fourcc('Y', '1', '6', ' ');   // 16 LE

// "GREY", "Y10", "YUYV" (trailing spaces dropped): for messages.
std::string v4l2FourccName(std::uint32_t fourcc);

struct V4l2Capabilities {
  std::string driver;
  std::string card;
  std::string bus_info;
  bool video_capture = false;  // V4L2_CAP_VIDEO_CAPTURE (single-planar) on this node
  bool streaming = false;      // V4L2_CAP_STREAMING
};

struct V4l2FrameSize {
  int width = 0;
  int height = 0;
};

struct V4l2Format {
  std::uint32_t fourcc = 0;
  int width = 0;
  int height = 0;
  int bytes_per_line = 0;
  std::size_t image_bytes = 0;
};

// The controls the backend uses; the device maps them to V4L2_CID_* ids.
enum class V4l2Control {
  kExposureAuto,      // V4L2_CID_EXPOSURE_AUTO (menu)
  kExposureAbsolute,  // V4L2_CID_EXPOSURE_ABSOLUTE (100 µs units)
  kAutoGain,          // V4L2_CID_AUTOGAIN (boolean)
  kAnalogueGain,      // V4L2_CID_ANALOGUE_GAIN (driver units)
  kGain,              // V4L2_CID_GAIN (driver units)
};

// "exposure_absolute", "analogue_gain": for messages.
std::string_view v4l2ControlName(V4l2Control control);

struct V4l2ControlRange {
  std::int64_t min = 0;
  std::int64_t max = 0;
  std::int64_t step = 1;
  std::int64_t default_value = 0;
};

struct V4l2ControlValue {
  V4l2Control control = V4l2Control::kExposureAbsolute;
  std::int64_t value = 0;
};

// A dequeued buffer: which mmap'd buffer holds the frame, and the driver's metadata.
struct V4l2Buffer {
  int index = 0;
  std::uint32_t sequence = 0;      // frame counter of the stream (may skip when frames drop)
  std::uint64_t timestamp_ns = 0;  // as the driver stamped it (usually CLOCK_MONOTONIC)
  std::size_t bytes_used = 0;
  bool error = false;  // V4L2_BUF_FLAG_ERROR: the data may be corrupt
};

class V4l2Device {
 public:
  virtual ~V4l2Device() = default;
  V4l2Device(const V4l2Device&) = delete;
  V4l2Device& operator=(const V4l2Device&) = delete;

  virtual Result<V4l2Capabilities> queryCapabilities() = 0;
  // Pixel formats of the capture queue, in the driver's order.
  virtual Result<std::vector<std::uint32_t>> enumerateFormats() = 0;
  // The largest frame size for a format (the current size when the driver enumerates none).
  virtual Result<V4l2FrameSize> largestFrameSize(std::uint32_t fourcc) = 0;
  // VIDIOC_S_FMT; returns what the driver applied (it may change size and stride).
  virtual Result<V4l2Format> setFormat(const V4l2Format& requested) = 0;

  // The control's range; nullopt when the device has no such control (or it is disabled).
  virtual Result<std::optional<V4l2ControlRange>> queryControl(V4l2Control control) = 0;
  // All values in one VIDIOC_S_EXT_CTRLS, in order (atomically where the driver can).
  virtual Status setControls(std::span<const V4l2ControlValue> values) = 0;
  // The current values (VIDIOC_G_EXT_CTRLS), in the order asked.
  virtual Result<std::vector<V4l2ControlValue>> getControls(
      std::span<const V4l2Control> controls) = 0;

  // Allocates and maps `count` buffers (the driver may grant more or fewer); 0 releases them.
  virtual Result<int> requestBuffers(int count) = 0;
  // The mapped bytes of a buffer (valid until requestBuffers() is called again).
  virtual std::span<const std::byte> bufferData(int index) const = 0;
  virtual Status queueBuffer(int index) = 0;
  // A filled buffer, or nullopt when none is ready now (never blocks).
  virtual Result<std::optional<V4l2Buffer>> dequeueBuffer() = 0;
  virtual Status streamOn() = 0;
  virtual Status streamOff() = 0;  // also returns every buffer to the application
  // Waits until a filled buffer is ready; false when `timeout` passed first.
  virtual Result<bool> waitForFrame(std::chrono::milliseconds timeout) = 0;

 protected:
  V4l2Device() = default;
};

// Opens a device node; errors say "no such device", "permission denied ...", "not a V4L2 device".
using V4l2DeviceOpener = std::function<Result<std::unique_ptr<V4l2Device>>(const std::string&)>;

// The real opener: open(O_RDWR | O_NONBLOCK | O_CLOEXEC) on a character device.
Result<std::unique_ptr<V4l2Device>> openV4l2Device(const std::string& path);

}  // namespace glarecam::capture
