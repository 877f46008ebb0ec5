// glarecam cameras: what every camera backend sees (capture/camera_registry.h; docs/cameras.md).
#include <cstdio>
#include <memory>

#include "apps/glarecam/commands.h"
#include "capture/camera_registry.h"
#include "core/json.h"
#include "core/stack_manifest.h"

namespace glarecam::apps {
namespace {

Status runCameras(bool json) {
  const capture::CameraListing listing = capture::listCameras();
  if (json) {
    std::fputs(jsonText(capture::toJson(listing)).c_str(), stdout);
    return {};
  }
  for (const capture::CameraListing::Backend& backend : listing.backends) {
    if (backend.unavailable)
      std::printf("%s: %s\n", backend.scheme.c_str(), backend.unavailable->c_str());
    for (const capture::CameraInfo& camera : backend.cameras)
      std::printf("%-28s %s %s (serial %s) %s\n", camera.uri.c_str(), camera.vendor.c_str(),
                  camera.model.c_str(), camera.serial.empty() ? "-" : camera.serial.c_str(),
                  camera.detail.c_str());
  }
  return {};
}

}  // namespace

void addCamerasCommand(CLI::App& app, Action& action) {
  auto json = std::make_shared<bool>(false);
  CLI::App* sub =
      app.add_subcommand("cameras",
                         "List the cameras every backend can see: sim, aravis, libcamera, v4l2 "
                         "(docs/cameras.md)");
  sub->add_flag("--json", *json, "print JSON instead of a table");
  sub->callback([json, &action] { action = [json] { return runCameras(*json); }; });
}

}  // namespace glarecam::apps
