#include "calibration/calibration_file.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>

#include "core/atomic_file.h"
#include "core/json.h"
#include "core/time.h"

namespace glarecam::calibration {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

// Keys of the document that are not calibration values.
const std::string kSchemaKey = "schema", kCameraKey = "camera", kPartsKey = "parts";

// Keys that a stack's calibration block needs, and the part that measures each.
constexpr std::pair<std::string_view, std::string_view> kRequiredKeys[] = {
    {"black_level_dn", "dark"},
    {"saturation_dn", "linearity"},
    {"luminance_factor", "luminance"},
    {"intrinsics", "intrinsics"},
};

std::string stringField(const json& object, const std::string& key) {
  const auto found = object.find(key);
  return found != object.end() && found->is_string() ? found->get<std::string>() : std::string();
}

Result<CameraIdentity> parseCamera(const JsonReader& document) {
  std::optional<JsonReader> camera;
  GLARECAM_ASSIGN(camera, document.optionalObject(kCameraKey));
  if (!camera) return CameraIdentity{};
  CameraIdentity identity;
  for (auto [key, field] : {std::pair{"model", &identity.model},
                            {"serial", &identity.serial},
                            {"pixel_format", &identity.pixel_format}}) {
    std::optional<std::string> text;
    GLARECAM_ASSIGN(text, camera->optionalText(key));
    *field = text.value_or("");
  }
  return identity;
}

Result<PartProvenance> parsePart(const JsonReader& part) {
  GLARECAM_CHECK(part.object());
  PartProvenance provenance;
  GLARECAM_ASSIGN(provenance.measured_at, part.text("measured_at"));
  GLARECAM_ASSIGN(provenance.method, part.text("method"));
  for (auto [key, size] : {std::pair{"width", &provenance.width}, {"height", &provenance.height}}) {
    if (!part.has(key)) continue;
    GLARECAM_ASSIGN(*size, part.integer(key, 1, kMaxImageSide));
  }
  if (provenance.width.has_value() != provenance.height.has_value())
    return part.fail("gives width and height together or neither");
  std::optional<JsonReader> inputs;
  GLARECAM_ASSIGN(inputs, part.optionalArray("inputs"));
  if (inputs) {
    for (std::size_t i = 0; i < inputs->size(); ++i) {
      std::string input;
      GLARECAM_ASSIGN(input, inputs->element(i).text());
      provenance.inputs.push_back(std::move(input));
    }
  }
  return provenance;
}

// Numbers a part wrote must be finite; the block's own rules are checked by parseCalibration.
Status checkNumbers(const json& values, const std::string& where, const std::string& prefix) {
  for (const auto& [key, value] : values.items()) {
    if (value.is_object()) GLARECAM_CHECK(checkNumbers(value, where, prefix + key + "."));
    if (value.is_number() && !std::isfinite(value.get<double>()))
      return badInput(fmt::format("{}: {}{} must be a finite number", where, prefix, key));
  }
  return {};
}

Status copyFileAtomic(const fs::path& source, const fs::path& target) {
  fs::path temporary;
  GLARECAM_ASSIGN(temporary, createTemporarySibling(target));
  std::error_code error;
  fs::copy_file(source, temporary, fs::copy_options::overwrite_existing, error);
  if (error) {
    fs::remove(temporary, error);
    return ioError(fmt::format("{}: cannot copy to {}: {}", source.string(), target.string(),
                               error.message()));
  }
  return commitTemporary(temporary, target);
}

bool isPathKey(std::string_view key) {
  return std::ranges::find(kPathKeys, key) != std::end(kPathKeys);
}

bool known(const std::string& a, const std::string& b) { return !a.empty() && !b.empty(); }

Status mergeCamera(CameraIdentity& into, const CameraIdentity& from, const fs::path& source) {
  const auto merge = [&](std::string& a, const std::string& b, const char* what) -> Status {
    if (known(a, b) && a != b) {
      return badInput(fmt::format("{}: camera {} \"{}\" differs from \"{}\" of the files before it",
                                  source.string(), what, b, a));
    }
    if (a.empty()) a = b;
    return {};
  };
  GLARECAM_CHECK(merge(into.model, from.model, "model"));
  GLARECAM_CHECK(merge(into.serial, from.serial, "serial"));
  return merge(into.pixel_format, from.pixel_format, "pixel_format");
}

// The frame size a part was measured at, and where it was stated, for the merge's check.
struct SizeWitness {
  int width = 0, height = 0;
  std::string what;  // "part flat", "the intrinsics"
  fs::path file;
};

// The sizes a document states: each part's, and the intrinsics' own (which `calibrate
// intrinsics` has always recorded).
std::vector<SizeWitness> statedSizes(const CalibrationDocument& document, const fs::path& file) {
  std::vector<SizeWitness> sizes;
  for (const auto& [name, part] : document.parts) {
    if (part.width && part.height)
      sizes.push_back({*part.width, *part.height, "part " + name, file});
  }
  const auto intrinsics = document.values.find("intrinsics");
  if (intrinsics != document.values.end() && intrinsics->is_object() &&
      intrinsics->contains("width") && intrinsics->contains("height") &&
      (*intrinsics)["width"].is_number_integer() && (*intrinsics)["height"].is_number_integer()) {
    sizes.push_back({(*intrinsics)["width"].get<int>(), (*intrinsics)["height"].get<int>(),
                     "the intrinsics", file});
  }
  return sizes;
}

}  // namespace

