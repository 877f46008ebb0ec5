// glarecamd: the rig's capture daemon under systemd (see --help, docs/operator.md).
#include "apps/glarecamd/daemon_cli.h"
#include "core/memory.h"

int main(int argc, char** argv) {
  glarecam::reuseLargeAllocations();  // best effort: only speed depends on it
  return glarecam::apps::runGlarecamd(argc, argv);
}
