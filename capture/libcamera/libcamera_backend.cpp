#include "capture/libcamera/libcamera_backend.h"

#include <fmt/format.h>
#include <libcamera/libcamera.h>
#include <sys/mman.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <deque>
#include <limits>
#include <mutex>
#include <utility>

#include "capture/libcamera/request_matching.h"

namespace glarecam::capture {
namespace {

namespace lc = ::libcamera;
using libcam::BracketMatcher;
using libcam::FrameMeta;
using libcam::RawLayout;

constexpr std::string_view kLibcameraScheme = "libcamera";
// libcamera logs INFO and WARN lines (the version banner, "No IPA found") to stderr from the
// first CameraManager on; glarecam keeps only its errors unless the user chose levels.
constexpr const char* kLogLevelsVariable = "LIBCAMERA_LOG_LEVELS";
constexpr const char* kQuietLogLevels = "*:ERROR";
// libcamera 0.0.3 does not publish a sensor's line period, the step its exposures are rounded to.
// A sensor integrates for at least one line, so the minimum of the ExposureTime control bounds
// the rounding; the cap keeps a pipeline reporting a long minimum from blurring the steps.
constexpr double kExposureControlUnitUs = 1.0;  // ExposureTime is an integer number of µs
constexpr double kMaxExposureRoundingUs = 100.0;

std::string uriFor(std::string_view id) { return fmt::format("{}:{}", kLibcameraScheme, id); }
std::string errnoText(int ret) { return std::strerror(-ret); }

std::string versionText() {
  const std::string& reported = lc::CameraManager::version();
  const auto version = libcam::parseLibcameraVersion(reported);
  return version ? version->toString() : reported;
}

std::optional<double> numeric(const lc::ControlValue& value) {
  if (value.isArray()) return std::nullopt;
  switch (value.type()) {
    case lc::ControlTypeInteger32:
      return value.get<std::int32_t>();
    case lc::ControlTypeInteger64:
      return static_cast<double>(value.get<std::int64_t>());
    case lc::ControlTypeFloat:
      return value.get<float>();
    default:
      return std::nullopt;
  }
}

std::optional<double> metadataValue(const lc::ControlList& metadata, const lc::ControlId& id) {
  if (!metadata.contains(id.id())) return std::nullopt;
  return numeric(metadata.get(id.id()));
}

const lc::ControlInfo* controlInfo(const lc::Camera& camera, const lc::ControlId& id) {
  const lc::ControlInfoMap& controls = camera.controls();
  const auto it = controls.find(&id);
  return it == controls.end() ? nullptr : &it->second;
}

// Runs `on_exit` on every way out of a scope.
template <typename F>
struct ScopeExit {
  F on_exit;
  ~ScopeExit() { on_exit(); }
};
template <typename F>
ScopeExit(F) -> ScopeExit<F>;

// The process's one CameraManager. libcamera aborts ("Multiple IPAManager objects are not
// allowed") when a second manager is constructed while one exists, so every backend object and
// every camera it opened share this one, and the last owner stops it. Sessions are created and
// dropped from one thread (glarecam opens cameras from its main thread).
class ManagerSession {
  struct Token {};

 public:
  ManagerSession(Token, std::unique_ptr<lc::CameraManager> manager)
      : manager_(std::move(manager)) {}
  ~ManagerSession() { manager_->stop(); }
  ManagerSession(const ManagerSession&) = delete;
  ManagerSession& operator=(const ManagerSession&) = delete;

  lc::CameraManager& manager() { return *manager_; }

  static Result<std::shared_ptr<ManagerSession>> shared() {
    static std::mutex mutex;
    static std::weak_ptr<ManagerSession> current;
    const std::lock_guard lock(mutex);
    if (auto session = current.lock()) return session;
    GLARECAM_CHECK(libcam::checkLibcameraVersion(lc::CameraManager::version()));
    setenv(kLogLevelsVariable, kQuietLogLevels, /*overwrite=*/0);
    auto manager = std::make_unique<lc::CameraManager>();
    if (const int ret = manager->start(); ret < 0) {
      return hardwareError(
          fmt::format("libcamera: the camera manager failed to start: {}", errnoText(ret)));
    }
    auto session = std::make_shared<ManagerSession>(Token{}, std::move(manager));
    current = session;
    return session;
  }

