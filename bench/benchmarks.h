// The benchmarks of glarecam-bench, registered explicitly from main() so that they run in a
// fixed order (static registration across files would follow link order). The names are what
// the reports print and what main() computes the ratios from.
#pragma once

#include <string>
#include <vector>

namespace glarecam::bench {

inline constexpr const char* kMergeGlarecam = "merge/glarecam";
inline constexpr const char* kMergeMemoryFloor = "merge/memory_floor";
inline constexpr const char* kMergeOpenCvDebevec = "merge/opencv_debevec";
inline constexpr const char* kAnalysisGlarecam = "analysis/glarecam";
inline constexpr const char* kAnalysisGlarecamLadder = "analysis/glarecam_ladder";
inline constexpr const char* kAnalysisOpenCvFitEllipse = "analysis/opencv_fitellipse";
inline constexpr const char* kProcessEndToEnd = "process/end_to_end";       // + "/5MP", ...
inline constexpr const char* kProcessDecodeFloor = "process/decode_floor";  // + "/5MP", ...
inline constexpr const char* kProcessNoLadder = "process/no_ladder";        // + "/5MP", ...
inline constexpr const char* kSweepOneThread = "sweep/20_stacks/1_thread";
inline constexpr const char* kSweepAllThreads = "sweep/20_stacks/all_threads";
inline constexpr const char* kCaptureFakeGvBracket = "capture/fake_gv_bracket";
inline constexpr const char* kCaptureLinkFloor = "capture/link_floor";
inline constexpr const char* kSunGlarecamSpa = "sun/glarecam_spa";
inline constexpr const char* kSunLibnova = "sun/libnova";
inline constexpr const char* kSunYearSpa = "sun/year_spa";
inline constexpr const char* kHazardYear = "hazard/year";
inline constexpr const char* kHazardScene = "hazard/scene";
inline constexpr const char* kHazardPairsNone = "hazard/pairs/none";
inline constexpr const char* kHazardPairsNever = "hazard/pairs/never_glaring";
inline constexpr const char* kHazardPairsGlaring = "hazard/pairs/glaring";
inline constexpr const char* kHazardCity = "hazard/city";  // + "/100_roofs", ...
inline constexpr int kHazardCityRoofs[] = {100, 200, 400};
inline constexpr const char* kHazardYearClearSky = "hazard/year_clear_sky";
inline constexpr const char* kHazardYearObstructions = "hazard/year_obstructions";
inline constexpr const char* kBrdfAngle = "brdf/angle";
inline constexpr const char* kBrdfAnalysisFloor = "brdf/analysis_floor";
inline constexpr const char* kSimSurfaceScene = "sim/surface_scene";
inline constexpr const char* kSimCurvesScene = "sim/curves_scene";

// Each returns the names it registered.
std::vector<std::string> registerMergeBenchmarks();     // merge/*
std::vector<std::string> registerAnalysisBenchmarks();  // analysis/*
std::vector<std::string> registerProcessBenchmarks();   // process/* at each SensorSize
std::vector<std::string> registerSweepBenchmarks();     // sweep/*
std::vector<std::string> registerCaptureBenchmarks();   // capture/* (with Aravis only)
std::vector<std::string> registerSunBenchmarks();       // sun/* (with libnova only)
std::vector<std::string> registerHazardBenchmarks();    // sun/year_spa, hazard/*
std::vector<std::string> registerBrdfBenchmarks();      // brdf/*
std::vector<std::string> registerSimBenchmarks();       // sim/*

}  // namespace glarecam::bench
