// The glarecam command line: one CLI11 app with a subcommand per operation. Each subcommand
// owns an options struct, validates it, calls one library function and maps the result to an
// exit status (0 success, 2 bad input or usage, 1 anything else).
#pragma once

namespace glarecam::apps {

int runGlarecam(int argc, char** argv);

}  // namespace glarecam::apps
