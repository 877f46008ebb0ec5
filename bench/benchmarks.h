// The benchmarks of glarecam-bench, registered explicitly from main() so that they run in a
// fixed order (static registration across files would follow link order) and so that main()
// can register them before running them.
#pragma once

namespace glarecam::bench {

// merge/glarecam, merge/memory_floor, merge/opencv_debevec.
void registerMergeBenchmarks();
// process/end_to_end.
void registerProcessBenchmarks();

}  // namespace glarecam::bench
