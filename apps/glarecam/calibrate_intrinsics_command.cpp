// glarecam calibrate intrinsics: checkerboard views (one stack each) -> fx, fy, cx, cy and
// distortion; with --camera, --views poses --view-interval seconds apart.
#include <memory>
#include <string>
#include <utility>

#include "apps/glarecam/calibrate_options.h"
#include "apps/glarecam/option_parsing.h"

namespace glarecam::apps {
namespace {

struct IntrinsicsArgs {
  PartArgs part;
  std::string board = "9x6";
  double square_mm = 25;
  bool fit_k3 = false;
};

Status runIntrinsics(const IntrinsicsArgs& args) {
  calibration::IntrinsicsPartOptions options;
  std::pair<int, int> corners;
  GLARECAM_ASSIGN(corners, parseSize(args.board, "--board"));
  options.board = {
      .inner_columns = corners.first, .inner_rows = corners.second, .square_mm = args.square_mm};
  options.fit_k3 = args.fit_k3;
  return runPart(args.part, std::move(options), calibration::calibrateIntrinsicsPart);
}

}  // namespace

void addCalibrateIntrinsicsCommand(CLI::App& calibrate, Action& action) {
  auto args = std::make_shared<IntrinsicsArgs>();
  CLI::App* sub = addPartCommand(
      calibrate, "intrinsics",
      "checkerboard views (one stack each) -> fx, fy, cx, cy, distortion (OpenCV calib3d)",
      args->part, true);
  sub->add_option("--board", args->board, "inner corners across x down (default 9x6)");
  sub->add_option("--square-mm", args->square_mm, "side of a square in mm (default 25)");
  sub->add_flag("--fit-k3", args->fit_k3, "fit k3 too (wide-angle lenses; needs many views)");
  sub->add_option("--views", args->part.views, "with --camera: board poses to capture (default 1)");
  sub->add_option("--view-interval", args->part.view_interval_s,
                  "with --camera: seconds between poses, to move the board (default 10)");
  setAction(sub, action, args, runIntrinsics);
}

}  // namespace glarecam::apps
