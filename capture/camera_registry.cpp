#include "capture/camera_registry.h"

#include <fmt/format.h>

#include <array>
#include <functional>

#include "capture/sim/sim_camera.h"
#include "capture/v4l2/v4l2_backend.h"
#include "core/build_config.h"
#if GLARECAM_WITH_ARAVIS
#include "capture/aravis/aravis_backend.h"
#endif
#if GLARECAM_WITH_LIBCAMERA
#include "capture/libcamera/libcamera_backend.h"
#endif

namespace glarecam::capture {
namespace {

// Stands in for a backend whose library was not found when this binary was built.
class UnavailableBackend final : public CameraBackend {
 public:
  UnavailableBackend(std::string_view scheme, std::string_view library)
      : scheme_(scheme),
        reason_(fmt::format("{}: camera support is not built into this glarecam ({} was not found "
                            "at build time; install it and rebuild)",
                            scheme, library)) {}
  std::string_view scheme() const override { return scheme_; }
  Result<std::vector<CameraInfo>> list() override { return hardwareError(reason_); }
  Result<std::unique_ptr<Camera>> open(std::string_view, const CameraOptions&) override {
    return hardwareError(reason_);
  }

 private:
  std::string scheme_;
  std::string reason_;
};

struct BackendEntry {
  std::string_view scheme;
  std::function<std::unique_ptr<CameraBackend>(const SceneSource&)> make;
};

const std::array<BackendEntry, 4>& backendEntries() {
  static const std::array<BackendEntry, 4> entries{{
      {"sim", makeSimCameraBackend},
#if GLARECAM_WITH_ARAVIS
      {"aravis", [](const SceneSource&) { return makeAravisBackend(); }},
#else
      {"aravis",
       [](const SceneSource&) {
         return std::make_unique<UnavailableBackend>("aravis", "Aravis 0.8");
       }},
#endif
#if GLARECAM_WITH_LIBCAMERA
      {"libcamera", [](const SceneSource&) { return makeLibcameraBackend(); }},
#else
      {"libcamera",
       [](const SceneSource&) {
         return std::make_unique<UnavailableBackend>("libcamera", "libcamera");
       }},
#endif
      {"v4l2", [](const SceneSource&) { return makeV4l2Backend(); }},
  }};
  return entries;
}

std::string knownSchemes() {
  std::string names;
  for (const auto& entry : backendEntries()) {
    names += (names.empty() ? "" : ", ") + std::string(entry.scheme) + ":";
  }
  return names;
}

}  // namespace

Result<CameraUri> parseCameraUri(std::string_view uri) {
  const auto colon = uri.find(':');
  CameraUri parsed{std::string(uri.substr(0, colon)),
                   colon == std::string_view::npos ? "" : std::string(uri.substr(colon + 1))};
  for (const auto& entry : backendEntries()) {
    if (entry.scheme == parsed.scheme) return parsed;
  }
  return badInput(
      fmt::format("camera URI '{}': unknown backend (expected one of {})", uri, knownSchemes()));
}

std::vector<std::unique_ptr<CameraBackend>> cameraBackends() {
  std::vector<std::unique_ptr<CameraBackend>> backends;
  for (const auto& entry : backendEntries()) backends.push_back(entry.make({}));
  return backends;
}

Result<std::unique_ptr<CameraBackend>> cameraBackend(std::string_view scheme,
                                                     const SceneSource& scene_source) {
  for (const auto& entry : backendEntries()) {
    if (entry.scheme == scheme) return entry.make(scene_source);
  }
  return badInput(
      fmt::format("unknown camera backend '{}' (expected one of {})", scheme, knownSchemes()));
}

CameraListing listCameras() {
  CameraListing listing;
  for (const auto& backend : cameraBackends()) {
    CameraListing::Backend& listed = listing.backends.emplace_back();
    listed.scheme = std::string(backend->scheme());
    auto cameras = backend->list();
    if (cameras)
      listed.cameras = std::move(*cameras);
    else
      listed.unavailable = cameras.error().message;
  }
  return listing;
}

nlohmann::json toJson(const CameraListing& listing) {
  nlohmann::json document = {{"cameras", nlohmann::json::array()},
                             {"unavailable", nlohmann::json::object()}};
  for (const CameraListing::Backend& backend : listing.backends) {
    if (backend.unavailable) document["unavailable"][backend.scheme] = *backend.unavailable;
    for (const CameraInfo& camera : backend.cameras)
      document["cameras"].push_back({{"uri", camera.uri},
                                     {"backend", camera.backend},
                                     {"vendor", camera.vendor},
                                     {"model", camera.model},
                                     {"serial", camera.serial},
                                     {"detail", camera.detail}});
  }
  return document;
}

Result<std::unique_ptr<Camera>> openCamera(std::string_view uri, const CameraOptions& options,
                                           const SceneSource& scene_source) {
  CameraUri parsed;
  GLARECAM_ASSIGN(parsed, parseCameraUri(uri));
  std::unique_ptr<CameraBackend> backend;
  GLARECAM_ASSIGN(backend, cameraBackend(parsed.scheme, scene_source));
  return backend->open(parsed.id, options);
}

}  // namespace glarecam::capture
