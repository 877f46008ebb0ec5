#include "capture/aravis/aravis_backend.h"

#include <arv.h>
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <optional>
#include <sstream>

#include "capture/aravis/glib_ownership.h"
#include "capture/network_interfaces.h"

namespace glarecam::capture {
namespace {

using aravis::GObjectPtr;
using aravis::OwnedError;

// Deepest first: Mono8 only as the last resort (a warning says so).
constexpr std::array<std::string_view, 3> kPreferredPixelFormats{"Mono16", "Mono12", "Mono8"};
constexpr int kStreamBufferCount = 8;    // enough to absorb a burst while one is copied
constexpr guint64 kPopSliceUs = 50'000;  // how often a wait checks for control-lost
// Free-running: the frame being exposed and the one being read out when the exposure changed
// (sensors apply a new exposure from the next frame start: a global-shutter pipeline of two).
constexpr int kFreeRunningSettleFrames = 2;
constexpr double kMicrosecondsPerSecond = 1e6;
constexpr std::string_view kFakeDevicePrefix = "Fake_";  // Aravis's in-process fake: "Fake_1"
constexpr std::string_view kGigEVisionProtocol = "GigEVision";  // arv_get_device_protocol()

// An address of a GigE device (transfer none), as text.
std::string addressText(GSocketAddress* address) {
  if (address == nullptr || !G_IS_INET_SOCKET_ADDRESS(address)) return "?";
  gchar* text =
      g_inet_address_to_string(g_inet_socket_address_get_address(G_INET_SOCKET_ADDRESS(address)));
  std::string copy = text != nullptr ? text : "?";
  g_free(text);
  return copy;
}

// "GigE Vision 192.168.1.20, streams to eth1 (192.168.1.2)": where this opened camera's stream
// comes to, as `glarecam doctor` reports it.
std::string gigeDetail(ArvGvDevice* device) {
  const std::string interface_address = addressText(arv_gv_device_get_interface_address(device));
  std::string interface_name = "?";
  const auto parsed = parseIpv4(interface_address);
  for (const NetworkInterface& interface : hostInterfaces())
    if (parsed && interface.address == *parsed) interface_name = interface.name;
  return fmt::format("GigE Vision {}, streams to {} ({})",
                     addressText(arv_gv_device_get_device_address(device)), interface_name,
                     interface_address);
}

std::string deviceDetail(ArvCamera* camera) {
  if (arv_camera_is_gv_device(camera))
    return gigeDetail(ARV_GV_DEVICE(arv_camera_get_device(camera)));
  if (arv_camera_is_uv_device(camera)) return "USB3 Vision";
  return "Aravis fake camera";
}

std::string orEmpty(const char* text) { return text != nullptr ? text : ""; }

// Copies an image buffer into a RawFrame; nullopt when it is not complete or not mono.
std::optional<RawFrame> toRawFrame(ArvBuffer* buffer) {
  const ArvPixelFormat format = arv_buffer_get_image_pixel_format(buffer);
  const int width = arv_buffer_get_image_width(buffer);
  const int height = arv_buffer_get_image_height(buffer);
  std::size_t bytes_per_pixel = 0;
  if (format == ARV_PIXEL_FORMAT_MONO_8) bytes_per_pixel = 1;
  if (format == ARV_PIXEL_FORMAT_MONO_12 || format == ARV_PIXEL_FORMAT_MONO_16) bytes_per_pixel = 2;
  std::size_t size = 0;
  const auto* data = static_cast<const std::uint8_t*>(arv_buffer_get_image_data(buffer, &size));
  const std::size_t expected = static_cast<std::size_t>(width) * height * bytes_per_pixel;
  if (bytes_per_pixel == 0 || width <= 0 || height <= 0 || data == nullptr || size < expected) {
    return std::nullopt;
  }
  RawFrame frame(width, height);
  if (bytes_per_pixel == 1) {
    std::copy(data, data + expected, frame.data());
  } else {
    std::memcpy(frame.data(), data, expected);  // GenICam Mono12/16: little-endian, unpacked
  }
  return frame;
}

void onControlLost(ArvDevice*, gpointer flag) {
  static_cast<std::atomic<bool>*>(flag)->store(true);
}

class AravisCamera final : public Camera {
 public:
  AravisCamera(GObjectPtr<ArvCamera> camera, const CameraOptions& options)
      : camera_(std::move(camera)), options_(options) {}

