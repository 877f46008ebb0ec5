#include "capture/aravis/fake_gv_camera.h"

#include <arpa/inet.h>
#include <arv.h>
#include <fmt/format.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstring>
#include <map>
#include <thread>
#include <tuple>
#include <vector>

#include "capture/aravis/glib_ownership.h"
#include "capture/sim/sensor_model.h"
#include "core/atomic_file.h"
#include "core/json.h"

namespace glarecam::capture {
namespace {

// The simulated sensor is 12-bit; Mono16 frames carry its values MSB-aligned, Mono8 its top
// 8 bits: 4 bits of shift either way.
constexpr int kMono16Shift = 4;
constexpr int kMono8Shift = 4;
constexpr int kMono8Max = 255;
constexpr std::size_t kMaxReusedFrames = 64;  // distinct exposures kept with reuse_frames
// The longest exposure the fake camera takes in full. Aravis's fake answers no control packets
// while its one thread waits, and its client gives up on the control channel after a few seconds
// (GVCP timeouts, the heartbeat): a longer exposure is sent after this long.
constexpr std::chrono::microseconds kMaxTakenExposure{2'000'000};

Calibration scaledCalibration(Calibration base, double dn_scale) {
  base.black_level_dn *= dn_scale;
  base.saturation_dn *= dn_scale;
  base.luminance_factor /= dn_scale;  // K is cd/m² per DN/µs
  if (base.noise) {
    base.noise->read_noise_dn *= dn_scale;
    base.noise->dn_per_electron *= dn_scale;
  }
  return base;
}

// GigE Vision control (GVCP) listens on this UDP port (GigE Vision 2.0, section 7).
constexpr std::uint16_t kGvcpPort = 3956;

// Aravis binds its fake camera's sockets with SO_REUSEADDR, so a second one would start and
// answer beside the first; a plain bind tells whether the port is already served at `address`.
bool isIpv4Address(const std::string& text) {
  in_addr parsed{};
  return inet_pton(AF_INET, text.c_str(), &parsed) == 1;
}

bool gvcpPortInUse(const std::string& address) {
  if (!isIpv4Address(address)) return false;  // an interface name: cannot be probed
  sockaddr_in where{};
  where.sin_family = AF_INET;
  where.sin_port = htons(kGvcpPort);
  inet_pton(AF_INET, address.c_str(), &where.sin_addr);
  const int probe = socket(AF_INET, SOCK_DGRAM | SOCK_CLOEXEC, 0);
  if (probe < 0) return false;
  const bool in_use = bind(probe, reinterpret_cast<const sockaddr*>(&where), sizeof where) != 0 &&
                      errno == EADDRINUSE;
  close(probe);
  return in_use;
}

}  // namespace

struct FakeGvCamera::State {
  FakeGvCameraOptions options;
  SimulatedScene scene;
  aravis::GObjectPtr<ArvGvFakeCamera> camera;
  std::atomic<std::uint64_t> frames_rendered{0};

  // ArvFakeCameraFillPattern: runs on the fake camera's thread for every frame it sends.
  static void fill(ArvBuffer* buffer, void* self, guint32 exposure_time_us, guint32 gain_raw,
                   ArvPixelFormat pixel_format) {
    static_cast<State*>(self)->render(buffer, exposure_time_us, gain_raw, pixel_format);
  }

  // The frame, then the rest of its exposure time (at most kMaxTakenExposure): the thread sends
  // it on return.
  void render(ArvBuffer* buffer, guint32 exposure_time_us, guint32 gain_raw,
              ArvPixelFormat pixel_format) {
    const auto triggered = std::chrono::steady_clock::now();
    renderFrame(buffer, exposure_time_us, gain_raw, pixel_format);
    std::this_thread::sleep_until(
        triggered + std::min<std::chrono::microseconds>(std::chrono::microseconds(exposure_time_us),
                                                        kMaxTakenExposure));
  }