 private:
  std::unique_ptr<lc::CameraManager> manager_;
};

// A camera acquired for exclusive use; released once, on destruction.
class AcquiredCamera {
 public:
  static Result<AcquiredCamera> acquire(std::shared_ptr<lc::Camera> camera) {
    if (const int ret = camera->acquire(); ret < 0) {
      return hardwareError(fmt::format("camera is in use ({})", errnoText(ret)));
    }
    return AcquiredCamera(std::move(camera));
  }
  AcquiredCamera(AcquiredCamera&& other) noexcept : camera_(std::move(other.camera_)) {}
  AcquiredCamera& operator=(AcquiredCamera&&) = delete;
  ~AcquiredCamera() {
    if (camera_) camera_->release();
  }

  lc::Camera& operator*() const { return *camera_; }
  lc::Camera* operator->() const { return camera_.get(); }
  const std::shared_ptr<lc::Camera>& shared() const { return camera_; }

 private:
  explicit AcquiredCamera(std::shared_ptr<lc::Camera> camera) : camera_(std::move(camera)) {}
  std::shared_ptr<lc::Camera> camera_;
};

// Plane 0 of a dma-buf frame buffer mapped read-only; unmapped once, on destruction. Raw
// formats are single-plane.
class MappedPlane {
 public:
  static Result<MappedPlane> map(const lc::FrameBuffer& buffer) {
    if (buffer.planes().empty()) return hardwareError("frame buffer has no planes");
    const lc::FrameBuffer::Plane& plane = buffer.planes().front();
    const std::size_t offset =
        plane.offset == lc::FrameBuffer::Plane::kInvalidOffset ? 0 : plane.offset;
    const std::size_t length = offset + plane.length;
    void* base = mmap(nullptr, length, PROT_READ, MAP_SHARED, plane.fd.get(), 0);
    if (base == MAP_FAILED) {
      return hardwareError(fmt::format("cannot map a frame buffer: {}", std::strerror(errno)));
    }
    return MappedPlane(base, length, offset);
  }
  MappedPlane(MappedPlane&& other) noexcept
      : base_(std::exchange(other.base_, nullptr)),
        length_(other.length_),
        offset_(other.offset_) {}
  MappedPlane& operator=(MappedPlane&&) = delete;
  ~MappedPlane() {
    if (base_) munmap(base_, length_);
  }

  std::span<const std::uint8_t> bytes() const {
    return {static_cast<const std::uint8_t*>(base_) + offset_, length_ - offset_};
  }

 private:
  MappedPlane(void* base, std::size_t length, std::size_t offset)
      : base_(base), length_(length), offset_(offset) {}
  void* base_;
  std::size_t length_;
  std::size_t offset_;
};

struct FormatChoice {
  lc::PixelFormat pixel_format;
  RawLayout layout;
};

std::string describeFormats(const std::vector<lc::PixelFormat>& formats) {
  std::string list;
  for (const lc::PixelFormat& format : formats) {
    const auto layout = libcam::parseRawLayout(format.toString());
    list += (list.empty() ? "" : ", ") + format.toString();
    if (layout) list += " = " + layout->genicamName();
  }
  return list.empty() ? "none" : list;
}

// The requested format (a GenICam name such as "Mono12" or a libcamera name such as
// "R12_CSI2P"), or the deepest one glarecam can unpack, mono before Bayer.
Result<FormatChoice> chooseFormat(const lc::StreamFormats& formats,
                                  const std::optional<std::string>& requested) {
  const std::vector<lc::PixelFormat> offered = formats.pixelformats();
  std::optional<FormatChoice> best;
  for (const lc::PixelFormat& format : offered) {
    const auto layout = libcam::parseRawLayout(format.toString());
    if (!layout) continue;
    if (requested) {
      if (*requested == format.toString() || *requested == layout->genicamName()) {
        return FormatChoice{format, *layout};
      }
    } else if (!best || layout->preference() > best->layout.preference()) {
      best = FormatChoice{format, *layout};
    }
  }
  if (requested) {
    return badInput(fmt::format("pixel format {} is not offered (offered: {})", *requested,
                                describeFormats(offered)));
  }
  if (!best) {
    return hardwareError(
        fmt::format("no raw format glarecam can unpack (offered: {})", describeFormats(offered)));
  }
  return *best;
}

lc::Size largestSize(const lc::StreamFormats& formats, const lc::PixelFormat& format,
                     lc::Size fallback) {
  const std::vector<lc::Size> sizes = formats.sizes(format);
  if (sizes.empty()) return fallback;
  return *std::ranges::max_element(
      sizes, {}, [](const lc::Size& s) { return static_cast<std::uint64_t>(s.width) * s.height; });
}

CameraInfo describe(const lc::Camera& camera) {
  CameraInfo info;
  info.uri = uriFor(camera.id());
  info.backend = std::string(kLibcameraScheme);
  info.model = camera.properties().get(lc::properties::Model).value_or("");
  info.detail = camera.id();
  return info;
}

class LibcameraCamera final : public Camera {
 public:
  LibcameraCamera(std::shared_ptr<ManagerSession> session, AcquiredCamera camera,
                  const CameraOptions& options)
      : session_(std::move(session)),
        camera_(std::move(camera)),
        options_(options),
        info_(describe(*camera_)) {}
  ~LibcameraCamera() override {
    camera_->requestCompleted.disconnect(this);
    camera_->disconnected.disconnect(this);
  }