  ~AravisCamera() override {
    if (acquiring_ && responsive()) {
      OwnedError ignored;
      arv_camera_stop_acquisition(camera_.get(), ignored.out());
    }
    if (control_lost_handler_ != 0) {
      g_signal_handler_disconnect(arv_camera_get_device(camera_.get()), control_lost_handler_);
    }
    stream_.reset();  // the stream thread stops before the camera goes
  }

  Status configure(std::string_view requested_id) {
    ArvCamera* camera = camera_.get();
    control_lost_handler_ = g_signal_connect(arv_camera_get_device(camera), "control-lost",
                                             G_CALLBACK(onControlLost), &control_lost_);
    OwnedError error;
    const std::string device_id = orEmpty(arv_camera_get_device_id(camera, error.out()));
    info_ = {.uri = "aravis:" + (requested_id.empty() ? device_id : std::string(requested_id)),
             .backend = "aravis",
             .vendor = orEmpty(arv_camera_get_vendor_name(camera, error.out())),
             .model = orEmpty(arv_camera_get_model_name(camera, error.out())),
             .serial = orEmpty(arv_camera_get_device_serial_number(camera, error.out())),
             .detail = deviceDetail(camera),
             .optics = {}};
    GLARECAM_CHECK(applyFeatures());
    GLARECAM_CHECK(choosePixelFormat());
    GLARECAM_CHECK(readLimits());
    GLARECAM_CHECK(chooseTrigger());
    return createStream();
  }

  const CameraInfo& info() const override { return info_; }
  CameraLimits limits() const override { return limits_; }
  SensorFormat format() const override { return format_; }

 private:
  // The base class turns an exception into an Error; acquisition stops first.
  Result<std::vector<CapturedFrame>> doCapture(std::span<const ExposureRequest> requests) override {
    try {
      return captureBracket(requests);
    } catch (...) {
      stopAcquisition();
      throw;
    }
  }

  Result<std::vector<CapturedFrame>> captureBracket(std::span<const ExposureRequest> requests) {
    GLARECAM_CHECK(checkConnected());
    GLARECAM_CHECK(startAcquisition());
    std::vector<CapturedFrame> frames;
    frames.reserve(requests.size());
    for (const ExposureRequest& request : requests) {
      auto frame = captureOne(request);
      if (!frame) {
        stopAcquisition();
        return std::unexpected(frame.error());
      }
      frames.push_back(std::move(*frame));
    }
    // Triggered cameras send nothing until triggered: acquisition stays on between brackets,
    // which saves its start latency (up to 100 ms with Aravis's fake camera) on every capture.
    if (!software_trigger_) stopAcquisition();
    return frames;
  }

  // A command that failed. When the camera stopped answering, later clean-up commands are
  // skipped instead of each waiting out its retries (seconds with GigE Vision).
  std::unexpected<Error> failed(std::string_view what, const OwnedError& error) {
    for (const ArvDeviceError gone : {ARV_DEVICE_ERROR_TIMEOUT, ARV_DEVICE_ERROR_NOT_CONNECTED,
                                      ARV_DEVICE_ERROR_TRANSFER_ERROR}) {
      if (error.matches(ARV_DEVICE_ERROR, gone)) unresponsive_ = true;
    }
    if (control_lost_) return lostError();
    return hardwareError(fmt::format("{}: {}: {}", info_.uri, what, error.message()));
  }
  std::unexpected<Error> lostError() const {
    return hardwareError(fmt::format(
        "{}: camera lost (control-lost: unplugged, powered off or unreachable); nothing was "
        "stored",
        info_.uri));
  }
  Status checkConnected() const {
    if (control_lost_) return lostError();
    return {};
  }

  // A preset's features first: glarecam's own settings (pixel format, manual exposure and gain,
  // the trigger) then override whatever it says about them.
  // A feature the camera lacks is the preset's fault (kBadInput); a write that fails, the link's.
  Status applyFeatures() {
    if (!options_.genicam_features || options_.genicam_features->empty()) return {};
    ArvDevice* device = arv_camera_get_device(camera_.get());
    std::istringstream entries(*options_.genicam_features);
    for (std::string entry; entries >> entry;) {
      const std::string name = entry.substr(0, entry.find('='));
      if (arv_device_get_feature(device, name.c_str()) == nullptr)
        return badInput(fmt::format("{}: GenICam features \"{}\": this camera has no feature {}",
                                    info_.uri, *options_.genicam_features, name));
    }
    OwnedError error;
    arv_device_set_features_from_string(device, options_.genicam_features->c_str(), error.out());
    if (error)
      return failed("cannot set GenICam features \"" + *options_.genicam_features + "\"", error);
    spdlog::info("{}: GenICam features set: {}", info_.uri, *options_.genicam_features);
    return {};
  }

