#include "core/stack_manifest.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace glarecam {
namespace {

using nlohmann::json;

std::string show(const json& value) {
  std::string text = value.dump(-1, ' ', false, json::error_handler_t::replace);
  return text.size() > 40 ? text.substr(0, 37) + "..." : text;
}

// Reads typed fields of one JSON object, naming the file and the field path in every error.
class FieldReader {
 public:
  FieldReader(const json& object, std::string where, std::string prefix)
      : object_(object), where_(std::move(where)), prefix_(std::move(prefix)) {}

  std::unexpected<Error> error(std::string_view key, const std::string& problem) const {
    return badInput(where_ + ": " + name(key) + " " + problem);
  }
  std::string name(std::string_view key) const { return prefix_ + std::string(key); }
  bool has(std::string_view key) const {
    return object_.contains(key) && !object_.at(key).is_null();
  }
  const json& at(std::string_view key) const { return object_.at(key); }

  // A finite number; absent or null gives nullopt.
  Result<std::optional<double>> optionalNumber(std::string_view key) const {
    if (!has(key)) return std::optional<double>{};
    const json& value = object_.at(key);
    if (!value.is_number()) return error(key, "must be a number, not " + show(value));
    double number = value.get<double>();
    if (!std::isfinite(number)) return error(key, "must be finite");
    return number;
  }
  Result<double> number(std::string_view key) const {
    auto value = optionalNumber(key);
    if (!value) return std::unexpected(value.error());
    if (!*value) return error(key, "is required");
    return **value;
  }
  // An image dimension in pixels: a whole number in [1, kMaxImageSide].
  Result<std::optional<int>> optionalSize(std::string_view key) const {
    std::optional<double> value;
    GLARECAM_ASSIGN(value, optionalNumber(key));
    if (!value) return std::optional<int>{};
    if (!isImageSidePx(*value))
      return error(key, "must be a whole number of pixels, not " + show(object_.at(key)));
    return std::optional<int>(static_cast<int>(*value));
  }
  Result<double> positive(std::string_view key) const {
    auto value = number(key);
    if (value && *value <= 0) return error(key, "must be positive, not " + show(object_.at(key)));
    return value;
  }
  Result<std::optional<std::string>> optionalString(std::string_view key) const {
    if (!has(key)) return std::optional<std::string>{};
    if (!object_.at(key).is_string())
      return error(key, "must be a string, not " + show(object_.at(key)));
    return object_.at(key).get<std::string>();
  }
  // A relative path that stays inside its base directory.
  Result<std::optional<std::string>> optionalContainedPath(std::string_view key) const {
    auto path = optionalString(key);
    if (path && *path && !isContainedRelativePath(**path)) {
      return error(key, "\"" + **path + "\" escapes the stack directory (absolute or with \"..\")");
    }
    return path;
  }

