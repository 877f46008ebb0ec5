// Logging setup shared by the executables: spdlog to stderr, quiet by default (warnings and
// errors), --verbose for info, --debug for everything. Messages go to stderr so stdout stays
// clean for results (paths, JSON).
#pragma once

#include <spdlog/spdlog.h>

namespace glarecam {

enum class Verbosity { kQuiet, kNormal, kVerbose, kDebug };

void initLogging(Verbosity verbosity);

}  // namespace glarecam