  Status choosePixelFormat() {
    OwnedError error;
    guint count = 0;
    aravis::StringArray available(
        arv_camera_dup_available_pixel_formats_as_strings(camera_.get(), &count, error.out()));
    if (error) return failed("cannot list pixel formats", error);
    const auto offered = [&](std::string_view name) {
      for (guint i = 0; i < count; ++i) {
        if (available.get()[i] != nullptr && name == available.get()[i]) return true;
      }
      return false;
    };
    std::string chosen;
    if (options_.pixel_format) {
      if (std::find(kPreferredPixelFormats.begin(), kPreferredPixelFormats.end(),
                    *options_.pixel_format) == kPreferredPixelFormats.end()) {
        return badInput(
            fmt::format("{}: pixel format {} is not one glarecam reads (Mono16, "
                        "Mono12, Mono8)",
                        info_.uri, *options_.pixel_format));
      }
      if (!offered(*options_.pixel_format)) {
        return badInput(fmt::format("{}: pixel format {} is not offered by this camera", info_.uri,
                                    *options_.pixel_format));
      }
      chosen = *options_.pixel_format;
    } else {
      for (const auto name : kPreferredPixelFormats) {
        if (offered(name)) {
          chosen = name;
          break;
        }
      }
      if (chosen.empty()) {
        return hardwareError(fmt::format("{}: offers none of Mono16, Mono12, Mono8", info_.uri));
      }
      if (chosen == "Mono8") {
        spdlog::warn(
            "{}: no 12- or 16-bit mono format; using Mono8 (less range per frame, the "
            "bracket needs more frames)",
            info_.uri);
      }
    }
    arv_camera_set_pixel_format_from_string(camera_.get(), chosen.c_str(), error.out());
    if (error) return failed("cannot set PixelFormat " + chosen, error);
    gint x = 0, y = 0, width = 0, height = 0;
    arv_camera_get_region(camera_.get(), &x, &y, &width, &height, error.out());
    if (error) return failed("cannot read the image size", error);
    format_ = {.pixel_format = chosen,
               .width = width,
               .height = height,
               .bits_per_pixel = chosen == "Mono8" ? 8 : 16};
    return {};
  }

  Status readLimits() {
    OwnedError error;
    arv_camera_set_exposure_time_auto(camera_.get(), ARV_AUTO_OFF, error.out());
    error.reset();  // cameras without ExposureAuto are already manual
    arv_camera_get_exposure_time_bounds(camera_.get(), &limits_.min_exposure_us,
                                        &limits_.max_exposure_us, error.out());
    if (error) return failed("cannot read the exposure time range", error);
    limits_.exposure_step_us = 1.0;  // GenICam floats rarely declare one; read-back decides
    if (arv_camera_is_gain_available(camera_.get(), error.out())) {
      arv_camera_set_gain_auto(camera_.get(), ARV_AUTO_OFF, error.out());
      error.reset();
      arv_camera_get_gain_bounds(camera_.get(), &limits_.min_gain_db, &limits_.max_gain_db,
                                 error.out());
      if (error) return failed("cannot read the gain range", error);
      gain_available_ = true;
    }
    return {};
  }

  Status chooseTrigger() {
    OwnedError error;
    arv_camera_set_acquisition_mode(camera_.get(), ARV_ACQUISITION_MODE_CONTINUOUS, error.out());
    if (error) return failed("cannot set AcquisitionMode Continuous", error);
    software_trigger_ = arv_camera_is_software_trigger_supported(camera_.get(), error.out());
    error.reset();
    if (software_trigger_) {
      arv_camera_set_trigger(camera_.get(), "Software", error.out());
      if (error) return failed("cannot set TriggerSource Software", error);
    } else {
      arv_camera_clear_triggers(camera_.get(), error.out());
      error.reset();  // cameras without TriggerMode are free-running anyway
    }
    return {};
  }

