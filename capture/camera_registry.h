// Camera URIs ("scheme:id") and the backends that open them: sim, aravis, libcamera, v4l2. A
// backend not built into this binary (its library was missing at build time) is still listed and
// fails with a message saying so, so a URI is never silently misread.
#pragma once

#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "capture/camera.h"
#include "core/error.h"

namespace glarecam::capture {

struct CameraUri {
  std::string scheme;  // "aravis"
  std::string id;      // everything after the first ':' (may be empty: the first camera)
};

// "aravis:GV01" → {aravis, GV01}; a bare known scheme ("sim") is accepted as "sim:".
Result<CameraUri> parseCameraUri(std::string_view uri);

// What a simulated camera (sim:) shows, asked before each bracket: the scene's α (the rig's
// measured α, or the capture's --alpha; nullopt: not known) and the direct normal illuminance of
// the sun that lights it (the clear-sky value for the rig's site and time, or the instrument's;
// nullopt: the URI's illuminance=, else 100 klx). Real cameras look at the real scene and never
// ask; any camera may be given one.
struct SceneState {
  std::optional<double> alpha_deg = std::nullopt;
  std::optional<double> source_illuminance_lx = std::nullopt;
};
using SceneSource = std::function<SceneState()>;

// Every backend, in the order `glarecam cameras` lists them.
std::vector<std::unique_ptr<CameraBackend>> cameraBackends();

// The backend for `scheme`, or a kBadInput error listing the known schemes.
Result<std::unique_ptr<CameraBackend>> cameraBackend(std::string_view scheme,
                                                     const SceneSource& scene_source = {});

// What every backend sees now (`glarecam cameras`): the cameras, and for each backend that could
// not list, why (not built in, no device, a library error).
struct CameraListing {
  struct Backend {
    std::string scheme;
    std::vector<CameraInfo> cameras;
    std::optional<std::string> unavailable;  // why it could not list
  };
  std::vector<Backend> backends;  // in the order `glarecam cameras` lists them
};
CameraListing listCameras();
// {"cameras": [{uri, backend, vendor, model, serial, detail}], "unavailable": {scheme: why}}.
nlohmann::json toJson(const CameraListing& listing);

// Parses `uri` and opens the camera it names.
Result<std::unique_ptr<Camera>> openCamera(std::string_view uri, const CameraOptions& options,
                                           const SceneSource& scene_source = {});

}  // namespace glarecam::capture
