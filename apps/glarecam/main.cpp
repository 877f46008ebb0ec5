// glarecam: glare measurement of PV modules from bracketed camera stacks (see --help).
#include "apps/glarecam/cli.h"
#include "core/memory.h"

int main(int argc, char** argv) {
  glarecam::reuseLargeAllocations();  // best effort: only speed depends on it
  return glarecam::apps::runGlarecam(argc, argv);
}
