// glarecam doctor: is this rig ready for glarecamd? (capture/daemon/rig_doctor.h)
#include <cstdio>
#include <memory>
#include <string>

#include "apps/glarecam/commands.h"
#include "capture/daemon/rig_doctor.h"
#include "capture/rig_config.h"
#include "core/stack_manifest.h"

namespace glarecam::apps {
namespace {

struct DoctorArgs {
  std::string config = capture::kDefaultRigConfigPath;
  bool json = false;
};

Status runDoctor(const DoctorArgs& args) {
  capture::DoctorOptions options{.config_path = args.config};
  const std::vector<capture::DoctorCheck> checks = capture::runDoctor(options);
  std::fputs(args.json ? jsonText(capture::doctorJson(checks)).c_str()
                       : capture::doctorTable(checks).c_str(),
             stdout);
  std::fflush(stdout);
  if (options.config_bad_input)
    return badInput("doctor: " + args.config + " is not a valid config");
  if (capture::anyFailed(checks))
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
