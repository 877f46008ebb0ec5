// One line for a command line CLI11 refused, shared by glarecam and glarecamd: an unknown option
// or command is named with the closest known one ("did you mean --threshold?"), and a value given
// to a flag (`--json=yes`) is refused as such; anything else keeps CLI11's own message.
#pragma once

#include <CLI/CLI.hpp>
#include <string>

namespace glarecam::apps {

// `app` is the top-level app as CLI11 left it after the failed parse (its chosen subcommands
// selected); argv as given to main.
std::string parseErrorMessage(const CLI::App& app, const CLI::ParseError& error, int argc,
                              char** argv);

}  // namespace glarecam::apps
