// What `--help` says an option's value is: "--alpha DEG", "--threshold CD_M2", "--size WxH",
// "--config FILE", instead of CLI11's "TEXT" for every option read as a string and parsed by
// the command itself. One table for glarecam and glarecamd, so that an option means the same
// value everywhere.
#pragma once

#include <CLI/CLI.hpp>

namespace glarecam::apps {

// Names the value of every option of `app` and its subcommands (recursively) that CLI11 would
// show as TEXT, by the option's long name; an option the table does not know keeps TEXT.
void nameOptionValues(CLI::App& app);

}  // namespace glarecam::apps
