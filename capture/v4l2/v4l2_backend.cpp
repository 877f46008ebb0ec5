#include "capture/v4l2/v4l2_backend.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <optional>
#include <utility>

namespace glarecam::capture {
namespace {

constexpr std::string_view kV4l2Scheme = "v4l2";

// The mono formats we read, deepest first. Y10 and Y12 are 16-bit little-endian containers.
struct MonoFormat {
  std::uint32_t fourcc;
  std::string_view genicam_name;
  int bytes_per_pixel;
};
constexpr std::array<MonoFormat, 4> kMonoFormats{{
    {kV4l2FourccY16, "Mono16", 2},
    {kV4l2FourccY12, "Mono12", 2},
    {kV4l2FourccY10, "Mono10", 2},
    {kV4l2FourccGrey, "Mono8", 1},
}};

std::string fourccList(std::span<const std::uint32_t> fourccs) {
  std::string names;
  for (const auto fourcc : fourccs) names += (names.empty() ? "" : ", ") + v4l2FourccName(fourcc);
  return names.empty() ? "none" : names;
}

Result<MonoFormat> chooseFormat(std::span<const std::uint32_t> offered,
                                const std::optional<std::string>& wanted) {
  const auto isOffered = [&](const MonoFormat& f) {
    return std::ranges::find(offered, f.fourcc) != offered.end();
  };
  if (wanted) {
    const auto found = std::ranges::find(kMonoFormats, *wanted, &MonoFormat::genicam_name);
    if (found == kMonoFormats.end()) {
      return badInput(
          fmt::format("pixel format '{}' is not one of Mono8, Mono10, Mono12, Mono16", *wanted));
    }
    if (!isOffered(*found)) {
      return badInput(fmt::format("pixel format {} ({}) not offered; the device offers: {}",
                                  *wanted, v4l2FourccName(found->fourcc), fourccList(offered)));
    }
    return *found;
  }
  const auto found = std::ranges::find_if(kMonoFormats, isOffered);
  if (found == kMonoFormats.end()) {
    return hardwareError(
        fmt::format("no supported mono format (GREY, Y10, Y12, Y16); the device offers: {}",
                    fourccList(offered)));
  }
  return *found;
}

// The bytes one frame must hold to be complete.
std::size_t frameBytes(const V4l2Format& format, const MonoFormat& mono) {
  if (format.height <= 0) return 0;
  return static_cast<std::size_t>(format.bytes_per_line) * (format.height - 1) +
         static_cast<std::size_t>(format.width) * mono.bytes_per_pixel;
}

void copyFrame(std::span<const std::byte> data, const V4l2Format& format, const MonoFormat& mono,
               RawFrame& frame) {
  for (int y = 0; y < format.height; ++y) {
    const auto* line = data.data() + static_cast<std::size_t>(y) * format.bytes_per_line;
    auto out = frame.row(y);
    for (std::size_t x = 0; x < out.size(); ++x) {
      const auto lo = std::to_integer<std::uint16_t>(line[x * mono.bytes_per_pixel]);
      out[x] = mono.bytes_per_pixel == 1
                   ? lo
                   : static_cast<std::uint16_t>(lo | std::to_integer<std::uint16_t>(line[x * 2 + 1])
                                                         << 8);
    }
  }
}

std::chrono::milliseconds frameTimeout(double frame_timeout_s, double exposure_us) {
  return std::chrono::milliseconds(
      static_cast<std::int64_t>(std::ceil(frame_timeout_s * 1e3 + exposure_us * 1e-3)));
}

// The buffers of one capture() call, streaming: stopped and released at destruction.
class StreamSession {
 public:
  explicit StreamSession(V4l2Device& device) : device_(device) {}
  ~StreamSession() {
    if (streaming_) (void)device_.streamOff();
    if (buffers_ > 0) (void)device_.requestBuffers(0);
  }
  StreamSession(const StreamSession&) = delete;
  StreamSession& operator=(const StreamSession&) = delete;

  Status start(int buffer_count) {
    GLARECAM_ASSIGN(buffers_, device_.requestBuffers(buffer_count));
    if (buffers_ < 1) return hardwareError("the driver granted no buffers");
    for (int index = 0; index < buffers_; ++index) GLARECAM_CHECK(device_.queueBuffer(index));
    GLARECAM_CHECK(device_.streamOn());
    streaming_ = true;
    return {};
  }
  int buffers() const { return buffers_; }

 private:
  V4l2Device& device_;
  int buffers_ = 0;
  bool streaming_ = false;
};

struct V4l2Setup {
  V4l2Format format;
  MonoFormat mono;
  V4l2ControlSet controls;
};

class V4l2Camera final : public Camera {
 public:
  V4l2Camera(CameraInfo info, std::unique_ptr<V4l2Device> device, V4l2Setup setup,
             CameraOptions options, V4l2Options v4l2_options)
      : info_(std::move(info)),
        device_(std::move(device)),
        setup_(setup),
        options_(std::move(options)),
        v4l2_options_(std::move(v4l2_options)) {}

