// `glarecam doctor`: is this rig ready for glarecamd? One check per part, each ok, warn (works,
// but look) or fail (glarecamd cannot do its job), in the order an operator fixes them: config,
// camera (streams a test frame), inclinometer (readable and steady), sun position, the
// illuminance instrument (one reading; a warning when it fails: stacks go on unreferred), clock,
// disk, permissions, the systemd unit. A part that cannot be checked because an earlier one failed
// is skipped. The camera is not touched while glarecamd runs (it owns it).
#pragma once

#include <filesystem>
#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "daemon/hardware/camera_supervisor.h"
#include "daemon/storage/disk_space.h"
#include "sun/clock_sync.h"

namespace glarecam::daemon {

enum class CheckLevel { kOk, kWarn, kFail, kSkip };

struct DoctorCheck {
  std::string name;
  CheckLevel level = CheckLevel::kOk;
  std::string detail;
};

// The systemd unit's state ("active (running)", "inactive", ...), or an error when systemd is
// not there to ask.
using UnitStateQuery = std::function<Result<std::string>(const std::string& unit)>;

struct DoctorOptions {
  std::filesystem::path config_path;
  CameraOpener open_camera{};                        // default openCamera
  DiskProbe* disk = nullptr;                         // default statvfs
  UnitStateQuery unit_state{};                       // default `systemctl show glarecamd.service`
  std::function<sun::ClockStatus()> clock_status{};  // default the kernel's (adjtimex)
  bool config_bad_input = false;                     // out: the config itself is invalid
};

std::vector<DoctorCheck> runDoctor(DoctorOptions& options);

// "ok", "warn", "FAIL", "skip".
const char* checkLevelName(CheckLevel level);
// The table as printed: one line a check.
std::string doctorTable(const std::vector<DoctorCheck>& checks);
nlohmann::json doctorJson(const std::vector<DoctorCheck>& checks);
bool anyFailed(const std::vector<DoctorCheck>& checks);

}  // namespace glarecam::daemon
