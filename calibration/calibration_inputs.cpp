#include "calibration/calibration_inputs.h"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>

#include "core/progress.h"

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

// The values of a --calibration file, absolute paths; a bare block or a calibration/1 file.
Result<json> fileValues(const fs::path& path) {
  json document;
  GLARECAM_ASSIGN(document, readJsonFile(path.string()));
  json values;
  if (document.is_object() && document.contains("schema")) {
    CalibrationDocument parsed;
    GLARECAM_ASSIGN(parsed, parseCalibrationDocument(document, path.string()));
    values = std::move(parsed.values);
  } else {
    Calibration block;
    GLARECAM_ASSIGN(block, parseCalibration(document, path.string()));
    values = block.source;
  }
  for (std::string_view key : kPathKeys) {
    const std::string name(key);
    if (values.contains(name) && values[name].is_string())
      values[name] = fs::absolute(path.parent_path() / values[name].get<std::string>()).string();
  }
  return values;
}

std::string nowIso() {
  const std::time_t now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  std::tm utc{};
  gmtime_r(&now, &utc);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &utc);
  return text;
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
    if (inputs.stack_paths.empty()) inputs.camera = cameraIdentityOf(stack.manifest);
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

Result<json> priorValues(std::span<const std::string> calibration_files,
                         const CalibrationInputs& inputs) {
  json prior = json::object();
  for (const std::string& file : calibration_files) {
    json values;
    GLARECAM_ASSIGN(values, fileValues(file));
    for (const auto& [key, value] : values.items()) prior[key] = value;
  }
  if (!calibration_files.empty()) return prior;
  const Stack& first = inputs.stacks.front();
  if (first.calibration_origin == kNoCalibration) return prior;
  prior = first.calibration.source;
  if (prior.contains("flat_field") && prior["flat_field"].is_string()) {
    const fs::path base = first.calibration_origin == "inline"
                              ? first.directory
                              : (first.directory / first.calibration_origin).parent_path();
    prior["flat_field"] = fs::absolute(base / prior["flat_field"].get<std::string>()).string();
  }
  return prior;
}

Result<SensorLevels> sensorLevels(const json& prior, const CalibrationInputs& inputs,
                                  const std::string& procedure) {
  if (!prior.contains("black_level_dn") || !prior["black_level_dn"].is_number()) {
    return badInput(fmt::format(
        "calibrate {}: the black level is unknown: measure it first (glarecam calibrate dark) "
        "and give that file with --calibration",
        procedure));
  }
  SensorLevels levels{.black_level_dn = prior["black_level_dn"].get<double>(),
                      .saturation_dn = formatMaxDn(inputs)};
  if (prior.contains("saturation_dn") && prior["saturation_dn"].is_number())
    levels.saturation_dn = prior["saturation_dn"].get<double>();
  if (!(levels.black_level_dn >= 0 && levels.black_level_dn < levels.saturation_dn)) {
    return badInput(fmt::format("calibrate {}: black level {:g} DN must be in [0, saturation {:g})",
                                procedure, levels.black_level_dn, levels.saturation_dn));
  }
  return levels;
}

Result<Calibration> priorCalibration(const json& prior, const SensorLevels& levels) {
  json block = prior;
  block["black_level_dn"] = levels.black_level_dn;
  block["saturation_dn"] = levels.saturation_dn;
  block["luminance_factor"] = 1.0;  // placeholders: the merge needs them, the result does not
  if (!block.contains("intrinsics"))
    block["intrinsics"] = {{"fx", 1}, {"fy", 1}, {"cx", 1}, {"cy", 1}};
  std::optional<std::string> flat;
  if (block.contains("flat_field")) {
    flat = block["flat_field"].get<std::string>();
    block.erase("flat_field");  // absolute: the block's parser takes contained paths only
  }
  Calibration calibration;
  GLARECAM_ASSIGN(calibration, parseCalibration(block, "--calibration"));
  calibration.flat_field = flat;
  return calibration;
}

CalibrationDocument partDocument(const CalibrationInputs& inputs, const std::string& part,
                                 const std::string& method, json values) {
  CalibrationDocument document;
  document.camera = inputs.camera;
  document.values = std::move(values);
  document.parts[part] = {
      .measured_at = inputs.latest_capture.empty() ? nowIso() : inputs.latest_capture,
      .method = method,
      .inputs = inputs.stack_paths};
  return document;
}

fs::path companionFile(const fs::path& out, const std::string& suffix) {
  return out.parent_path() / (out.stem().string() + suffix);
}

}  // namespace glarecam::calibration