  const CameraInfo& info() const override { return info_; }
  CameraLimits limits() const override { return limitsOf(setup_.controls); }
  SensorFormat format() const override {
    return {std::string(setup_.mono.genicam_name), setup_.format.width, setup_.format.height,
            8 * setup_.mono.bytes_per_pixel};
  }

 private:
  Result<std::vector<CapturedFrame>> doCapture(std::span<const ExposureRequest> requests) override {
    return captureAll(requests);
  }
  Result<std::vector<CapturedFrame>> captureAll(std::span<const ExposureRequest> requests);
  Result<CapturedFrame> captureOne(std::size_t index, const ExposureRequest& request);
  Result<int> drainReadyFrames();
  Result<AppliedControls> writeControls(const ExposureRequest& request);
  Result<V4l2Buffer> nextBuffer(std::chrono::milliseconds timeout, std::string_view what);
  Status requeue(const V4l2Buffer& buffer) { return device_->queueBuffer(buffer.index); }
  // Stale frames one step may see: the settle frames, the queued buffers and the retries.
  int maxStaleFrames() const {
    return v4l2_options_.settle_frames + buffer_count_ + options_.max_frame_retries;
  }
  bool complete(const V4l2Buffer& buffer) const {
    return !buffer.error && buffer.bytes_used >= frameBytes(setup_.format, setup_.mono) &&
           device_->bufferData(buffer.index).size() >= frameBytes(setup_.format, setup_.mono);
  }

  CameraInfo info_;
  std::unique_ptr<V4l2Device> device_;
  V4l2Setup setup_;
  CameraOptions options_;
  V4l2Options v4l2_options_;
  int buffer_count_ = 0;                        // of the current session
  std::optional<std::uint32_t> last_sequence_;  // of the last frame dequeued in this session
  double exposure_in_flight_us_ = 0;            // the longest exposure frames may still carry
};

Result<std::vector<CapturedFrame>> V4l2Camera::captureAll(
    std::span<const ExposureRequest> requests) {
  std::vector<CapturedFrame> frames;
  StreamSession session(*device_);
  GLARECAM_CHECK(session.start(v4l2_options_.buffer_count));
  buffer_count_ = session.buffers();
  last_sequence_.reset();
  exposure_in_flight_us_ = 0;
  for (std::size_t i = 0; i < requests.size(); ++i) {
    CapturedFrame frame;
    GLARECAM_ASSIGN(frame, captureOne(i, requests[i]));
    frames.push_back(std::move(frame));
  }
  return frames;
}

// Returns the frames that completed before the controls are written (they carry old controls).
Result<int> V4l2Camera::drainReadyFrames() {
  int drained = 0;
  for (int i = 0; i < buffer_count_; ++i) {
    std::optional<V4l2Buffer> buffer;
    GLARECAM_ASSIGN(buffer, device_->dequeueBuffer());
    if (!buffer) break;
    last_sequence_ = buffer->sequence;
    GLARECAM_CHECK(requeue(*buffer));
    ++drained;
  }
  return drained;
}

Result<AppliedControls> V4l2Camera::writeControls(const ExposureRequest& request) {
  const auto write = controlWrite(setup_.controls, request);
  GLARECAM_CHECK(device_->setControls(write.values));
  std::vector<V4l2ControlValue> read_back;
  GLARECAM_ASSIGN(read_back, device_->getControls(readBackControls(setup_.controls)));
  AppliedControls applied;
  GLARECAM_ASSIGN(applied, appliedControls(setup_.controls, read_back));
  spdlog::debug("{}: exposure {} µs requested, {} µs applied; gain {} dB requested, {} dB applied",
                info_.uri, request.exposure_us, applied.exposure_us, request.gain_db,
                applied.gain_db);
  return applied;
}

// The next filled buffer; fails when none arrives within `timeout`.
Result<V4l2Buffer> V4l2Camera::nextBuffer(std::chrono::milliseconds timeout,
                                          std::string_view what) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  for (;;) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
        deadline - std::chrono::steady_clock::now());
    bool ready = false;
    if (left.count() > 0) GLARECAM_ASSIGN(ready, device_->waitForFrame(left));
    if (!ready) {
      return hardwareError(
          fmt::format("{}: no frame within {:.3g} s (frame timeout {} s + exposure)", what,
                      timeout.count() * 1e-3, options_.frame_timeout_s));
    }
    std::optional<V4l2Buffer> buffer;
    GLARECAM_ASSIGN(buffer, device_->dequeueBuffer());
    if (buffer) {
      last_sequence_ = buffer->sequence;
      return *buffer;
    }
  }
}

