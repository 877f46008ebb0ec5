// A camera as the bracketer sees it: one interface over every backend (Aravis, libcamera, V4L2,
// the simulator). A backend lists the cameras it can see and opens one by id; the Camera owns its
// device until destroyed. capture() takes a whole bracket, so a backend can pipeline the frames
// and match each one to its request (libcamera by the ExposureTime in the request metadata, V4L2
// by dropping frames until the control took effect), and returns the exposure and gain the camera
// actually applied: cameras round them, and the manifest must record what was used.
//
// The base class owns the contract (style.md, habit 3): capture() is public and not virtual. It
// refuses a request the camera cannot take (not finite, outside limits(), a gain the camera does
// not have), calls the backend's protected doCapture(), checks that one frame came back per
// request, and turns an exception into an Error. Every error names the camera's URI. Backends
// never see an unchecked request, and a caller never sees a short bracket.
// Hardware libraries are included only by each backend's .cpp; this header stays portable.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "core/error.h"
#include "core/image.h"
#include "core/stack_manifest.h"

namespace glarecam::capture {

// The lens and filter in front of the sensor, when the backend knows them (the simulator does;
// real cameras do not, and the capture's --f-number / --nd-transmission say).
struct CameraOptics {
  std::optional<double> f_number;
  std::optional<double> nd_transmission;
};

struct CameraInfo {
  std::string uri;      // what `glarecam capture --camera` accepts, e.g. "aravis:GV01"
  std::string backend;  // "aravis", "libcamera", "v4l2", "sim"
  std::string vendor;
  std::string model;
  std::string serial;
  std::string detail;  // transport, address, device node
  CameraOptics optics;
  // The calibration of a camera that knows its own (factory-calibrated cameras, the simulator);
  // otherwise the capture's --calibration supplies it.
  std::optional<Calibration> calibration{};
};

struct CameraLimits {
  double min_exposure_us = 0;
  double max_exposure_us = 0;
  double exposure_step_us = 1;  // resolution the camera rounds to
  double min_gain_db = 0;
  double max_gain_db = 0;
};

// What the frames hold: the GenICam PixelFormat name (Mono8, Mono12, Mono16) and the number of
// significant bits of each value, which the stack's PNGs keep (8 or 16 bits per file).
struct SensorFormat {
  std::string pixel_format;
  int width = 0;
  int height = 0;
  int bits_per_pixel = 16;  // 8 or 16 as stored; values use up to this many bits
};

struct ExposureRequest {
  double exposure_us = 0;
  double gain_db = 0;
};

struct CapturedFrame {
  RawFrame image;
  double exposure_us = 0;  // as applied (read back or from the frame's metadata)
  double gain_db = 0;      // as applied
  // The camera's own clock (GenICam timestamp, V4L2 / libcamera buffer time); the simulator's
  // runs as a camera's would (sim_camera.h).
  std::uint64_t timestamp_ns = 0;
  int retries = 0;  // incomplete or stale frames discarded before this one
};

// Options every backend understands; the ones a backend has no use for are ignored.
struct CameraOptions {
  std::optional<std::string> pixel_format;  // GenICam name; default: the deepest mono format
  int max_frame_retries = 5;                // incomplete / timed-out frames per request
  double frame_timeout_s = 5.0;             // beyond the exposure time
  // aravis: GenICam features set right after opening, before glarecam's own ("Feature=Value"
  // separated by spaces, arv_device_set_features_from_string; a preset, daemon_config.h).
  std::optional<std::string> genicam_features{};

  bool operator==(const CameraOptions&) const = default;
};

class Camera {
 public:
  virtual ~Camera() = default;
  Camera(const Camera&) = delete;
  Camera& operator=(const Camera&) = delete;

  virtual const CameraInfo& info() const = 0;
  virtual CameraLimits limits() const = 0;
  virtual SensorFormat format() const = 0;

  // One frame per request, in request order; none for no request. kBadInput for a request
  // outside limits(); a camera that was lost (unplugged, powered off) fails every later call
  // (kHardware). Errors name the camera's URI.
  Result<std::vector<CapturedFrame>> capture(std::span<const ExposureRequest> requests);

 protected:
  Camera() = default;

  // The backend's capture, given only requests that passed the checks (at least one). Returns
  // one frame per request; may throw (the base turns the exception into an Error).
  virtual Result<std::vector<CapturedFrame>> doCapture(
      std::span<const ExposureRequest> requests) = 0;
};

// Gigabit Ethernet's 125 MB/s on the wire, of which GigE Vision's stream (GVSP) over 1500-byte
// packets keeps about 95 %: the rig's camera link.
inline constexpr double kGigabitPayloadBytesPerS = 125e6 * 0.95;

// The least time any camera takes for `requests`: each exposure, then its frame of `frame_bytes`
// sent at `link_bytes_per_s` (nothing overlapped). What a bracket's time is measured against.
double bracketFloorS(std::span<const ExposureRequest> requests, double frame_bytes,
                     double link_bytes_per_s = kGigabitPayloadBytesPerS);

// Whether `request` is one `limits` allow: both values finite, the exposure positive and within
// the range (an upper limit of 0: none known), the gain within its range (a camera without
// analogue gain has the range 0…0). kBadInput naming `uri` and the value otherwise.
Status checkRequest(const ExposureRequest& request, const CameraLimits& limits,
                    std::string_view uri);

class CameraBackend {
 public:
  virtual ~CameraBackend() = default;
  virtual std::string_view scheme() const = 0;  // the URI prefix: "aravis"
  // Cameras this backend can see now; an empty list is not an error.
  virtual Result<std::vector<CameraInfo>> list() = 0;
  // Opens the camera `id` (the part of the URI after "scheme:"; empty: the first one found).
  virtual Result<std::unique_ptr<Camera>> open(std::string_view id,
                                               const CameraOptions& options) = 0;
};

}  // namespace glarecam::capture
