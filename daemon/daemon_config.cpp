#include "daemon/daemon_config.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <fstream>

#include "core/config_table.h"

namespace glarecam::daemon {

namespace {

constexpr std::size_t kMaxExposures = 64;          // as `glarecam capture --exposures`
constexpr double kMinExposureUs = 1e-3;            // far below any sensor's shortest
constexpr double kMaxExposureUs = 3.6e9;           // an hour
constexpr double kMaxGainDb = 100.0;               // beyond any sensor's analogue gain
constexpr std::int64_t kMaxFrameRetries = 1000;    // beyond this a link is broken, not lossy
constexpr std::int64_t kMaxIntervalS = 7 * 86400;  // a week
constexpr std::int64_t kMaxThreads = 256;
constexpr std::int64_t kMaxCameraFailures = 1000;
constexpr std::int64_t kMaxBackoffS = 86400;
constexpr double kAlphaTargetStepDeg = 5.0;  // the paper's sweep, 5° ... 80°

Result<capture::CaptureConfig> readCapture(const std::filesystem::path& file,
                                           const toml::table* table) {
  capture::CaptureConfig capture;
  if (!table) return capture;
  TableReader reader(file, *table, "capture");
  if (const toml::node* exposures = reader.node("exposures");
      exposures && !(exposures->is_string() && *exposures->value<std::string>() == "auto")) {
    if (!exposures->is_array())
      return reader.error(*exposures,
                          "capture.exposures must be \"auto\" or an array of exposure times in µs");
    GLARECAM_ASSIGN(capture.exposures_us, reader.numberList("exposures", kMinExposureUs,
                                                            kMaxExposureUs, 1, kMaxExposures));
  }
  std::optional<double> gain;
  GLARECAM_ASSIGN(gain, reader.number("gain_db", -kMaxGainDb, kMaxGainDb));
  capture.gain_db = gain.value_or(0.0);
  GLARECAM_ASSIGN(capture.pixel_format, reader.string("pixel_format"));
  GLARECAM_ASSIGN(capture.f_number, reader.number("f_number", 0.1, 1000));
  GLARECAM_ASSIGN(capture.nd_transmission, reader.number("nd_transmission", 1e-9, 1));
  std::optional<std::int64_t> retries;
  GLARECAM_ASSIGN(retries, reader.integer("max_frame_retries", 0, kMaxFrameRetries));
  if (retries) capture.max_frame_retries = static_cast<int>(*retries);
  std::optional<std::string> preset;
  GLARECAM_ASSIGN(preset, reader.string("genicam_preset"));
  GLARECAM_CHECK(reader.checkNoUnknownKeys());
  if (preset) {
    capture.genicam_preset = file.parent_path() / *preset;
    std::string features;
    GLARECAM_ASSIGN(features, readGenicamPreset(*capture.genicam_preset));
    capture.genicam_features = std::move(features);
  }
  return capture;
}

bool isFeatureName(std::string_view name) {
  if (name.empty() || !std::isalpha(static_cast<unsigned char>(name[0]))) return false;
  return std::all_of(name.begin(), name.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_';
  });
}

Result<ScheduleConfig> readSchedule(const std::filesystem::path& file, const toml::table* table,
                                    bool has_site) {
  ScheduleConfig schedule{.alpha_targets_deg = defaultAlphaTargetsDeg()};
  if (!table) return schedule;
  TableReader reader(file, *table, "schedule");
  std::optional<std::string> mode;
  GLARECAM_ASSIGN(mode, reader.choice("mode", {"interval", "alpha-targets", "button"}));
  if (mode == "alpha-targets") schedule.mode = ScheduleMode::kAlphaTargets;
  if (mode == "button") schedule.mode = ScheduleMode::kButton;
  std::optional<std::int64_t> interval;
  GLARECAM_ASSIGN(interval, reader.integer("interval_s", 1, kMaxIntervalS));
  if (interval) schedule.interval = std::chrono::seconds(*interval);
  std::optional<double> max_alpha;
  GLARECAM_ASSIGN(max_alpha, reader.number("max_alpha_deg", 0, 89.999));
  if (max_alpha) schedule.max_alpha_deg = *max_alpha;
  std::optional<std::vector<double>> targets;
  GLARECAM_ASSIGN(targets, reader.numberList("alpha_targets_deg", 0, 89.999, 1, 90));
  if (targets) {
    std::sort(targets->begin(), targets->end());
    targets->erase(std::unique(targets->begin(), targets->end()), targets->end());
    schedule.alpha_targets_deg = std::move(*targets);
  }
  std::optional<bool> button;
  GLARECAM_ASSIGN(button, reader.boolean("button"));
  if (button) schedule.button = *button;
  GLARECAM_CHECK(reader.checkNoUnknownKeys());
  if (schedule.mode == ScheduleMode::kAlphaTargets && !has_site)
    return reader.tableError(
        "mode = \"alpha-targets\" needs a [site]: the targets are crossed as the sun moves");
  return schedule;
}

Result<OutputConfig> readOutput(const std::filesystem::path& file, const toml::table* table) {
  OutputConfig output;
  if (!table) return output;
  TableReader reader(file, *table, "output");
  std::optional<std::string> root, module;
  GLARECAM_ASSIGN(root, reader.string("root"));
  if (root) output.root = (file.parent_path() / *root).lexically_normal();
  std::optional<std::int64_t> reserve_mb, threads;
  GLARECAM_ASSIGN(reserve_mb, reader.integer("reserve_mb", 0, kMaxReserveMb));
  if (reserve_mb) output.reserve_bytes = static_cast<std::uint64_t>(*reserve_mb) << 20;
  GLARECAM_ASSIGN(module, reader.string("module"));
  if (module) output.module = *module;
  GLARECAM_ASSIGN(threads, reader.integer("processing_threads", 1, kMaxThreads));
  if (threads) output.processing_threads = static_cast<unsigned>(*threads);
  std::optional<std::int64_t> keep_stacks, keep_results;
  GLARECAM_ASSIGN(keep_stacks, reader.integer("keep_stacks_days", 1, kMaxKeepDays));
  GLARECAM_ASSIGN(keep_results, reader.integer("keep_results_days", 1, kMaxKeepDays));
  if (keep_stacks) output.retention.keep_stacks_days = static_cast<int>(*keep_stacks);
  if (keep_results) output.retention.keep_results_days = static_cast<int>(*keep_results);
  std::optional<double> max_use_gib;
  GLARECAM_ASSIGN(max_use_gib, reader.number("max_use_gib", kMinMaxUseGib, kMaxMaxUseGib));
  if (max_use_gib)
    output.retention.max_use_bytes = static_cast<std::uint64_t>(*max_use_gib * kBytesPerGib);
  if (const Status valid = output.retention.validate(); !valid)
    return reader.tableError(valid.error().message);
  GLARECAM_CHECK(reader.checkNoUnknownKeys());
  return output;
}

Result<std::optional<std::chrono::seconds>> seconds(TableReader& reader, const char* key) {
  std::optional<std::int64_t> value;
  GLARECAM_ASSIGN(value, reader.integer(key, 1, kMaxBackoffS));
  if (!value) return std::nullopt;
  return std::chrono::seconds(*value);
}

Result<FaultConfig> readFaults(const std::filesystem::path& file, const toml::table* table) {
  FaultConfig faults;
  if (!table) return faults;
  TableReader reader(file, *table, "faults");
  std::optional<std::string> policy;
  GLARECAM_ASSIGN(policy, reader.choice("inclinometer", {"continue", "pause"}));
  if (policy == "pause") faults.inclinometer = InclinometerFaultPolicy::kPause;
  std::optional<double> min_tilt, max_tilt;
  GLARECAM_ASSIGN(min_tilt, reader.number("min_tilt_deg", 0, 180));
  GLARECAM_ASSIGN(max_tilt, reader.number("max_tilt_deg", 0, 180));
  faults.min_tilt_deg = min_tilt.value_or(faults.min_tilt_deg);
  faults.max_tilt_deg = max_tilt.value_or(faults.max_tilt_deg);
  std::optional<std::int64_t> failures;
  GLARECAM_ASSIGN(failures, reader.integer("camera_max_failures", 1, kMaxCameraFailures));
  if (failures) faults.camera_max_failures = static_cast<int>(*failures);
  std::optional<std::chrono::seconds> backoff, backoff_max;
  GLARECAM_ASSIGN(backoff, seconds(reader, "camera_backoff_s"));
  GLARECAM_ASSIGN(backoff_max, seconds(reader, "camera_backoff_max_s"));
  faults.camera_backoff = backoff.value_or(faults.camera_backoff);
  faults.camera_backoff_max =
      backoff_max.value_or(std::max(faults.camera_backoff_max, faults.camera_backoff));
  GLARECAM_CHECK(reader.checkNoUnknownKeys());
  if (!(faults.min_tilt_deg < faults.max_tilt_deg))
    return reader.tableError(fmt::format("min_tilt_deg {:g} must be below max_tilt_deg {:g}",
                                         faults.min_tilt_deg, faults.max_tilt_deg));
  if (faults.camera_backoff_max < faults.camera_backoff)
    return reader.tableError(fmt::format("camera_backoff_max_s {} is below camera_backoff_s {}",
                                         faults.camera_backoff_max.count(),
                                         faults.camera_backoff.count()));
  return faults;
}

Result<StatusConfig> readStatus(const std::filesystem::path& file, const toml::table* table) {
  StatusConfig status;
  if (!table) return status;
  TableReader reader(file, *table, "status");
  const toml::node* listen = reader.node("listen");
  GLARECAM_CHECK(reader.checkNoUnknownKeys());
  if (!listen) return status;
  if (!listen->is_string())
    return reader.error(*listen, "status.listen must be a string such as \"127.0.0.1:8080\"");
  auto address = parseListenAddress(*listen->value<std::string>());
  if (!address) return reader.error(*listen, "status.listen: " + address.error().message);
  status.listen = std::move(*address);
  return status;
}

}  // namespace

