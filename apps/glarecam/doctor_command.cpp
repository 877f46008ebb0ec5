// glarecam doctor: is this rig ready for glarecamd? (daemon/hardware/rig_doctor.h)
#include <cstdio>
#include <memory>
#include <string>

#include "apps/glarecam/commands.h"
#include "core/json.h"
#include "daemon/hardware/rig_doctor.h"
#include "rig/rig_config.h"

namespace glarecam::apps {
namespace {

struct DoctorArgs {
  std::string config = rig::kDefaultRigConfigPath;
  bool json = false;
};

Status runDoctor(const DoctorArgs& args) {
  daemon::DoctorOptions options{.config_path = args.config};
  const std::vector<daemon::DoctorCheck> checks = daemon::runDoctor(options);
  std::fputs(args.json ? jsonText(daemon::doctorJson(checks)).c_str()
                       : daemon::doctorTable(checks).c_str(),
             stdout);
  std::fflush(stdout);
  if (options.config_bad_input)
    return badInput("doctor: " + args.config + " is not a valid config");
  if (daemon::anyFailed(checks))
    return fail(ErrorCode::kHardware, "doctor: the rig is not ready (the FAIL lines above)");
  return {};
}

}  // namespace

void addDoctorCommand(CLI::App& app, Action& action) {
  auto args = std::make_shared<DoctorArgs>();
  CLI::App* sub = app.add_subcommand(
      "doctor",
      "Check the rig for glarecamd: config, camera (a test frame), inclinometer, sun, clock, "
      "disk, permissions, the systemd unit; exit 1 when a check fails (docs/operator.md)");
  sub->add_option("--config", args->config, "rig config (TOML)")->capture_default_str();
  sub->add_flag("--json", args->json, "print the checks as JSON");
  sub->callback([args, &action] { action = [args] { return runDoctor(*args); }; });
}

}  // namespace glarecam::apps
