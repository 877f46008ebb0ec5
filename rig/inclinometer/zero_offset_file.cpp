#include "rig/inclinometer/zero_offset_file.h"

#include <fmt/format.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstring>

#include "core/atomic_file.h"
#include "core/json.h"

namespace glarecam::rig {

namespace {

using nlohmann::json;

constexpr const char* kBlock = "inclinometer";

}  // namespace

json tiltReadingJson(const TiltReading& r) {
  json mean{{"x_g", r.mean.x_g}, {"y_g", r.mean.y_g}, {"z_g", r.mean.z_g}};
  if (r.mean.temperature_c) mean["temperature_c"] = *r.mean.temperature_c;
  return {{"tilt_x_deg", r.tilt.x_deg},
          {"tilt_y_deg", r.tilt.y_deg},
          {"raw_tilt_x_deg", r.raw_tilt.x_deg},
          {"raw_tilt_y_deg", r.raw_tilt.y_deg},
          {"module_tilt_deg", r.module_tilt_deg},
          {"tilt_std_deg", r.tilt_std_deg},
          {"tilt_uncertainty_deg", r.tilt_uncertainty_deg},
          {"samples", r.samples},
          {"mean", mean}};
}

Result<TiltReading> parseTiltReading(const json& document, const std::string& where) {
  const JsonReader fields(document, where);
  GLARECAM_CHECK(fields.object());
  TiltReading r;
  GLARECAM_ASSIGN(r.raw_tilt.x_deg, fields.number("raw_tilt_x_deg"));
  GLARECAM_ASSIGN(r.raw_tilt.y_deg, fields.number("raw_tilt_y_deg"));
  GLARECAM_ASSIGN(r.tilt_std_deg, fields.nonNegative("tilt_std_deg"));
  GLARECAM_ASSIGN(r.samples, fields.integer("samples", kMinTiltSamples, kMaxTiltSamples));
  r.tilt = r.raw_tilt;
  r.module_tilt_deg = moduleTiltDeg(r.tilt);
  // The raw mean vector (the flip's exact formula uses it); from the tilts when not recorded.
  r.mean = mountedGravity(r.raw_tilt, {});
  std::optional<JsonReader> mean;
  GLARECAM_ASSIGN(mean, fields.optionalObject("mean"));
  if (mean) {
    GLARECAM_ASSIGN(r.mean.x_g, mean->number("x_g"));
    GLARECAM_ASSIGN(r.mean.y_g, mean->number("y_g"));
    GLARECAM_ASSIGN(r.mean.z_g, mean->number("z_g"));
    if (!(std::hypot(r.mean.x_g, r.mean.y_g, r.mean.z_g) > 0))
      return mean->fail("is the zero vector");
  }
  return r;
}

Result<std::optional<InclinometerZeroOffset>> readZeroOffset(const std::filesystem::path& file) {
  json document;
  GLARECAM_ASSIGN(document, readJsonFile(file));
  const JsonReader fields(document, file.string());
  std::optional<JsonReader> block;
  GLARECAM_ASSIGN(block, fields.optionalObject(kBlock));
  if (!block) return std::nullopt;
  InclinometerZeroOffset zero;
  GLARECAM_ASSIGN(zero.offset.x_deg, block->number("zero_offset_x_deg"));
  GLARECAM_ASSIGN(zero.offset.y_deg, block->number("zero_offset_y_deg"));
  const auto uri = block->value().find("uri");
  if (uri != block->value().end() && uri->is_string()) zero.measured_with = uri->get<std::string>();
  std::optional<double> uncertainty_deg;
  GLARECAM_ASSIGN(uncertainty_deg, block->optionalNonNegative("uncertainty_deg"));
  if (uncertainty_deg) zero.uncertainty_deg = *uncertainty_deg;
  if (std::abs(zero.offset.x_deg) > kMaxPlausibleZeroOffsetDeg ||
      std::abs(zero.offset.y_deg) > kMaxPlausibleZeroOffsetDeg)
    return block->fail(fmt::format("zero offset ({:g}°, {:g}°) is implausibly large (> {:g}°)",
                                   zero.offset.x_deg, zero.offset.y_deg,
                                   kMaxPlausibleZeroOffsetDeg));
  return zero;
}

Status checkZeroOffsetWritable(const std::filesystem::path& file) {
  std::error_code ec;
  if (std::filesystem::exists(file, ec)) {
    json document;
    GLARECAM_ASSIGN(document, readJsonFile(file.string()));
    if (!document.is_object())
      return badInput(file.string() + ": not a JSON object; refusing to overwrite it");
    if (::access(file.c_str(), W_OK) != 0)
      return ioError(file.string() + ": not writable (" + std::strerror(errno) + ")");
    return {};
  }
  const std::filesystem::path directory =
      file.has_parent_path() ? file.parent_path() : std::filesystem::path(".");
  if (!std::filesystem::is_directory(directory, ec))
    return badInput(file.string() + ": its directory " + directory.string() + " does not exist");
  if (::access(directory.c_str(), W_OK) != 0)
    return ioError(file.string() + ": cannot create it in " + directory.string() + " (" +
                   std::strerror(errno) + ")");
  return {};
}

Status writeZeroOffset(const std::filesystem::path& file, const InclinometerZeroOffset& zero,
                       const json& provenance) {
  if (!std::isfinite(zero.offset.x_deg) || !std::isfinite(zero.offset.y_deg) ||
      !(zero.uncertainty_deg >= 0))
    return badInput(file.string() + ": refusing to store a zero offset that is not a number");
  GLARECAM_CHECK(checkZeroOffsetWritable(file));
  json document = json::object();
  std::error_code ec;
  if (std::filesystem::exists(file, ec)) GLARECAM_ASSIGN(document, readJsonFile(file.string()));
  json block = provenance.is_object() ? provenance : json::object();
  block["zero_offset_x_deg"] = zero.offset.x_deg;
  block["zero_offset_y_deg"] = zero.offset.y_deg;
  block["uncertainty_deg"] = zero.uncertainty_deg;
  document[kBlock] = block;
  return writeJsonFile(file, document);
}

}  // namespace glarecam::rig