 private:
  const json& object_;
  std::string where_;
  std::string prefix_;
};

Result<Intrinsics> parseIntrinsics(const FieldReader& parent, const std::string& where) {
  if (!parent.has("intrinsics")) return parent.error("intrinsics", "is required (fx, fy, cx, cy)");
  const json& block = parent.at("intrinsics");
  if (!block.is_object()) return parent.error("intrinsics", "must be an object");
  FieldReader fields(block, where, parent.name("intrinsics."));
  Intrinsics intrinsics;
  // "intrinsics that are not finite and positive" are refused (stack-format.md).
  GLARECAM_ASSIGN(intrinsics.fx, fields.positive("fx"));
  GLARECAM_ASSIGN(intrinsics.fy, fields.positive("fy"));
  GLARECAM_ASSIGN(intrinsics.cx, fields.positive("cx"));
  GLARECAM_ASSIGN(intrinsics.cy, fields.positive("cy"));
  GLARECAM_ASSIGN(intrinsics.width, fields.optionalSize("width"));
  GLARECAM_ASSIGN(intrinsics.height, fields.optionalSize("height"));
  if (intrinsics.width.has_value() != intrinsics.height.has_value())
    return parent.error("intrinsics", "gives width and height together or neither");
  if (!fields.has("distortion")) return intrinsics;
  const json& distortion = block.at("distortion");
  if (!distortion.is_array() || distortion.size() > intrinsics.distortion.size()) {
    return fields.error("distortion", "must be an array of at most 5 numbers (k1, k2, p1, p2, k3)");
  }
  for (std::size_t i = 0; i < distortion.size(); ++i) {
    if (!distortion[i].is_number() || !std::isfinite(distortion[i].get<double>())) {
      return fields.error("distortion", "[" + std::to_string(i) + "] must be a finite number");
    }
    intrinsics.distortion[i] = distortion[i].get<double>();
  }
  return intrinsics;
}

Result<std::optional<NoiseModel>> parseNoise(const FieldReader& parent, const std::string& where) {
  if (!parent.has("noise")) return std::optional<NoiseModel>{};
  if (!parent.at("noise").is_object()) return parent.error("noise", "must be an object");
  FieldReader fields(parent.at("noise"), where, parent.name("noise."));
  NoiseModel noise;
  GLARECAM_ASSIGN(noise.read_noise_dn, fields.number("read_noise_dn"));
  GLARECAM_ASSIGN(noise.dn_per_electron, fields.positive("dn_per_electron"));
  if (noise.read_noise_dn < 0) return fields.error("read_noise_dn", "must not be negative");
  return noise;
}

Result<FrameSpec> parseFrame(const json& entry, std::size_t index, const std::string& where) {
  std::string prefix = "frames[" + std::to_string(index) + "].";
  if (!entry.is_object())
    return badInput(where + ": frames[" + std::to_string(index) + "] must be an object");
  FieldReader fields(entry, where, prefix);
  FrameSpec frame;
  frame.source = entry;
  std::optional<std::string> file;
  GLARECAM_ASSIGN(file, fields.optionalContainedPath("file"));
  if (!file || file->empty()) return fields.error("file", "is required");
  frame.file = *file;
  GLARECAM_ASSIGN(frame.exposure_us, fields.positive("exposure_us"));
  std::optional<double> gain_db, nd;
  GLARECAM_ASSIGN(gain_db, fields.optionalNumber("gain_db"));
  GLARECAM_ASSIGN(frame.f_number, fields.optionalNumber("f_number"));
  GLARECAM_ASSIGN(nd, fields.optionalNumber("nd_transmission"));
  frame.gain_db = gain_db.value_or(0.0);
  frame.nd_transmission = nd.value_or(1.0);
  if (frame.f_number && *frame.f_number <= 0) return fields.error("f_number", "must be positive");
  if (frame.nd_transmission <= 0 || frame.nd_transmission > 1) {
    return fields.error("nd_transmission",
                        "must be in (0, 1], not " + show(entry.at("nd_transmission")));
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
  if (!block.is_object())
    return badInput(where + ": calibration must be an object or a path string");
  FieldReader fields(block, where, "calibration.");
  Calibration calibration;
  calibration.source = block;
  GLARECAM_ASSIGN(calibration.black_level_dn, fields.number("black_level_dn"));
  GLARECAM_ASSIGN(calibration.saturation_dn, fields.positive("saturation_dn"));
  GLARECAM_ASSIGN(calibration.luminance_factor, fields.positive("luminance_factor"));
  GLARECAM_ASSIGN(calibration.reference_f_number, fields.optionalNumber("reference_f_number"));
  GLARECAM_ASSIGN(calibration.intrinsics, parseIntrinsics(fields, where));
  GLARECAM_ASSIGN(calibration.flat_field, fields.optionalContainedPath("flat_field"));
  GLARECAM_ASSIGN(calibration.dark_frame, fields.optionalContainedPath("dark_frame"));
  GLARECAM_ASSIGN(calibration.dark_frame_exposure_us,
                  fields.optionalNumber("dark_frame_exposure_us"));
  std::optional<double> dark_gain;
  GLARECAM_ASSIGN(dark_gain, fields.optionalNumber("dark_frame_gain_db"));
  calibration.dark_frame_gain_db = dark_gain.value_or(0.0);
  std::optional<double> dark_current;
  GLARECAM_ASSIGN(dark_current, fields.optionalNumber("dark_current_dn_per_us"));
  calibration.dark_current_dn_per_us = dark_current.value_or(0.0);
  GLARECAM_ASSIGN(calibration.hot_pixels, fields.optionalContainedPath("hot_pixels"));
  GLARECAM_ASSIGN(calibration.noise, parseNoise(fields, where));
  if (calibration.dark_frame_exposure_us && !(*calibration.dark_frame_exposure_us > 0))
    return fields.error("dark_frame_exposure_us", "must be positive");
  if (!std::isfinite(calibration.dark_current_dn_per_us))
    return fields.error("dark_current_dn_per_us", "must be finite");
  if (calibration.black_level_dn < 0) return fields.error("black_level_dn", "must not be negative");
  if (calibration.black_level_dn >= calibration.saturation_dn) {
    return badInput(where + ": calibration.black_level_dn (" + show(block.at("black_level_dn")) +
                    ") must be below saturation_dn (" + show(block.at("saturation_dn")) + ")");
  }
  if (calibration.reference_f_number && *calibration.reference_f_number <= 0) {
    return fields.error("reference_f_number", "must be positive");
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
  FieldReader fields(document, where, "");
  std::optional<std::string> schema;
  GLARECAM_ASSIGN(schema, fields.optionalString("schema"));
  if (!schema)
    return fields.error("schema", "is missing (expected \"" + std::string(kStackSchema) + "\")");
  if (*schema != kStackSchema) {
    return badInput(where + ": schema \"" + *schema + "\" is not supported (expected \"" +
                    std::string(kStackSchema) + "\")");
  }
  StackManifest manifest;
  manifest.source = document;
  GLARECAM_ASSIGN(manifest.id, fields.optionalString("id"));
  GLARECAM_ASSIGN(manifest.captured_at, fields.optionalString("captured_at"));
  GLARECAM_ASSIGN(manifest.alpha_deg, fields.optionalNumber("alpha_deg"));
  if (manifest.alpha_deg && (*manifest.alpha_deg < 0 || *manifest.alpha_deg > kMaxStackAlphaDeg)) {
    return fields.error("alpha_deg",
                        "must be between 0 and 90 degrees, not " + show(document.at("alpha_deg")));
  }
  if (fields.has("calibration")) {
    if (document.at("calibration").is_string()) {
      manifest.calibration_path = document.at("calibration").get<std::string>();
    } else {
      GLARECAM_ASSIGN(manifest.calibration, parseCalibration(document.at("calibration"), where));
    }
  }
  if (!fields.has("frames") || !document.at("frames").is_array())
    return fields.error("frames", "must be a list of frames");
  const json& frames = document.at("frames");
  if (frames.empty()) return fields.error("frames", "is empty: a stack needs at least one frame");
  for (std::size_t i = 0; i < frames.size(); ++i) {
    auto frame = parseFrame(frames[i], i, where);
    if (!frame) return std::unexpected(frame.error());
    manifest.frames.push_back(std::move(*frame));
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

Result<json> parseJsonText(std::string_view text, const std::string& where) {
  // Deeper documents are refused while parsing: copying or printing them recurses once per
  // level and a hostile manifest nested 100 000 deep would overflow the stack.
  const json::parser_callback_t depth_guard = [](int depth, json::parse_event_t, json&) {
    if (depth > kMaxJsonDepth)
      throw std::length_error("nesting deeper than " + std::to_string(kMaxJsonDepth));
    return true;
  };
  try {
    return json::parse(text, depth_guard);
  } catch (const json::exception& e) {
    std::string message = e.what();
    // "[json.exception.parse_error.101] parse error at line 3, ..." -> keep the readable part.
    if (auto pos = message.find("] "); pos != std::string::npos) message = message.substr(pos + 2);
    // The parser quotes the offending bytes: keep the line printable when they are binary.
    for (char& c : message) {
      if (static_cast<unsigned char>(c) < 0x20 || static_cast<unsigned char>(c) == 0x7f) c = '?';
    }
    return badInput(where + ": invalid JSON: " + message);
  } catch (const std::length_error& e) {
    return badInput(where + ": invalid JSON: " + e.what());
  }
}

Result<json> readJsonFile(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    return badInput(path + ": file is missing or not a regular file");
  std::ifstream in(path, std::ios::binary);
  if (!in) return badInput(path + ": cannot open for reading");
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) return ioError(path + ": read failed");
  return parseJsonText(text.view(), path);
}

std::string jsonText(const json& document) {
  constexpr int kIndent = 2;
  return document.dump(kIndent, ' ', false, json::error_handler_t::replace) + "\n";
}

}  // namespace glarecam