  // Configures the raw stream, allocates and maps its buffers, reads the limits.
  Status setUp();

  const CameraInfo& info() const override { return info_; }
  CameraLimits limits() const override { return limits_; }
  SensorFormat format() const override { return format_; }

 private:
  Result<std::vector<CapturedFrame>> doCapture(std::span<const ExposureRequest> requests) override;
  Status readControls();
  Status configureStream();
  Status createRequests();
  Status checkControlRange(std::span<const ExposureRequest> requests) const;
  Result<std::vector<CapturedFrame>> captureBracket(std::span<const ExposureRequest> requests);
  Status handleCompletion(lc::Request& request, BracketMatcher& matcher,
                          std::vector<CapturedFrame>& frames);
  Status queueFor(std::size_t request_index, std::size_t step, BracketMatcher& matcher);
  void setControls(lc::ControlList& controls, const ExposureRequest& step) const;
  std::optional<std::string> failure(const lc::Request& request) const;
  FrameMeta readMeta(lc::Request& request) const;
  Result<CapturedFrame> frameFrom(const lc::Request& request, const FrameMeta& meta,
                                  const ExposureRequest& step) const;
  Result<lc::Request*> waitForCompletion(double timeout_s);
  void stopStreaming();
  void onRequestCompleted(lc::Request* request);
  void onDisconnected();

  std::shared_ptr<ManagerSession> session_;  // outlives everything below
  AcquiredCamera camera_;
  CameraOptions options_;
  CameraInfo info_;
  CameraLimits limits_;
  SensorFormat format_;
  RawLayout layout_;
  libcam::MatchRule rule_;
  bool has_gain_ = false;
  bool has_ae_enable_ = false;
  std::optional<std::array<std::int64_t, 2>> frame_durations_us_;
  std::unique_ptr<lc::CameraConfiguration> config_;
  std::unique_ptr<lc::FrameBufferAllocator> allocator_;
  std::vector<MappedPlane> mapped_;                     // one per request, same index
  std::vector<std::unique_ptr<lc::Request>> requests_;  // cookie = index
  std::vector<std::size_t> request_step_;               // the step each request was queued for

