#include "capture/inclinometer/zero_offset_file.h"

#include <fmt/format.h>

#include <cmath>

#include "core/atomic_file.h"
#include "core/stack_manifest.h"

namespace glarecam::capture {

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
  double samples = 0;
  GLARECAM_ASSIGN(samples, finiteNumber(document, "samples", where));
  if (samples < 1 || samples != std::floor(samples))
    return badInput(where + ": \"samples\" must be a positive integer");
  r.samples = int(samples);
  r.tilt = r.raw_tilt;
  r.module_tilt_deg = moduleTiltDeg(r.tilt);
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
  if (block->contains("uncertainty_deg"))
    GLARECAM_ASSIGN(zero.uncertainty_deg, finiteNumber(*block, "uncertainty_deg", where));
  if (std::abs(zero.offset.x_deg) > kMaxPlausibleZeroOffsetDeg ||
      std::abs(zero.offset.y_deg) > kMaxPlausibleZeroOffsetDeg)
    return badInput(fmt::format("{}: zero offset ({:g}°, {:g}°) is implausibly large (> {:g}°)",
                                where, zero.offset.x_deg, zero.offset.y_deg,
                                kMaxPlausibleZeroOffsetDeg));
  return zero;
}

Status writeZeroOffset(const std::filesystem::path& file, const InclinometerZeroOffset& zero,
                       const json& provenance) {
  json document = json::object();
  std::error_code ec;
  if (std::filesystem::exists(file, ec)) {
    GLARECAM_ASSIGN(document, readJsonFile(file.string()));
    if (!document.is_object())
      return badInput(file.string() + ": not a JSON object; refusing to overwrite it");
  }
  json block = provenance.is_object() ? provenance : json::object();
  block["zero_offset_x_deg"] = zero.offset.x_deg;
  block["zero_offset_y_deg"] = zero.offset.y_deg;
  block["uncertainty_deg"] = zero.uncertainty_deg;
  document[kBlock] = block;
  return writeFileAtomic(file, jsonText(document));
}

}  // namespace glarecam::capture