Result<CapturedFrame> V4l2Camera::captureOne(std::size_t index, const ExposureRequest& request) {
  int drained = 0;
  GLARECAM_ASSIGN(drained, drainReadyFrames());
  const auto gate =
      settleGate(last_sequence_ ? *last_sequence_ + 1 : 0, v4l2_options_.settle_frames);
  AppliedControls applied;
  GLARECAM_ASSIGN(applied, writeControls(request));
  exposure_in_flight_us_ = std::max(exposure_in_flight_us_, applied.exposure_us);
  const auto timeout = frameTimeout(options_.frame_timeout_s, exposure_in_flight_us_);
  const auto what = fmt::format("frame {} (exposure {} µs)", index + 1, applied.exposure_us);
  int stale = 0, corrupt = 0;
  for (;;) {
    V4l2Buffer buffer;
    GLARECAM_ASSIGN(buffer, nextBuffer(timeout, what));
    if (!gate.settled(buffer.sequence)) {
      // A driver whose sequence numbers do not advance would keep every frame stale: bounded.
      if (++stale > maxStaleFrames()) {
        GLARECAM_CHECK(requeue(buffer));
        return hardwareError(fmt::format(
            "{}: {} frames without the new exposure taking effect (the driver's sequence "
            "numbers do not advance?)",
            what, stale));
      }
    } else if (!complete(buffer)) {
      if (++corrupt > options_.max_frame_retries) {
        return hardwareError(fmt::format(
            "{}: {} corrupt frames (error flag or short), more than max_frame_retries = {}", what,
            corrupt, options_.max_frame_retries));
      }
    } else {
      CapturedFrame frame;
      frame.image = RawFrame(setup_.format.width, setup_.format.height);
      frame.exposure_us = applied.exposure_us;
      frame.gain_db = applied.gain_db;
      frame.timestamp_ns = buffer.timestamp_ns;
      frame.retries = drained + stale + corrupt;
      copyFrame(device_->bufferData(buffer.index), setup_.format, setup_.mono, frame.image);
      GLARECAM_CHECK(requeue(buffer));
      exposure_in_flight_us_ = applied.exposure_us;  // every later frame has the new exposure
      spdlog::debug("{}: {}: sequence {}, dropped {} drained, {} stale, {} corrupt", info_.uri,
                    what, buffer.sequence, drained, stale, corrupt);
      return frame;
    }
    GLARECAM_CHECK(requeue(buffer));
  }
}

// "/dev/video0" stays; "video0" means "/dev/video0".
std::string devicePath(std::string_view id) {
  return id.find('/') == std::string_view::npos ? "/dev/" + std::string(id) : std::string(id);
}

// "video12" → 12; nullopt for anything else ("video", "video0p", "vbi0").
std::optional<int> videoNodeNumber(std::string_view name) {
  constexpr std::string_view kPrefix = "video";
  if (!name.starts_with(kPrefix) || name.size() == kPrefix.size()) return std::nullopt;
  int number = 0;
  const auto digits = name.substr(kPrefix.size());
  const auto [end, error] = std::from_chars(digits.data(), digits.data() + digits.size(), number);
  if (error != std::errc{} || end != digits.data() + digits.size()) return std::nullopt;
  return number;
}

std::vector<std::string> videoNodes(const std::string& directory) {
  std::vector<std::pair<int, std::string>> numbered;
  std::error_code error;
  for (const auto& entry : std::filesystem::directory_iterator(directory, error)) {
    if (const auto number = videoNodeNumber(entry.path().filename().string())) {
      numbered.emplace_back(*number, entry.path().string());
    }
  }
  std::ranges::sort(numbered);
  std::vector<std::string> paths;
  for (auto& [number, path] : numbered) paths.push_back(std::move(path));
  return paths;
}

CameraInfo cameraInfo(const std::string& path, const V4l2Capabilities& caps) {
  CameraInfo info;
  info.uri = fmt::format("{}:{}", kV4l2Scheme, path);
  info.backend = kV4l2Scheme;
  info.model = caps.card;  // V4L2 names neither vendor nor serial
  info.detail = fmt::format("{} (driver {})", caps.bus_info, caps.driver);
  return info;
}

Status checkCapabilities(const V4l2Capabilities& caps) {
  if (!caps.video_capture) {
    return badInput(
        fmt::format("not a video capture device ('{}', driver {}: a metadata or output "
                    "node?)",
                    caps.card, caps.driver));
  }
  if (!caps.streaming) return hardwareError("the driver does not support streaming I/O");
  return {};
}