  void renderFrame(ArvBuffer* buffer, guint32 exposure_time_us, guint32 gain_raw,
                   ArvPixelFormat pixel_format) {
    const int width = arv_buffer_get_image_width(buffer);
    const int height = arv_buffer_get_image_height(buffer);
    const bool mono16 = pixel_format == ARV_PIXEL_FORMAT_MONO_16;
    if (!scene.true_luminance_cd_m2.sameSize(width, height) ||
        (!mono16 && pixel_format != ARV_PIXEL_FORMAT_MONO_8)) {
      return;  // only the scene's size in Mono16 / Mono8: anything else stays as it was
    }
    const std::vector<std::uint8_t>& bytes = frameBytes(exposure_time_us, gain_raw, mono16);
    // Fits: Aravis calls the fill pattern only when the buffer holds the current payload
    // (arv_fake_camera_fill_buffer: SIZE_MISMATCH otherwise), and for Mono8 / Mono16 at the
    // scene's size that payload is exactly these bytes.
    std::memcpy(const_cast<void*>(arv_buffer_get_data(buffer, nullptr)), bytes.data(),
                bytes.size());
  }

  // The bytes of a frame at this exposure and gain: rendered with fresh noise, or with
  // reuse_frames the first rendering again (for benchmarks of everything but the simulator).
  const std::vector<std::uint8_t>& frameBytes(guint32 exposure_time_us, guint32 gain_raw,
                                              bool mono16) {
    const auto key = std::make_tuple(exposure_time_us, gain_raw, mono16);
    if (const auto cached = cache.find(key); cached != cache.end()) return cached->second;
    const FrameSpec spec =
        simulatedFrameSpec(options.scene, std::max<guint32>(exposure_time_us, 1), gain_raw);
    const RawFrame frame =
        exposeFrame(scene.true_luminance_cd_m2, spec, scene.calibration, options.scene.sensor,
                    simulatedFrameSeed(options.scene.seed, frames_rendered++));
    std::vector<std::uint8_t> bytes(frame.pixelCount() * (mono16 ? 2 : 1));
    const std::uint16_t* values = frame.data();
    for (std::size_t i = 0; i < frame.pixelCount(); ++i) {
      if (mono16) {
        const auto value = static_cast<std::uint16_t>(values[i] << kMono16Shift);
        std::memcpy(bytes.data() + 2 * i, &value, sizeof value);  // GenICam Mono16: little-endian
      } else {
        // Rounded, not truncated: the scaled calibration then holds without a half-DN bias.
        const int rounded = (values[i] + (1 << (kMono8Shift - 1))) >> kMono8Shift;
        bytes[i] = static_cast<std::uint8_t>(std::min(rounded, kMono8Max));
      }
    }
    if (!options.reuse_frames) {
      scratch = std::move(bytes);
      return scratch;
    }
    if (cache.size() >= kMaxReusedFrames) cache.clear();
    return cache.emplace(key, std::move(bytes)).first->second;
  }

