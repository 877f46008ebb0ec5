#include "core/stack_manifest.h"

#include <cmath>
#include <filesystem>

#include "core/json.h"

namespace glarecam {
namespace {

using nlohmann::json;

// An image dimension in pixels: a whole number in [1, kMaxImageSide].
Result<std::optional<int>> optionalSize(const JsonReader& fields, std::string_view key) {
  std::optional<double> value;
  GLARECAM_ASSIGN(value, fields.optionalNumber(key));
  if (!value) return std::optional<int>{};
  if (!isImageSidePx(*value))
    return fields.fail(
        key, "must be a whole number of pixels, not " + jsonSnippet(fields.value().at(key)));
  return std::optional<int>(static_cast<int>(*value));
}

// A relative path that stays inside its base directory.
Result<std::optional<std::string>> optionalContainedPath(const JsonReader& fields,
                                                         std::string_view key) {
  auto path = fields.optionalText(key);
  if (path && *path && !isContainedRelativePath(**path)) {
    return fields.fail(key,
                       "\"" + **path + "\" escapes the stack directory (absolute or with \"..\")");
  }
  return path;
}

Result<Intrinsics> parseIntrinsics(const JsonReader& parent) {
  if (!parent.has("intrinsics")) return parent.fail("intrinsics", "is missing (fx, fy, cx, cy)");
  JsonReader fields;
  GLARECAM_ASSIGN(fields, parent.objectMember("intrinsics"));
  Intrinsics intrinsics;
  // "intrinsics that are not finite and positive" are refused (stack-format.md).
  GLARECAM_ASSIGN(intrinsics.fx, fields.positive("fx"));
  GLARECAM_ASSIGN(intrinsics.fy, fields.positive("fy"));
  GLARECAM_ASSIGN(intrinsics.cx, fields.positive("cx"));
  GLARECAM_ASSIGN(intrinsics.cy, fields.positive("cy"));
  GLARECAM_ASSIGN(intrinsics.width, optionalSize(fields, "width"));
  GLARECAM_ASSIGN(intrinsics.height, optionalSize(fields, "height"));
  if (intrinsics.width.has_value() != intrinsics.height.has_value())
    return fields.fail("gives width and height together or neither");
  std::optional<JsonReader> distortion;
  GLARECAM_ASSIGN(distortion, fields.optionalMember("distortion"));
  if (!distortion) return intrinsics;
  if (!distortion->value().is_array() || distortion->size() > intrinsics.distortion.size())
    return distortion->fail("must be an array of at most 5 numbers (k1, k2, p1, p2, k3)");
  for (std::size_t i = 0; i < distortion->size(); ++i)
    GLARECAM_ASSIGN(intrinsics.distortion[i], distortion->element(i).number());
  return intrinsics;
}

Result<std::optional<NoiseModel>> parseNoise(const JsonReader& parent) {
  std::optional<JsonReader> fields;
  GLARECAM_ASSIGN(fields, parent.optionalObject("noise"));
  if (!fields) return std::optional<NoiseModel>{};
  NoiseModel noise;
  GLARECAM_ASSIGN(noise.read_noise_dn, fields->nonNegative("read_noise_dn"));
  GLARECAM_ASSIGN(noise.dn_per_electron, fields->positive("dn_per_electron"));
  return noise;
}

Result<FrameSpec> parseFrame(const JsonReader& fields) {
  GLARECAM_CHECK(fields.object());
  FrameSpec frame;
  frame.source = fields.value();
  std::optional<std::string> file;
  GLARECAM_ASSIGN(file, optionalContainedPath(fields, "file"));
  if (!file || file->empty()) return fields.fail("file", "is missing");
  frame.file = *file;
  GLARECAM_ASSIGN(frame.exposure_us, fields.positive("exposure_us"));
  std::optional<double> gain_db, nd;
  GLARECAM_ASSIGN(gain_db, fields.optionalNumber("gain_db"));
  GLARECAM_ASSIGN(frame.f_number, fields.optionalPositive("f_number"));
  GLARECAM_ASSIGN(nd, fields.optionalNumber("nd_transmission"));
  frame.gain_db = gain_db.value_or(0.0);
  frame.nd_transmission = nd.value_or(1.0);
  if (frame.nd_transmission <= 0 || frame.nd_transmission > 1) {
    return fields.fail("nd_transmission", "must be in (0, 1], not " +
                                              jsonSnippet(fields.value().at("nd_transmission")));
  }
  return frame;
}

}  // namespace

bool isImageSidePx(double value) {
  return value >= 1 && value <= kMaxImageSide && value == std::floor(value);
}

bool isContainedRelativePath(std::string_view relative) {
  std::filesystem::path path(relative);
  if (relative.empty() || path.is_absolute() || path.has_root_name()) return false;
  for (const auto& part : path) {
    if (part == "..") return false;
  }
  return true;
}

Result<Calibration> parseCalibration(const json& block, const std::string& where) {
  const JsonReader fields(block, where, "calibration");
  if (!block.is_object())
    return badInput(where + ": calibration must be an object or a path string");
  Calibration calibration;
  calibration.source = block;
  GLARECAM_ASSIGN(calibration.black_level_dn, fields.nonNegative("black_level_dn"));
  GLARECAM_ASSIGN(calibration.saturation_dn, fields.positive("saturation_dn"));
  GLARECAM_ASSIGN(calibration.luminance_factor, fields.positive("luminance_factor"));
  GLARECAM_ASSIGN(calibration.reference_f_number, fields.optionalPositive("reference_f_number"));
  GLARECAM_ASSIGN(calibration.intrinsics, parseIntrinsics(fields));
  GLARECAM_ASSIGN(calibration.flat_field, optionalContainedPath(fields, "flat_field"));
  GLARECAM_ASSIGN(calibration.dark_frame, optionalContainedPath(fields, "dark_frame"));
  GLARECAM_ASSIGN(calibration.dark_frame_exposure_us,
                  fields.optionalPositive("dark_frame_exposure_us"));
  std::optional<double> dark_gain;
  GLARECAM_ASSIGN(dark_gain, fields.optionalNumber("dark_frame_gain_db"));
  calibration.dark_frame_gain_db = dark_gain.value_or(0.0);
  std::optional<double> dark_current;
  GLARECAM_ASSIGN(dark_current, fields.optionalNumber("dark_current_dn_per_us"));
  calibration.dark_current_dn_per_us = dark_current.value_or(0.0);
  GLARECAM_ASSIGN(calibration.hot_pixels, optionalContainedPath(fields, "hot_pixels"));
  GLARECAM_ASSIGN(calibration.noise, parseNoise(fields));
  if (calibration.black_level_dn >= calibration.saturation_dn) {
    return badInput(where + ": calibration.black_level_dn (" +
                    jsonSnippet(block.at("black_level_dn")) + ") must be below saturation_dn (" +
                    jsonSnippet(block.at("saturation_dn")) + ")");
  }
  return calibration;
}

std::vector<std::pair<std::string, std::string>> calibrationImages(const Calibration& calibration) {
  std::vector<std::pair<std::string, std::string>> images;
  if (calibration.flat_field) images.emplace_back("flat_field", *calibration.flat_field);
  if (calibration.dark_frame) images.emplace_back("dark_frame", *calibration.dark_frame);
  if (calibration.hot_pixels) images.emplace_back("hot_pixels", *calibration.hot_pixels);
  return images;
}

void setCalibrationImage(Calibration& calibration, const std::string& key,
                         const std::string& path) {
  if (key == "flat_field") calibration.flat_field = path;
  if (key == "dark_frame") calibration.dark_frame = path;
  if (key == "hot_pixels") calibration.hot_pixels = path;
  if (calibration.source.is_object()) calibration.source[key] = path;
}

Result<StackManifest> parseManifest(const json& document, const std::string& where) {
  if (!document.is_object()) return badInput(where + ": manifest must be a JSON object");
  const JsonReader fields(document, where);
  GLARECAM_CHECK(fields.schema(kStackSchema, "a stack manifest"));
  StackManifest manifest;
  manifest.source = document;
  GLARECAM_ASSIGN(manifest.id, fields.optionalText("id"));
  GLARECAM_ASSIGN(manifest.captured_at, fields.optionalText("captured_at"));
  GLARECAM_ASSIGN(manifest.alpha_deg,
                  fields.optionalNumberIn("alpha_deg", 0, kMaxStackAlphaDeg, "°"));
  if (fields.has("source")) {
    JsonReader block;
    GLARECAM_ASSIGN(block, fields.member("source"));
    GLARECAM_ASSIGN(manifest.source_illuminance, parseSourceIlluminance(block));
  }
  if (fields.has("calibration")) {
    if (document.at("calibration").is_string()) {
      manifest.calibration_path = document.at("calibration").get<std::string>();
    } else {
      GLARECAM_ASSIGN(manifest.calibration, parseCalibration(document.at("calibration"), where));
    }
  }
  if (!fields.has("frames") || !document.at("frames").is_array())
    return fields.fail("frames", "must be a list of frames");
  JsonReader frames;
  GLARECAM_ASSIGN(frames, fields.member("frames"));
  if (frames.size() == 0) return frames.fail("is empty: a stack needs at least one frame");
  for (std::size_t i = 0; i < frames.size(); ++i) {
    FrameSpec frame;
    GLARECAM_ASSIGN(frame, parseFrame(frames.element(i)));
    manifest.frames.push_back(std::move(frame));
  }
  return manifest;
}

json toJson(const Calibration& calibration) {
  json block = calibration.source.is_object() ? calibration.source : json::object();
  block["black_level_dn"] = calibration.black_level_dn;
  block["saturation_dn"] = calibration.saturation_dn;
  block["luminance_factor"] = calibration.luminance_factor;
  if (calibration.reference_f_number) block["reference_f_number"] = *calibration.reference_f_number;
  const Intrinsics& k = calibration.intrinsics;
  json intrinsics = block.contains("intrinsics") && block["intrinsics"].is_object()
                        ? block["intrinsics"]
                        : json::object();
  intrinsics.update(
      json{{"fx", k.fx}, {"fy", k.fy}, {"cx", k.cx}, {"cy", k.cy}, {"distortion", k.distortion}});
  block["intrinsics"] = intrinsics;
  if (calibration.flat_field) block["flat_field"] = *calibration.flat_field;
  if (calibration.dark_frame) block["dark_frame"] = *calibration.dark_frame;
  if (calibration.dark_frame_exposure_us)
    block["dark_frame_exposure_us"] = *calibration.dark_frame_exposure_us;
  if (calibration.dark_frame && calibration.dark_frame_gain_db != 0)
    block["dark_frame_gain_db"] = calibration.dark_frame_gain_db;
  if (calibration.dark_current_dn_per_us != 0)
    block["dark_current_dn_per_us"] = calibration.dark_current_dn_per_us;
  if (calibration.hot_pixels) block["hot_pixels"] = *calibration.hot_pixels;
  if (calibration.noise) {
    json noise =
        block.contains("noise") && block["noise"].is_object() ? block["noise"] : json::object();
    noise["read_noise_dn"] = calibration.noise->read_noise_dn;
    noise["dn_per_electron"] = calibration.noise->dn_per_electron;
    block["noise"] = noise;
  }
  return block;
}

json toJson(const StackManifest& manifest) {
  json document = manifest.source.is_object() ? manifest.source : json::object();
  document["schema"] = kStackSchema;
  if (manifest.id) document["id"] = *manifest.id;
  if (manifest.captured_at) document["captured_at"] = *manifest.captured_at;
  if (manifest.alpha_deg) document["alpha_deg"] = *manifest.alpha_deg;
  if (manifest.source_illuminance) {
    document["source"] = toJson(*manifest.source_illuminance);
  } else {
    document.erase("source");
  }
  if (manifest.calibration) {
    document["calibration"] = toJson(*manifest.calibration);
  } else if (manifest.calibration_path) {
    document["calibration"] = *manifest.calibration_path;
  }
  json frames = json::array();
  for (const FrameSpec& frame : manifest.frames) {
    json entry = frame.source.is_object() ? frame.source : json::object();
    entry["file"] = frame.file;
    entry["exposure_us"] = frame.exposure_us;
    entry["gain_db"] = frame.gain_db;
    if (frame.f_number) entry["f_number"] = *frame.f_number;
    entry["nd_transmission"] = frame.nd_transmission;
    frames.push_back(entry);
  }
  document["frames"] = frames;
  return document;
}

}  // namespace glarecam
