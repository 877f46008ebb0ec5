#include "calibration/calibration_inputs.h"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>

#include "core/progress.h"
#include "core/time.h"

namespace glarecam::calibration {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

Status checkSameCamera(const CalibrationInputs& inputs, const Stack& stack,
                       const std::string& path) {
  const CameraIdentity camera = cameraIdentityOf(stack.manifest);
  if (!camera.serial.empty() && !inputs.camera.serial.empty() &&
      camera.serial != inputs.camera.serial) {
    return badInput(fmt::format("{}: camera serial {} differs from {} of {}", path, camera.serial,
                                inputs.camera.serial, inputs.stack_paths.front()));
  }
  const RawFrame& first = inputs.frames.front().frame;
  if (!stack.frames.front().sameSize(first.width(), first.height())) {
    return badInput(fmt::format("{}: frames are {}x{}, those of {} {}x{}", path,
                                stack.frames.front().width(), stack.frames.front().height(),
                                inputs.stack_paths.front(), first.width(), first.height()));
  }
  return {};
}

}  // namespace

double formatMaxDn(const CalibrationInputs& inputs) {
  const std::string& format = inputs.camera.pixel_format;
  int bits = 0;
  if (format.starts_with("Mono") && std::sscanf(format.c_str() + 4, "%d", &bits) == 1 && bits > 0 &&
      bits <= 16)
    return std::ldexp(1.0, bits) - 1;
  int depth = 8;
  for (const InputFrame& frame : inputs.frames) depth = std::max(depth, frame.bit_depth);
  return std::ldexp(1.0, depth) - 1;
}

Result<CalibrationInputs> readCalibrationInputs(std::span<const std::string> stack_paths,
                                                bool show_progress) {
  if (stack_paths.empty()) return badInput("no stacks given");
  CalibrationInputs inputs;
  Progress progress("read stacks", static_cast<int>(stack_paths.size()), show_progress);
  StackReadOptions read_options;
  read_options.require_calibration = false;  // targets need none: the procedures make it
  for (const std::string& path : stack_paths) {
    Stack stack;
    GLARECAM_ASSIGN(stack, readStack(path, read_options));
    if (!inputs.frames.empty()) GLARECAM_CHECK(checkSameCamera(inputs, stack, path));
    if (inputs.stack_paths.empty()) {
      inputs.camera = cameraIdentityOf(stack.manifest);
      inputs.width = stack.frames.front().width();
      inputs.height = stack.frames.front().height();
    }
    inputs.stack_paths.push_back(path);
    for (std::size_t i = 0; i < stack.frames.size(); ++i) {
      inputs.frames.push_back({.frame = std::move(stack.frames[i]),
                               .spec = stack.manifest.frames[i],
                               .name = (fs::path(path) / stack.manifest.frames[i].file).string(),
                               .bit_depth = stack.bit_depths[i],
                               .stack = inputs.stack_paths.size() - 1});
    }
    if (stack.manifest.captured_at && *stack.manifest.captured_at > inputs.latest_capture)
      inputs.latest_capture = *stack.manifest.captured_at;
    stack.frames.clear();  // moved into `frames`: each frame is held once
    inputs.stacks.push_back(std::move(stack));
    progress.advance(path);
  }
  return inputs;
}

CalibrationDocument partDocument(const CalibrationInputs& inputs, const std::string& part,
                                 const std::string& method, json values) {
  CalibrationDocument document;
  document.camera = inputs.camera;
  document.values = std::move(values);
  document.parts[part] = {.measured_at = inputs.latest_capture.empty() ? formatIsoSeconds(utcNow())
                                                                       : inputs.latest_capture,
                          .method = method,
                          .inputs = inputs.stack_paths,
                          .width = inputs.width,
                          .height = inputs.height};
  return document;
}

fs::path companionFile(const fs::path& out, const std::string& suffix) {
  return out.parent_path() / (out.stem().string() + suffix);
}

}  // namespace glarecam::calibration