  std::mutex mutex_;  // guards done_ and lost_, written by libcamera's thread
  std::condition_variable completed_;
  std::deque<lc::Request*> done_;
  bool lost_ = false;
};

Status LibcameraCamera::setUp() {
  camera_->requestCompleted.connect(this, &LibcameraCamera::onRequestCompleted);
  camera_->disconnected.connect(this, &LibcameraCamera::onDisconnected);
  GLARECAM_CHECK(readControls());
  GLARECAM_CHECK(configureStream());
  return createRequests();
}

Status LibcameraCamera::readControls() {
  const lc::ControlInfo* exposure = controlInfo(*camera_, lc::controls::ExposureTime);
  if (!exposure) return hardwareError("no ExposureTime control: exposures cannot be set");
  limits_.min_exposure_us = numeric(exposure->min()).value_or(0);
  limits_.max_exposure_us = numeric(exposure->max()).value_or(0);
  limits_.exposure_step_us = kExposureControlUnitUs;
  rule_.exposure_rounding_us =
      std::clamp(limits_.min_exposure_us, kExposureControlUnitUs, kMaxExposureRoundingUs);
  if (const lc::ControlInfo* gain = controlInfo(*camera_, lc::controls::AnalogueGain)) {
    has_gain_ = true;
    limits_.min_gain_db = libcam::gainLinearToDb(std::max(numeric(gain->min()).value_or(1), 1e-3));
    limits_.max_gain_db = libcam::gainLinearToDb(std::max(numeric(gain->max()).value_or(1), 1e-3));
  }
  has_ae_enable_ = controlInfo(*camera_, lc::controls::AeEnable) != nullptr;
  if (const lc::ControlInfo* frame = controlInfo(*camera_, lc::controls::FrameDurationLimits)) {
    const auto min_us = numeric(frame->min());
    const auto max_us = numeric(frame->max());
    if (min_us && max_us) {
      frame_durations_us_ = {static_cast<std::int64_t>(*min_us),
                             static_cast<std::int64_t>(*max_us)};
    }
  }
  return {};
}

Status LibcameraCamera::configureStream() {
  config_ = camera_->generateConfiguration({lc::StreamRole::Raw});
  if (!config_ || config_->empty()) return hardwareError("the pipeline offers no raw stream");
  lc::StreamConfiguration& stream = config_->at(0);
  FormatChoice choice;
  GLARECAM_ASSIGN(choice, chooseFormat(stream.formats(), options_.pixel_format));
  stream.pixelFormat = choice.pixel_format;
  stream.size = largestSize(stream.formats(), choice.pixel_format, stream.size);
  if (config_->validate() == lc::CameraConfiguration::Invalid) {
    return hardwareError(fmt::format("the raw stream {} is invalid", stream.toString()));
  }
  const auto layout = libcam::parseRawLayout(stream.pixelFormat.toString());  // maybe adjusted
  if (!layout) {
    return hardwareError(
        fmt::format("the pipeline adjusted the raw format to {}, which glarecam "
                    "cannot unpack",
                    stream.pixelFormat.toString()));
  }
  if (const int ret = camera_->configure(config_.get()); ret < 0) {
    return hardwareError(
        fmt::format("configuring {} failed: {}", stream.toString(), errnoText(ret)));
  }
  layout_ = *layout;
  format_.pixel_format = layout_.genicamName();
  format_.width = static_cast<int>(stream.size.width);
  format_.height = static_cast<int>(stream.size.height);
  format_.bits_per_pixel = layout_.depth_bits <= 8 ? 8 : 16;
  return {};
}

Status LibcameraCamera::createRequests() {
  lc::Stream* stream = config_->at(0).stream();
  allocator_ = std::make_unique<lc::FrameBufferAllocator>(camera_.shared());
  if (const int ret = allocator_->allocate(stream); ret < 0) {
    return hardwareError(fmt::format("cannot allocate frame buffers: {}", errnoText(ret)));
  }
  const auto& buffers = allocator_->buffers(stream);
  for (std::size_t i = 0; i < buffers.size(); ++i) {
    auto plane = MappedPlane::map(*buffers[i]);
    if (!plane) return std::unexpected(plane.error());
    mapped_.push_back(std::move(*plane));
    std::unique_ptr<lc::Request> request = camera_->createRequest(i);
    if (!request) return hardwareError("cannot create a capture request");
    if (const int ret = request->addBuffer(stream, buffers[i].get()); ret < 0) {
      return hardwareError(fmt::format("cannot attach a frame buffer: {}", errnoText(ret)));
    }
    requests_.push_back(std::move(request));
  }
  request_step_.assign(requests_.size(), 0);
  if (requests_.empty()) return hardwareError("the pipeline allocated no frame buffers");
  return {};
}

Result<std::vector<CapturedFrame>> LibcameraCamera::doCapture(
    std::span<const ExposureRequest> requests) {
  {
    const std::lock_guard lock(mutex_);
    if (lost_) return hardwareError(info_.uri + ": the camera was disconnected");
  }
  GLARECAM_CHECK(checkControlRange(requests));
  return captureBracket(requests);
}

// The base class checked the requests against limits(); a camera that states no longest
// exposure still takes ExposureTime as a 32-bit count of µs.
Status LibcameraCamera::checkControlRange(std::span<const ExposureRequest> requests) const {
  constexpr double kMaxControlUs = std::numeric_limits<std::int32_t>::max();
  for (const ExposureRequest& step : requests) {
    if (step.exposure_us > kMaxControlUs)
      return badInput(fmt::format("exposure {} µs is beyond libcamera's ExposureTime control",
                                  step.exposure_us));
  }
  return {};
}

Result<std::vector<CapturedFrame>> LibcameraCamera::captureBracket(
    std::span<const ExposureRequest> requests) {
  BracketMatcher matcher({requests.begin(), requests.end()}, rule_, options_.max_frame_retries);
  lc::ControlList start_controls(camera_->controls());
  setControls(start_controls, requests.front());
  if (frame_durations_us_) {
    start_controls.set(lc::controls::FrameDurationLimits,
                       lc::Span<const std::int64_t, 2>(*frame_durations_us_));
  }
  if (const int ret = camera_->start(&start_controls); ret < 0) {
    return hardwareError(fmt::format("cannot start streaming: {}", errnoText(ret)));
  }
  const ScopeExit stop_on_exit{[this] { stopStreaming(); }};  // pending requests: cancelled
  for (std::size_t r = 0; r < requests_.size(); ++r) {
    const auto step = matcher.nextStep();
    if (!step) break;
    GLARECAM_CHECK(queueFor(r, *step, matcher));
  }
  const double longest_us =
      std::ranges::max(requests, {}, &ExposureRequest::exposure_us).exposure_us;
  const double timeout_s = options_.frame_timeout_s + longest_us * 1e-6;
  std::vector<CapturedFrame> frames(requests.size());
  while (!matcher.complete()) {
    lc::Request* request = nullptr;
    GLARECAM_ASSIGN(request, waitForCompletion(timeout_s));
    GLARECAM_CHECK(handleCompletion(*request, matcher, frames));
  }
  for (std::size_t i = 0; i < frames.size(); ++i) frames[i].retries = matcher.retries(i);
  return frames;
}

Status LibcameraCamera::handleCompletion(lc::Request& request, BracketMatcher& matcher,
                                         std::vector<CapturedFrame>& frames) {
  const auto index = static_cast<std::size_t>(request.cookie());
  const std::size_t queued_for = request_step_[index];
  if (const auto why = failure(request)) {
    GLARECAM_CHECK(matcher.onFailure(queued_for, *why));
  } else {
    const FrameMeta meta = readMeta(request);
    std::optional<std::size_t> filled;
    GLARECAM_ASSIGN(filled, matcher.onFrame(queued_for, meta));
    if (filled) GLARECAM_ASSIGN(frames[*filled], frameFrom(request, meta, matcher.step(*filled)));
  }
  if (const auto next = matcher.nextStep()) GLARECAM_CHECK(queueFor(index, *next, matcher));
  return {};
}

Status LibcameraCamera::queueFor(std::size_t request_index, std::size_t step,
                                 BracketMatcher& matcher) {
  lc::Request& request = *requests_[request_index];
  request.reuse(lc::Request::ReuseBuffers);
  setControls(request.controls(), matcher.step(step));
  request_step_[request_index] = step;
  if (const int ret = camera_->queueRequest(&request); ret < 0) {
    return hardwareError(fmt::format("cannot queue a request: {}", errnoText(ret)));
  }
  matcher.onQueued(step);
  return {};
}

void LibcameraCamera::setControls(lc::ControlList& controls, const ExposureRequest& step) const {
  if (has_ae_enable_) controls.set(lc::controls::AeEnable, false);
  controls.set(lc::controls::ExposureTime,
               static_cast<std::int32_t>(std::lround(step.exposure_us)));
  if (has_gain_) {
    controls.set(lc::controls::AnalogueGain,
                 static_cast<float>(libcam::gainDbToLinear(step.gain_db)));
  }
}

std::optional<std::string> LibcameraCamera::failure(const lc::Request& request) const {
  if (request.status() == lc::Request::RequestCancelled) return "request cancelled";
  const lc::FrameBuffer* buffer = request.findBuffer(config_->at(0).stream());
  if (!buffer) return "request completed without its buffer";
  if (buffer->metadata().status != lc::FrameMetadata::FrameSuccess) {
    return fmt::format("frame {} failed", buffer->metadata().sequence);
  }
  return std::nullopt;
}

// Request::metadata() has no const overload in libcamera 0.0.3, hence the non-const request.
FrameMeta LibcameraCamera::readMeta(lc::Request& request) const {
  const lc::ControlList& metadata = request.metadata();
  FrameMeta meta;
  meta.exposure_us = metadataValue(metadata, lc::controls::ExposureTime);
  const auto gain_linear = metadataValue(metadata, lc::controls::AnalogueGain);
  if (gain_linear && *gain_linear > 0) meta.gain_db = libcam::gainLinearToDb(*gain_linear);
  meta.sequence = request.findBuffer(config_->at(0).stream())->metadata().sequence;
  return meta;
}

Result<CapturedFrame> LibcameraCamera::frameFrom(const lc::Request& request, const FrameMeta& meta,
                                                 const ExposureRequest& step) const {
  const lc::StreamConfiguration& stream = config_->at(0);
  const std::size_t stride =
      stream.stride > 0 ? stream.stride : libcam::packedRowBytes(layout_, format_.width);
  CapturedFrame frame;
  GLARECAM_ASSIGN(frame.image, libcam::unpackRaw(mapped_[request.cookie()].bytes(), format_.width,
                                                 format_.height, stride, layout_));
  frame.exposure_us = *meta.exposure_us;
  frame.gain_db = meta.gain_db.value_or(step.gain_db);  // pipelines that report no gain
  frame.timestamp_ns = request.findBuffer(stream.stream())->metadata().timestamp;
  return frame;
}

Result<lc::Request*> LibcameraCamera::waitForCompletion(double timeout_s) {
  std::unique_lock lock(mutex_);
  const auto timeout = std::chrono::duration<double>(timeout_s);
  if (!completed_.wait_for(lock, timeout, [this] { return lost_ || !done_.empty(); })) {
    return hardwareError(fmt::format("no frame completed within {:.1f} s", timeout_s));
  }
  if (lost_) return hardwareError("the camera was disconnected");
  lc::Request* request = done_.front();
  done_.pop_front();
  return request;
}

void LibcameraCamera::stopStreaming() {
  camera_->stop();  // completes the pending requests, cancelled, before it returns
  const std::lock_guard lock(mutex_);
  done_.clear();
}

void LibcameraCamera::onRequestCompleted(lc::Request* request) {
  {
    const std::lock_guard lock(mutex_);
    done_.push_back(request);
  }
  completed_.notify_one();
}

void LibcameraCamera::onDisconnected() {
  {
    const std::lock_guard lock(mutex_);
    lost_ = true;
  }
  completed_.notify_one();
}

class LibcameraBackend final : public CameraBackend {
 public:
  std::string_view scheme() const override { return kLibcameraScheme; }
  Result<std::vector<CameraInfo>> list() override {
    return catchExceptions([&] { return listCameras(); });
  }
  Result<std::unique_ptr<Camera>> open(std::string_view id, const CameraOptions& options) override {
    return catchExceptions([&] { return openCamera(id, options); });
  }