  Status createStream() {
    OwnedError error;
    if (arv_camera_is_gv_device(camera_.get())) {
      arv_camera_gv_auto_packet_size(camera_.get(), error.out());
      if (error) spdlog::warn("{}: packet size negotiation failed: {}", info_.uri, error.message());
      error.reset();
    }
    stream_.reset(arv_camera_create_stream(camera_.get(), nullptr, nullptr, error.out()));
    if (error || !stream_) return failed("cannot create a stream", error);
    const guint payload = arv_camera_get_payload(camera_.get(), error.out());
    if (error) return failed("cannot read the payload size", error);
    for (int i = 0; i < kStreamBufferCount; ++i) {
      arv_stream_push_buffer(stream_.get(), arv_buffer_new_allocate(payload));
    }
    return {};
  }

  Status startAcquisition() {
    if (acquiring_) return {};
    OwnedError error;
    arv_camera_start_acquisition(camera_.get(), error.out());
    if (error) return failed("cannot start acquisition", error);
    acquiring_ = true;
    return {};
  }

  bool responsive() const { return !unresponsive_ && !control_lost_; }

  void stopAcquisition() {
    if (responsive()) {
      OwnedError error;
      arv_camera_stop_acquisition(camera_.get(), error.out());
    }
    acquiring_ = false;
    drainQueued();  // buffers that arrived after the last frame was taken
  }

  // Sets exposure and gain and returns what the camera applied.
  // Sets exposure and gain and returns what the camera applied. A value equal to the last one
  // requested is not written again (each write and read-back is a network round trip).
  Result<ExposureRequest> apply(const ExposureRequest& request) {
    const bool new_exposure = !last_request_ || last_request_->exposure_us != request.exposure_us;
    const bool new_gain = !last_request_ || last_request_->gain_db != request.gain_db;
    if (new_exposure) GLARECAM_ASSIGN(applied_.exposure_us, applyExposure(request.exposure_us));
    if (new_gain) GLARECAM_ASSIGN(applied_.gain_db, applyGain(request.gain_db));
    last_request_ = request;
    return applied_;
  }

  using FeatureSetter = void (*)(ArvCamera*, double, GError**);
  using FeatureGetter = double (*)(ArvCamera*, GError**);

  // Writes a control and reads back what the camera made of it.
  Result<double> setAndReadBack(FeatureSetter set, FeatureGetter get, double value,
                                std::string_view what) {
    last_request_.reset();  // unknown until the read-back succeeds
    OwnedError error;
    set(camera_.get(), value, error.out());
    if (error) return failed(fmt::format("cannot set {} {:g}", what, value), error);
    const double applied = get(camera_.get(), error.out());
    if (error) return failed(fmt::format("cannot read back the {}", what), error);
    return applied;
  }

  Result<double> applyExposure(double exposure_us) {
    return setAndReadBack(arv_camera_set_exposure_time, arv_camera_get_exposure_time, exposure_us,
                          "exposure (µs)");
  }

  Result<double> applyGain(double gain_db) {
    if (!gain_available_) {
      if (gain_db != 0) {
        return badInput(fmt::format("{}: this camera has no gain control", info_.uri));
      }
      return 0.0;
    }
    return setAndReadBack(arv_camera_set_gain, arv_camera_get_gain, gain_db, "gain");
  }

  // Waits for the next buffer, in slices so that control-lost ends the wait at once.
  Result<ArvBuffer*> waitForBuffer(double timeout_s) {
    const gint64 deadline =
        g_get_monotonic_time() + static_cast<gint64>(timeout_s * kMicrosecondsPerSecond);
    while (g_get_monotonic_time() < deadline) {
      GLARECAM_CHECK(checkConnected());
      if (ArvBuffer* buffer = arv_stream_timeout_pop_buffer(stream_.get(), kPopSliceUs)) {
        return buffer;
      }
    }
    return nullptr;
  }

  Status trigger() {
    if (!software_trigger_) return {};
    OwnedError error;
    arv_camera_software_trigger(camera_.get(), error.out());
    if (error) return failed("software trigger failed", error);
    return {};
  }

  // Returns buffers that arrived before this step to the pool: frames of the previous exposure.
  int drainQueued() {
    int drained = 0;
    while (ArvBuffer* queued = arv_stream_try_pop_buffer(stream_.get())) {
      arv_stream_push_buffer(stream_.get(), queued);
      ++drained;
    }
    return drained;
  }

