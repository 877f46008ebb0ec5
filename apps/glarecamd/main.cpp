// glarecamd: the rig's capture daemon under systemd (see --help, docs/operator.md).
#include "apps/glarecamd/daemon_cli.h"

int main(int argc, char** argv) { return glarecam::apps::runGlarecamd(argc, argv); }