 private:
  Result<std::vector<CameraInfo>> listCameras();
  Result<std::unique_ptr<Camera>> openCamera(std::string_view id, const CameraOptions& options);
  // Started on first use, so that building the registry does not start libcamera.
  Result<ManagerSession*> session();
  std::shared_ptr<ManagerSession> session_;
};

Result<ManagerSession*> LibcameraBackend::session() {
  if (!session_) GLARECAM_ASSIGN(session_, ManagerSession::shared());
  return session_.get();
}

Result<std::vector<CameraInfo>> LibcameraBackend::listCameras() {
  ManagerSession* session = nullptr;
  GLARECAM_ASSIGN(session, this->session());
  std::vector<CameraInfo> cameras;
  for (const std::shared_ptr<lc::Camera>& camera : session->manager().cameras()) {
    cameras.push_back(describe(*camera));
  }
  return cameras;
}

Result<std::unique_ptr<Camera>> LibcameraBackend::openCamera(std::string_view id,
                                                             const CameraOptions& options) {
  const std::string uri = uriFor(id);
  auto started = this->session();
  if (!started) return std::unexpected(withContext(started.error(), uri));
  ManagerSession* session = *started;
  const std::vector<std::shared_ptr<lc::Camera>> cameras = session->manager().cameras();
  if (cameras.empty()) {
    return hardwareError(
        fmt::format("{}: no camera found (libcamera {} sees none)", uri, versionText()));
  }
  std::shared_ptr<lc::Camera> camera =
      id.empty() ? cameras.front() : session->manager().get(std::string(id));
  if (!camera) {
    std::string seen;
    for (const auto& c : cameras) seen += (seen.empty() ? "" : ", ") + uriFor(c->id());
    return hardwareError(fmt::format("{}: no such camera (libcamera sees {})", uri, seen));
  }
  auto acquired = AcquiredCamera::acquire(camera);
  if (!acquired) return std::unexpected(withContext(acquired.error(), uriFor(camera->id())));
  auto opened = std::make_unique<LibcameraCamera>(session_, std::move(*acquired), options);
  if (auto set_up = opened->setUp(); !set_up) {
    return std::unexpected(withContext(set_up.error(), opened->info().uri));
  }
  return opened;
}

}  // namespace

std::unique_ptr<CameraBackend> makeLibcameraBackend() {
  return std::make_unique<LibcameraBackend>();
}

}  // namespace glarecam::capture
