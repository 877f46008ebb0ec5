// glarecam calibrate merge: calibration parts -> one file (later files win).
#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "apps/glarecam/calibrate_options.h"
#include "apps/glarecam/option_parsing.h"
#include "core/json.h"

namespace glarecam::apps {
namespace {

struct MergeArgs {
  std::vector<std::string> files;
  std::optional<std::string> out;
  bool json = false;
};

Status runMerge(const MergeArgs& args) {
  GLARECAM_CHECK(requireNonEmptyPath(args.out, "--out"));
  calibration::MergePartsOptions options;
  options.files.assign(args.files.begin(), args.files.end());
  options.out = args.out.value_or("");
  calibration::MergedCalibration merged;
  GLARECAM_ASSIGN(merged, calibration::mergeCalibrationParts(options));
  if (args.json) {
    std::printf("%s", jsonText(calibration::toJson(merged.document)).c_str());
  } else {
    std::printf("%s\n", merged.file.c_str());
  }
  return {};
}

}  // namespace

void addCalibrateMergeCommand(CLI::App& calibrate, Action& action) {
  auto args = std::make_shared<MergeArgs>();
  CLI::App* sub = calibrate.add_subcommand(
      "merge", "combine calibration parts into one file (later files win)");
  sub->add_option("FILE", args->files, "glarecam.calibration/1 files")->required();
  sub->add_option("--out", args->out, "the combined file (its images are copied beside it)");
  sub->add_flag("--json", args->json, "print the written file on stdout");
  setAction(sub, action, args, runMerge);
}

}  // namespace glarecam::apps