  // One frame at `request`: triggers, and discards (counting them) frames that time out or
  // arrive incomplete (at most max_frame_retries), and complete frames received before the new
  // exposure was set (late answers to an earlier trigger; at most one per stream buffer).
  // Free-running cameras also skip the frames in flight during the change.
  Result<CapturedFrame> captureOne(const ExposureRequest& request) {
    CapturedFrame frame;
    frame.retries = drainQueued();
    ExposureRequest applied;
    GLARECAM_ASSIGN(applied, apply(request));
    const auto applied_at_ns = static_cast<guint64>(g_get_real_time()) * 1000;  // host clock
    frame.exposure_us = applied.exposure_us;
    frame.gain_db = applied.gain_db;
    const double timeout_s =
        options_.frame_timeout_s + applied.exposure_us / kMicrosecondsPerSecond;
    int settle = software_trigger_ ? 0 : kFreeRunningSettleFrames;
    int failures = 0, stale = 0;
    std::string last_problem = "no frame";
    bool needs_trigger = true;
    while (failures <= options_.max_frame_retries && stale <= kStreamBufferCount) {
      if (needs_trigger) GLARECAM_CHECK(trigger());
      ArvBuffer* buffer = nullptr;
      GLARECAM_ASSIGN(buffer, waitForBuffer(timeout_s));
      if (buffer == nullptr) {
        last_problem = fmt::format("no frame within {:g} s", timeout_s);
        ++failures;
        needs_trigger = true;
        continue;
      }
      const ArvBufferStatus status = arv_buffer_get_status(buffer);
      // The receive time is that of the frame's first packet: meaningful for complete frames.
      const bool late = status == ARV_BUFFER_STATUS_SUCCESS &&
                        arv_buffer_get_system_timestamp(buffer) < applied_at_ns;
      std::optional<RawFrame> image;
      if (!late && status == ARV_BUFFER_STATUS_SUCCESS) image = toRawFrame(buffer);
      frame.timestamp_ns = arv_buffer_get_timestamp(buffer);
      arv_stream_push_buffer(stream_.get(), buffer);
      needs_trigger = !late;  // a late frame answered an earlier trigger: ours is pending
      if (late) {
        ++stale;
        ++frame.retries;
      } else if (!image) {
        last_problem = status == ARV_BUFFER_STATUS_SUCCESS ? "frame of unexpected size or format"
                                                           : bufferStatusText(status);
        ++failures;
        ++frame.retries;
      } else if (settle > 0) {
        --settle;  // exposed (partly) before the change
        ++frame.retries;
      } else {
        frame.image = std::move(*image);
        return frame;
      }
    }
    return hardwareError(fmt::format("{}: {} attempts at {:g} µs failed (last: {}); nothing stored",
                                     info_.uri, failures, frame.exposure_us, last_problem));
  }

  static std::string bufferStatusText(ArvBufferStatus status) {
    switch (status) {
      case ARV_BUFFER_STATUS_TIMEOUT:
        return "buffer timed out: packets lost";
      case ARV_BUFFER_STATUS_MISSING_PACKETS:
        return "missing packets";
      case ARV_BUFFER_STATUS_WRONG_PACKET_ID:
        return "wrong packet id";
      case ARV_BUFFER_STATUS_SIZE_MISMATCH:
        return "payload larger than the buffer";
      case ARV_BUFFER_STATUS_ABORTED:
        return "acquisition aborted";
      default:
        return fmt::format("buffer status {}", static_cast<int>(status));
    }
  }

  GObjectPtr<ArvCamera> camera_;
  GObjectPtr<ArvStream> stream_;
  CameraOptions options_;
  CameraInfo info_;
  CameraLimits limits_;
  SensorFormat format_;
  bool gain_available_ = false;
  bool software_trigger_ = false;
  bool acquiring_ = false;
  bool unresponsive_ = false;
  std::optional<ExposureRequest> last_request_;  // and what the camera made of it:
  ExposureRequest applied_;
  std::atomic<bool> control_lost_{false};
  gulong control_lost_handler_ = 0;
};

}  // namespace

void enableAravisFakeInterface() { arv_enable_interface("Fake"); }

namespace {

class AravisBackend final : public CameraBackend {
 public:
  std::string_view scheme() const override { return "aravis"; }

