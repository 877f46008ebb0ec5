#include "calibration/prior_calibration.h"

#include <fmt/format.h>

#include <string_view>
#include <utility>

#include "core/json.h"

namespace glarecam::calibration {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

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

// The first stack's own calibration block, its flat field's path made absolute.
json stackValues(const Stack& stack) {
  if (stack.calibration_origin == kNoCalibration) return json::object();
  json values = stack.calibration.source;
  if (values.contains("flat_field") && values["flat_field"].is_string()) {
    const fs::path base = stack.calibration_origin == "inline"
                              ? stack.directory
                              : (stack.directory / stack.calibration_origin).parent_path();
    values["flat_field"] = fs::absolute(base / values["flat_field"].get<std::string>()).string();
  }
  return values;
}

}  // namespace

PriorCalibration priorCalibrationOf(json values) {
  // The values come from a calibration already read; one a prior cannot use is no prior.
  const auto number = [](const JsonReader& block, const char* key) {
    return block.optionalNumber(key).value_or(std::nullopt);
  };
  const JsonReader fields(values, "the calibration");
  PriorCalibration prior;
  prior.black_level_dn = number(fields, "black_level_dn");
  prior.saturation_dn = number(fields, "saturation_dn");
  if (const auto intrinsics = fields.optionalMember("intrinsics").value_or(std::nullopt)) {
    prior.principal_x_px = number(*intrinsics, "cx");
    prior.principal_y_px = number(*intrinsics, "cy");
  }
  prior.reference_f_number = number(fields, "reference_f_number");
  prior.luminance_factor = number(fields, "luminance_factor");
  prior.luminance_factor_u = number(fields, "luminance_factor_u");
  prior.flat_field = fields.optionalText("flat_field").value_or(std::nullopt);
  prior.source = std::move(values);
  return prior;
}

Result<PriorCalibration> readPriorCalibration(std::span<const std::string> calibration_files,
                                              const CalibrationInputs& inputs) {
  if (calibration_files.empty()) return priorCalibrationOf(stackValues(inputs.stacks.front()));
  json merged = json::object();
  for (const std::string& file : calibration_files) {
    json values;
    GLARECAM_ASSIGN(values, fileValues(file));
    for (const auto& [key, value] : values.items()) merged[key] = value;
  }
  return priorCalibrationOf(std::move(merged));
}

Result<SensorLevels> sensorLevels(const PriorCalibration& prior, const CalibrationInputs& inputs,
                                  const std::string& procedure) {
  if (!prior.black_level_dn) {
    return badInput(fmt::format(
        "calibrate {}: the black level is unknown: measure it first (glarecam calibrate dark) "
        "and give that file with --calibration",
        procedure));
  }
  const SensorLevels levels{.black_level_dn = *prior.black_level_dn,
                            .saturation_dn = prior.saturation_dn.value_or(formatMaxDn(inputs))};
  if (!(levels.black_level_dn >= 0 && levels.black_level_dn < levels.saturation_dn)) {
    return badInput(fmt::format("calibrate {}: black level {:g} DN must be in [0, saturation {:g})",
                                procedure, levels.black_level_dn, levels.saturation_dn));
  }
  return levels;
}

Result<Calibration> mergeCalibration(const PriorCalibration& prior, const SensorLevels& levels) {
  json block = prior.source;
  block["black_level_dn"] = levels.black_level_dn;
  block["saturation_dn"] = levels.saturation_dn;
  block["luminance_factor"] = 1.0;  // placeholders: the merge needs them, the result does not
  if (!block.contains("intrinsics"))
    block["intrinsics"] = {{"fx", 1}, {"fy", 1}, {"cx", 1}, {"cy", 1}};
  // Absolute paths: the block's parser takes contained paths only. The procedures measure above
  // the black level; the flat field comes back below.
  for (std::string_view key : kPathKeys) block.erase(std::string(key));
  Calibration calibration;
  GLARECAM_ASSIGN(calibration, parseCalibration(block, "--calibration"));
  if (prior.flat_field) calibration.flat_field = prior.flat_field->string();
  return calibration;
}

}  // namespace glarecam::calibration