Result<std::string> readGenicamPreset(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) return badInput(path.string() + ": cannot read the GenICam preset");
  std::string features, line;
  for (int number = 1; std::getline(in, line); ++number) {
    const std::size_t begin = line.find_first_not_of(" \t");
    if (begin == std::string::npos || line[begin] == '#') continue;
    const std::string entry = line.substr(begin, line.find_last_not_of(" \t\r") - begin + 1);
    const std::size_t equals = entry.find('=');
    const bool valid = equals != std::string::npos && isFeatureName(entry.substr(0, equals)) &&
                       equals + 1 < entry.size() &&
                       entry.find_first_of(" \t", equals) == std::string::npos;
    if (!valid)
      return badInput(
          fmt::format("{}:{}: expected Feature=Value (a GenICam feature name, a value "
                      "without spaces), got \"{}\"",
                      path.string(), number, entry));
    features += (features.empty() ? "" : " ") + entry;
  }
  if (features.empty()) return badInput(path.string() + ": the GenICam preset sets no feature");
  return features;
}

std::vector<double> defaultAlphaTargetsDeg() {
  std::vector<double> targets;
  for (double alpha = kAlphaTargetStepDeg; alpha <= pipeline::kMaxLimitAlphaDeg;
       alpha += kAlphaTargetStepDeg)
    targets.push_back(alpha);
  return targets;
}

