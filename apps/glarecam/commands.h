// Subcommands of the glarecam CLI. Each add*Command registers its options on `app` and, when
// its subcommand is chosen, sets `action` to the work to run after parsing.
#pragma once

#include <CLI/CLI.hpp>
#include <functional>

#include "core/error.h"

namespace glarecam::apps {

using Action = std::function<Status()>;

void addSimulateCommand(CLI::App& app, Action& action);
void addProcessCommand(CLI::App& app, Action& action);

}  // namespace glarecam::apps