Result<V4l2Format> configureFormat(V4l2Device& device, const MonoFormat& mono) {
  V4l2FrameSize size;
  GLARECAM_ASSIGN(size, device.largestFrameSize(mono.fourcc));
  V4l2Format format;
  GLARECAM_ASSIGN(format, device.setFormat({mono.fourcc, size.width, size.height, 0, 0}));
  if (format.fourcc != mono.fourcc) {
    return hardwareError(fmt::format("the driver replaced {} by {}", v4l2FourccName(mono.fourcc),
                                     v4l2FourccName(format.fourcc)));
  }
  if (format.width <= 0 || format.height <= 0) {
    return hardwareError(fmt::format("the driver set a {}x{} frame", format.width, format.height));
  }
  format.bytes_per_line = std::max(format.bytes_per_line, format.width * mono.bytes_per_pixel);
  return format;
}

Result<V4l2Setup> setUp(V4l2Device& device, const CameraOptions& options) {
  std::vector<std::uint32_t> offered;
  GLARECAM_ASSIGN(offered, device.enumerateFormats());
  V4l2Setup setup{};
  GLARECAM_ASSIGN(setup.mono, chooseFormat(offered, options.pixel_format));
  GLARECAM_ASSIGN(setup.format, configureFormat(device, setup.mono));
  GLARECAM_ASSIGN(setup.controls, queryControlSet(device));
  return setup;
}

Status validate(const CameraOptions& options, const V4l2Options& v4l2_options) {
  if (options.max_frame_retries < 0) return badInput("max_frame_retries must be >= 0");
  if (!(options.frame_timeout_s > 0)) return badInput("frame_timeout_s must be > 0");
  if (v4l2_options.settle_frames < 0) return badInput("settle_frames must be >= 0");
  if (v4l2_options.buffer_count < 1) return badInput("buffer_count must be >= 1");
  return {};
}

class V4l2Backend final : public CameraBackend {
 public:
  V4l2Backend(V4l2DeviceOpener opener, V4l2Options options)
      : opener_(std::move(opener)), options_(std::move(options)) {}

  std::string_view scheme() const override { return kV4l2Scheme; }

  Result<std::vector<CameraInfo>> list() override {
    std::vector<CameraInfo> cameras;
    for (const auto& path : videoNodes(options_.device_directory)) {
      if (auto info = probe(path)) {
        cameras.push_back(std::move(*info));
      } else {
        spdlog::debug("{}:{}: skipped: {}", kV4l2Scheme, path, info.error().message);
      }
    }
    return cameras;
  }

  Result<std::unique_ptr<Camera>> open(std::string_view id, const CameraOptions& options) override {
    std::string path;
    GLARECAM_ASSIGN(path, resolve(id));
    const auto uri = fmt::format("{}:{}", kV4l2Scheme, path);
    auto camera = openPath(path, options);
    if (!camera) return std::unexpected(withContext(camera.error(), uri));
    return camera;
  }

 private:
  Result<CameraInfo> probe(const std::string& path) {
    std::unique_ptr<V4l2Device> device;
    GLARECAM_ASSIGN(device, opener_(path));
    V4l2Capabilities caps;
    GLARECAM_ASSIGN(caps, device->queryCapabilities());
    GLARECAM_CHECK(checkCapabilities(caps));
    return cameraInfo(path, caps);
  }

  Result<std::string> resolve(std::string_view id) {
    if (!id.empty()) return devicePath(id);
    std::vector<CameraInfo> cameras;
    GLARECAM_ASSIGN(cameras, list());
    if (cameras.empty()) {
      return hardwareError(fmt::format("{}: no V4L2 capture device found in {}", kV4l2Scheme,
                                       options_.device_directory));
    }
    return cameras.front().uri.substr(kV4l2Scheme.size() + 1);
  }

  Result<std::unique_ptr<Camera>> openPath(const std::string& path, const CameraOptions& options) {
    GLARECAM_CHECK(validate(options, options_));
    std::unique_ptr<V4l2Device> device;
    GLARECAM_ASSIGN(device, opener_(path));
    V4l2Capabilities caps;
    GLARECAM_ASSIGN(caps, device->queryCapabilities());
    GLARECAM_CHECK(checkCapabilities(caps));
    V4l2Setup setup;
    GLARECAM_ASSIGN(setup, setUp(*device, options));
    return std::make_unique<V4l2Camera>(cameraInfo(path, caps), std::move(device), setup, options,
                                        options_);
  }

  V4l2DeviceOpener opener_;
  V4l2Options options_;
};

}  // namespace

std::unique_ptr<CameraBackend> makeV4l2Backend() { return makeV4l2Backend(openV4l2Device); }

std::unique_ptr<CameraBackend> makeV4l2Backend(V4l2DeviceOpener opener, V4l2Options options) {
  return std::make_unique<V4l2Backend>(std::move(opener), std::move(options));
}

}  // namespace glarecam::capture
