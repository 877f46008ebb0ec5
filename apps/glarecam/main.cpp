// glarecam: glare measurement of PV modules from bracketed camera stacks (see --help).
#include "apps/glarecam/cli.h"

int main(int argc, char** argv) { return glarecam::apps::runGlarecam(argc, argv); }