  Result<std::vector<CameraInfo>> list() override {
    arv_update_device_list();
    const std::vector<NetworkInterface> interfaces = hostInterfaces();
    std::vector<CameraInfo> cameras;
    for (unsigned i = 0; i < arv_get_n_devices(); ++i) {
      std::string detail = fmt::format("{} {}", orEmpty(arv_get_device_protocol(i)),
                                       orEmpty(arv_get_device_address(i)));
      if (const auto stream = streamInterfaceOf(i, interfaces))
        detail += ", streams to " + describeInterface(*stream);
      cameras.push_back({.uri = "aravis:" + orEmpty(arv_get_device_id(i)),
                         .backend = "aravis",
                         .vendor = orEmpty(arv_get_device_vendor(i)),
                         .model = orEmpty(arv_get_device_model(i)),
                         .serial = orEmpty(arv_get_device_serial_nbr(i)),
                         .detail = std::move(detail),
                         .optics = {}});
    }
    return cameras;
  }

 private:
  struct GigeTarget {
    std::uint32_t device_address = 0;
    NetworkInterface interface;
  };

  // The interface device `index` of Aravis's list streams to, when it is a GigE Vision camera
  // whose address a local subnet holds.
  static std::optional<NetworkInterface> streamInterfaceOf(
      unsigned index, const std::vector<NetworkInterface>& interfaces) {
    if (orEmpty(arv_get_device_protocol(index)) != kGigEVisionProtocol) return std::nullopt;
    const auto address = parseIpv4(orEmpty(arv_get_device_address(index)));
    return address ? streamInterfaceFor(*address, interfaces) : std::nullopt;
  }

  // What `name` (an address, or an id as `glarecam cameras` lists it: device id, physical id or
  // address; empty: the first camera) names, when it is a GigE Vision camera on a local subnet.
  // The list Aravis already has is asked first, a discovery only when it does not know the name.
  static std::optional<GigeTarget> gigeTarget(const std::string& name) {
    const std::vector<NetworkInterface> interfaces = hostInterfaces();
    if (const auto address = parseIpv4(name)) {
      const auto interface = streamInterfaceFor(*address, interfaces);
      if (!interface) return std::nullopt;
      return GigeTarget{.device_address = *address, .interface = *interface};
    }
    const auto find = [&]() -> std::optional<unsigned> {
      for (unsigned i = 0; i < arv_get_n_devices(); ++i)
        if (name.empty() || name == orEmpty(arv_get_device_id(i)) ||
            name == orEmpty(arv_get_device_physical_id(i)) ||
            name == orEmpty(arv_get_device_address(i)))
          return i;
      return std::nullopt;
    };
    std::optional<unsigned> index = find();
    if (!index) {
      arv_update_device_list();
      index = find();
    }
    if (!index) return std::nullopt;
    const auto address = parseIpv4(orEmpty(arv_get_device_address(*index)));
    const auto interface = streamInterfaceOf(*index, interfaces);
    if (!address || !interface) return std::nullopt;
    return GigeTarget{.device_address = *address, .interface = *interface};
  }

  Result<std::unique_ptr<Camera>> open(std::string_view id, const CameraOptions& options) override {
    const std::string name(id);
    // Aravis's in-process fake camera is a test double: enabled only when asked for by name.
    if (name.starts_with(kFakeDevicePrefix)) enableAravisFakeInterface();
    OwnedError error;
    GObjectPtr<ArvCamera> camera;
    // A GigE Vision camera streams to the interface whose subnet holds its address
    // (network_interfaces.h); anything else, and a routed camera, as Aravis opens it.
    if (const auto target = gigeTarget(name)) {
      GObjectPtr<GInetAddress> interface_address(
          g_inet_address_new_from_string(formatIpv4(target->interface.address).c_str()));
      GObjectPtr<GInetAddress> device_address(
          g_inet_address_new_from_string(formatIpv4(target->device_address).c_str()));
      GObjectPtr<ArvDevice> device(
          arv_gv_device_new(interface_address.get(), device_address.get(), error.out()));
      if (device && !error) camera.reset(arv_camera_new_with_device(device.get(), error.out()));
    } else {
      camera.reset(arv_camera_new(name.empty() ? nullptr : name.c_str(), error.out()));
    }
    if (error || !camera) {
      return hardwareError(
          fmt::format("aravis:{}: no such camera ({}); `glarecam cameras` lists "
                      "what Aravis sees",
                      name, error ? error.message() : "none found"));
    }
    auto opened = std::make_unique<AravisCamera>(std::move(camera), options);
    GLARECAM_CHECK(opened->configure(id));
    return opened;
  }
};

}  // namespace

std::unique_ptr<CameraBackend> makeAravisBackend() { return std::make_unique<AravisBackend>(); }

}  // namespace glarecam::capture
