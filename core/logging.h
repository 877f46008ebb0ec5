// Logging setup shared by the executables: spdlog to stderr, quiet by default (warnings and
// errors), --verbose for info, --debug for everything. Messages go to stderr so stdout stays
// clean for results (paths, JSON).
#pragma once

#include <spdlog/common.h>
#include <spdlog/spdlog.h>

namespace glarecam {

enum class Verbosity { kQuiet, kNormal, kVerbose, kDebug };

void initLogging(Verbosity verbosity);

// The same levels to another sink (glarecamd's journal sink).
void initLogging(Verbosity verbosity, spdlog::sink_ptr sink);

}  // namespace glarecam