  std::map<std::tuple<guint32, guint32, bool>, std::vector<std::uint8_t>> cache;
  std::vector<std::uint8_t> scratch;
};

SimulationOptions fakeCameraScene() {
  constexpr int kWidth = 640, kHeight = 512;
  constexpr double kFieldOfViewDeg = 20.0;
  SimulationOptions scene;
  scene.width = kWidth;
  scene.height = kHeight;
  scene.horizontal_fov_deg = kFieldOfViewDeg;
  return scene;
}

Status FakeGvCameraOptions::validate() const {
  // GigE Vision bootstrap register "Serial number": 16 bytes, NUL-terminated.
  constexpr std::size_t kMaxSerialLength = 15;
  if (serial.empty() || serial.size() > kMaxSerialLength) {
    return badInput("fake-camera: --serial must be 1 to 15 characters (GigE Vision's field)");
  }
  if (interface_address.empty()) return badInput("fake-camera: --interface must not be empty");
  if (!(packet_loss >= 0 && packet_loss < 1)) {
    return badInput("fake-camera: --packet-loss must be in [0, 1)");
  }
  if (!(trigger_poll_hz > 0 && trigger_poll_hz <= 10'000)) {
    return badInput("fake-camera: the trigger poll rate must be in (0, 10000] Hz");
  }
  if (scene.width > ARV_FAKE_CAMERA_SENSOR_WIDTH || scene.height > ARV_FAKE_CAMERA_SENSOR_HEIGHT) {
    return badInput(fmt::format("fake-camera: --size is limited to {}x{} (Aravis's fake sensor)",
                                ARV_FAKE_CAMERA_SENSOR_WIDTH, ARV_FAKE_CAMERA_SENSOR_HEIGHT));
  }
  return scene.validate();
}

FakeGvCamera::FakeGvCamera(std::unique_ptr<State> state) : state_(std::move(state)) {}

FakeGvCamera::~FakeGvCamera() {
  if (state_ && state_->camera) {
    // Stop the thread (unref) before the fill pattern's data goes.
    state_->camera.reset();
  }
}

Result<std::unique_ptr<FakeGvCamera>> FakeGvCamera::start(const FakeGvCameraOptions& options) {
  GLARECAM_CHECK(options.validate());
  auto state = std::make_unique<State>();
  state->options = options;
  if (gvcpPortInUse(options.interface_address)) {
    return hardwareError(fmt::format(
        "fake-camera: UDP port {} on {} is already in use (another GigE Vision fake camera?)",
        kGvcpPort, options.interface_address));
  }
  GLARECAM_ASSIGN(state->scene, renderSimulatedScene(options.scene));
  state->camera.reset(
      arv_gv_fake_camera_new(options.interface_address.c_str(), options.serial.c_str()));
  if (!state->camera || !arv_gv_fake_camera_is_running(state->camera.get())) {
    return hardwareError(fmt::format(
        "fake-camera: cannot serve GigE Vision on {} (no such interface, or another GigE Vision "
        "device already uses UDP port 3956 there)",
        options.interface_address));
  }
  ArvFakeCamera* fake = arv_gv_fake_camera_get_fake_camera(state->camera.get());
  arv_fake_camera_write_register(fake, ARV_FAKE_CAMERA_REGISTER_WIDTH,
                                 static_cast<guint32>(options.scene.width));
  arv_fake_camera_write_register(fake, ARV_FAKE_CAMERA_REGISTER_HEIGHT,
                                 static_cast<guint32>(options.scene.height));
  arv_fake_camera_set_trigger_frequency(fake, options.trigger_poll_hz);
  g_object_set(state->camera.get(), "gvsp-lost-ratio", options.packet_loss, nullptr);
  arv_fake_camera_set_fill_pattern(fake, &State::fill, state.get());
  return std::unique_ptr<FakeGvCamera>(new FakeGvCamera(std::move(state)));
}

std::string FakeGvCamera::uri() const {
  // By address, not by serial: discovery can find a loopback camera through another interface
  // (broadcasts loop back), and its stream would then be sent where it cannot arrive.
  const std::string& where = state_->options.interface_address;
  return "aravis:" + (isIpv4Address(where) ? where : state_->options.serial);
}

const SimulatedScene& FakeGvCamera::scene() const { return state_->scene; }

Result<Calibration> FakeGvCamera::calibration(std::string_view pixel_format) const {
  // A GigE Vision client cannot know the simulated lens's ND filter: it is folded into K, so that
  // frames recorded with the default transmission of 1 read true luminance.
  Calibration base = state_->scene.calibration;
  base.luminance_factor /= state_->options.scene.nd_transmission;
  if (pixel_format == "Mono16") return scaledCalibration(base, std::ldexp(1.0, kMono16Shift));
  if (pixel_format == "Mono8") return scaledCalibration(base, std::ldexp(1.0, -kMono8Shift));
  return badInput(fmt::format("fake-camera: no calibration for pixel format '{}' (Mono16, Mono8)",
                              pixel_format));
}

Status writeFakeCameraFiles(const FakeGvCamera& camera, const std::filesystem::path& directory,
                            double alpha_deg) {
  GLARECAM_CHECK(ensureDirectory(directory));
  for (const auto& [format, file] : {std::pair{"Mono16", "fake-camera-mono16.json"},
                                     std::pair{"Mono8", "fake-camera-mono8.json"}}) {
    Calibration calibration;
    GLARECAM_ASSIGN(calibration, camera.calibration(format));
    GLARECAM_CHECK(writeFileAtomic(directory / file, jsonText(toJson(calibration))));
  }
  return writeFileAtomic(directory / "fake-camera-truth.json",
                         jsonText(sceneTruthJson(camera.scene(), alpha_deg)));
}

}  // namespace glarecam::capture