CameraIdentity cameraIdentityOf(const StackManifest& manifest) {
  const auto camera = manifest.source.find(kCameraKey);
  if (camera == manifest.source.end() || !camera->is_object()) return {};
  return {.model = stringField(*camera, "model"),
          .serial = stringField(*camera, "serial"),
          .pixel_format = stringField(*camera, "pixel_format")};
}

Result<CalibrationDocument> parseCalibrationDocument(const json& document,
                                                     const std::string& where) {
  const JsonReader fields(document, where);
  GLARECAM_CHECK(fields.schema(kCalibrationSchema, "a calibration file"));
  CalibrationDocument parsed;
  GLARECAM_ASSIGN(parsed.camera, parseCamera(fields));
  std::optional<JsonReader> parts;
  GLARECAM_ASSIGN(parts, fields.optionalObject(kPartsKey));
  if (parts) {
    for (const auto& [name, part] : parts->value().items()) {
      JsonReader reader;
      GLARECAM_ASSIGN(reader, parts->member(name));
      GLARECAM_ASSIGN(parsed.parts[name], parsePart(reader));
    }
  }
  for (const auto& [key, value] : document.items()) {
    if (key != kSchemaKey && key != kCameraKey && key != kPartsKey) parsed.values[key] = value;
  }
  GLARECAM_CHECK(checkNumbers(parsed.values, where, ""));
  for (std::string_view key : kPathKeys) {
    const auto path = parsed.values.find(std::string(key));
    if (path != parsed.values.end() &&
        (!path->is_string() || !isContainedRelativePath(path->get<std::string>()))) {
      return badInput(fmt::format(
          "{}: {} must be a relative path inside the calibration's directory", where, key));
    }
  }
  return parsed;
}

Result<CalibrationDocument> readCalibrationDocument(const fs::path& path) {
  json document;
  GLARECAM_ASSIGN(document, readJsonFile(path.string()));
  return parseCalibrationDocument(document, path.string());
}

json toJson(const CalibrationDocument& document) {
  json out = {{kSchemaKey, std::string(kCalibrationSchema)}};
  json camera = json::object();
  if (!document.camera.model.empty()) camera["model"] = document.camera.model;
  if (!document.camera.serial.empty()) camera["serial"] = document.camera.serial;
  if (!document.camera.pixel_format.empty()) camera["pixel_format"] = document.camera.pixel_format;
  out[kCameraKey] = camera;
  for (const auto& [key, value] : document.values.items()) out[key] = value;
  json parts = json::object();
  for (const auto& [name, part] : document.parts) {
    parts[name] = {
        {"measured_at", part.measured_at}, {"method", part.method}, {"inputs", part.inputs}};
    if (part.width && part.height) {
      parts[name]["width"] = *part.width;
      parts[name]["height"] = *part.height;
    }
  }
  out[kPartsKey] = parts;
  return out;
}

Status writeCalibrationDocument(const fs::path& path, const CalibrationDocument& document) {
  return writeFileAtomic(path, jsonText(toJson(document)));
}