Result<Config> readConfig(const std::filesystem::path& path) {
  std::vector<std::string_view> sections(rig::kRigSections.begin(), rig::kRigSections.end());
  sections.insert(sections.end(), kDaemonSections.begin(), kDaemonSections.end());
  toml::table root;
  GLARECAM_ASSIGN(root, readConfigFile(path, sections));
  Config config;
  GLARECAM_ASSIGN(config.rig, rig::readRigSections(path, root));
  DaemonConfig& daemon = config.daemon;
  GLARECAM_ASSIGN(daemon.capture, readCapture(path, root["capture"].as_table()));
  GLARECAM_ASSIGN(daemon.schedule,
                  readSchedule(path, root["schedule"].as_table(), config.rig.site.has_value()));
  GLARECAM_ASSIGN(daemon.output, readOutput(path, root["output"].as_table()));
  GLARECAM_ASSIGN(daemon.faults, readFaults(path, root["faults"].as_table()));
  GLARECAM_ASSIGN(daemon.status, readStatus(path, root["status"].as_table()));
  return config;
}

Result<rig::RigConfig> readRigConfig(const std::filesystem::path& path) {
  Config config;
  GLARECAM_ASSIGN(config, readConfig(path));
  return std::move(config.rig);
}

}  // namespace glarecam::daemon
