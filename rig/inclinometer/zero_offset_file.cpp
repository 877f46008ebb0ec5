#include "rig/inclinometer/zero_offset_file.h"

#include <fmt/format.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstring>

#include "core/atomic_file.h"
#include "core/stack_manifest.h"

namespace glarecam::rig {

namespace {

using nlohmann::json;

constexpr const char* kBlock = "inclinometer";

Result<double> finiteNumber(const json& object, const char* key, const std::string& where) {
  const auto it = object.find(key);
  if (it == object.end()) return badInput(fmt::format("{}: missing \"{}\"", where, key));
  if (!it->is_number() || !std::isfinite(it->get<double>()))
    return badInput(fmt::format("{}: \"{}\" must be a finite number", where, key));
  return it->get<double>();
}

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
  if (!document.is_object()) return badInput(where + ": a tilt reading must be a JSON object");
  TiltReading r;
  GLARECAM_ASSIGN(r.raw_tilt.x_deg, finiteNumber(document, "raw_tilt_x_deg", where));
  GLARECAM_ASSIGN(r.raw_tilt.y_deg, finiteNumber(document, "raw_tilt_y_deg", where));
  GLARECAM_ASSIGN(r.tilt_std_deg, finiteNumber(document, "tilt_std_deg", where));
  if (r.tilt_std_deg < 0) return badInput(where + ": \"tilt_std_deg\" must not be negative");
  double samples = 0;
  GLARECAM_ASSIGN(samples, finiteNumber(document, "samples", where));
  if (!(samples >= kMinTiltSamples && samples <= kMaxTiltSamples) || samples != std::floor(samples))
    return badInput(fmt::format("{}: \"samples\" must be a whole number in [{}, {}]", where,
                                kMinTiltSamples, kMaxTiltSamples));
  r.samples = static_cast<int>(samples);
  r.tilt = r.raw_tilt;
  r.module_tilt_deg = moduleTiltDeg(r.tilt);
  // The raw mean vector (the flip's exact formula uses it); from the tilts when not recorded.
  r.mean = mountedGravity(r.raw_tilt, {});
  const auto mean = document.find("mean");
  if (mean != document.end()) {
    if (!mean->is_object()) return badInput(where + ": \"mean\" must be an object");
    const std::string mean_where = where + ": mean";
    GLARECAM_ASSIGN(r.mean.x_g, finiteNumber(*mean, "x_g", mean_where));
    GLARECAM_ASSIGN(r.mean.y_g, finiteNumber(*mean, "y_g", mean_where));
    GLARECAM_ASSIGN(r.mean.z_g, finiteNumber(*mean, "z_g", mean_where));
    if (!(std::hypot(r.mean.x_g, r.mean.y_g, r.mean.z_g) > 0))
      return badInput(mean_where + ": the vector is zero");
  }
  return r;
}

Result<std::optional<InclinometerZeroOffset>> readZeroOffset(const std::filesystem::path& file) {
  json document;
  GLARECAM_ASSIGN(document, readJsonFile(file.string()));
  if (!document.is_object()) return badInput(file.string() + ": not a JSON object");
  const auto block = document.find(kBlock);
  if (block == document.end()) return std::nullopt;
  const std::string where = file.string() + ": " + kBlock;
  if (!block->is_object()) return badInput(where + " must be an object");
  InclinometerZeroOffset zero;
  GLARECAM_ASSIGN(zero.offset.x_deg, finiteNumber(*block, "zero_offset_x_deg", where));
  GLARECAM_ASSIGN(zero.offset.y_deg, finiteNumber(*block, "zero_offset_y_deg", where));
  const auto uri = block->find("uri");
  if (uri != block->end() && uri->is_string()) zero.measured_with = uri->get<std::string>();
  if (block->contains("uncertainty_deg"))
    GLARECAM_ASSIGN(zero.uncertainty_deg, finiteNumber(*block, "uncertainty_deg", where));
  if (zero.uncertainty_deg < 0)
    return badInput(where + ": \"uncertainty_deg\" must not be negative");
  if (std::abs(zero.offset.x_deg) > kMaxPlausibleZeroOffsetDeg ||
      std::abs(zero.offset.y_deg) > kMaxPlausibleZeroOffsetDeg)
    return badInput(fmt::format("{}: zero offset ({:g}°, {:g}°) is implausibly large (> {:g}°)",
                                where, zero.offset.x_deg, zero.offset.y_deg,
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
  return writeFileAtomic(file, jsonText(document));
}

}  // namespace glarecam::rig