Result<CalibrationDocument> mergeCalibrationDocuments(
    std::span<const CalibrationDocument> documents, std::span<const fs::path> files,
    std::vector<std::string>& warnings) {
  CalibrationDocument merged;
  std::optional<SizeWitness> first_size;
  for (std::size_t i = 0; i < documents.size(); ++i) {
    const CalibrationDocument& document = documents[i];
    const fs::path directory = files[i].parent_path();
    GLARECAM_CHECK(mergeCamera(merged.camera, document.camera, files[i]));
    // A flat field or intrinsics of another size than the frames would be wrong for every stack.
    for (SizeWitness& size : statedSizes(document, files[i])) {
      if (!first_size)
        first_size = std::move(size);
      else if (size.width != first_size->width || size.height != first_size->height)
        return badInput(fmt::format(
            "{}: {} was measured at {}x{}, but {} of {} at {}x{}: make every part at the "
            "camera's capture size",
            files[i].string(), size.what, size.width, size.height, first_size->what,
            first_size->file.string(), first_size->width, first_size->height));
    }
    for (const auto& [key, value] : document.values.items()) {
      json moved = value;
      if (isPathKey(key)) moved = fs::absolute(directory / value.get<std::string>()).string();
      if (merged.values.contains(key) && merged.values[key] != moved)
        warnings.push_back(fmt::format("{} replaced by {}'s", key, files[i].string()));
      merged.values[key] = std::move(moved);
    }
    for (const auto& [name, part] : document.parts) {
      if (merged.parts.contains(name))
        warnings.push_back(fmt::format("part {} replaced by {}'s", name, files[i].string()));
      merged.parts[name] = part;
    }
  }
  return merged;
}

Status attachFiles(CalibrationDocument& document, const fs::path& output_directory) {
  for (std::string_view key : kPathKeys) {
    const auto value = document.values.find(std::string(key));
    if (value == document.values.end() || !fs::path(value->get<std::string>()).is_absolute())
      continue;
    const fs::path source = value->get<std::string>();
    const fs::path target = output_directory / source.filename();
    std::error_code error;
    if (!fs::equivalent(source, target, error)) GLARECAM_CHECK(copyFileAtomic(source, target));
    *value = source.filename().string();
  }
  return {};
}

Status checkCalibrationUse(const Calibration& calibration, const StackManifest& manifest,
                           const std::string& where, const CalibrationUseOptions& options,
                           std::vector<std::string>& warnings) {
  const json& source = calibration.source;
  const std::string calibrated_serial =
      source.contains(kCameraKey) && source[kCameraKey].is_object()
          ? stringField(source[kCameraKey], "serial")
          : std::string();
  const std::string stack_serial = cameraIdentityOf(manifest).serial;
  if (known(calibrated_serial, stack_serial) && calibrated_serial != stack_serial) {
    const std::string message =
        fmt::format("{}: made for camera serial {}, but the stack was taken with serial {}", where,
                    calibrated_serial, stack_serial);
    if (!options.force) return badInput(message + " (--force-calibration uses it anyway)");
    warnings.push_back(message + "; used as forced");
  }
  if (!source.contains(kPartsKey) || !source[kPartsKey].is_object()) return {};
  for (const auto& [name, part] : source[kPartsKey].items()) {
    const auto measured =
        part.is_object() ? isoDayOf(stringField(part, "measured_at")) : std::nullopt;
    if (!measured) continue;
    const std::chrono::sys_days today = options.today == std::chrono::sys_days{}
                                            ? std::chrono::floor<std::chrono::days>(utcNow())
                                            : options.today;
    const auto age_days = (today - *measured).count();
    if (age_days > options.max_age_days) {
      warnings.push_back(
          fmt::format("{}: part {} was measured {} days ago (more than {:g}): "
                      "recalibrate (docs/calibration.md)",
                      where, name, age_days, options.max_age_days));
    }
  }
  return {};
}

Result<Calibration> calibrationBlock(const CalibrationDocument& document,
                                     const std::string& where) {
  std::vector<std::string> missing;
  for (const auto& [key, part] : kRequiredKeys) {
    if (!document.values.contains(std::string(key)))
      missing.push_back(fmt::format("{} (calibrate {})", key, part));
  }
  if (!missing.empty()) {
    std::string list;
    for (const std::string& m : missing) list += (list.empty() ? "" : ", ") + m;
    return badInput(fmt::format(
        "{}: the calibration is incomplete: no {}; measure those parts and combine the files "
        "with `glarecam calibrate merge`",
        where, list));
  }
  return parseCalibration(toJson(document), where);
}

}  // namespace glarecam::calibration
