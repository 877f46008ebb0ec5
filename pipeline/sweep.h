// `glarecam sweep`: many stacks of one module over α processed in parallel into a sweep table.
// Each stack runs through processStack() with its outputs under OUT/results/<stack name>/; a stack
// that fails (unreadable, no α, corrupt frames) is reported and skipped, never stops the rest.
// OUT/sweep.csv (sweep_table.h, rows sorted by α, skipped stacks as '#' notes) is written
// atomically once every stack is done, and beside it OUT/contours.csv (contour_table.h: every
// processed stack's contour ladder, one row per stack and level).
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "core/error.h"
#include "pipeline/contour_table.h"
#include "pipeline/sweep_table.h"

namespace glarecam::pipeline {

struct SweepOptions {
  std::filesystem::path output_directory = "sweep";
  unsigned jobs = 0;     // stacks processed at once; 0: one per core (at most `threads`)
  unsigned threads = 0;  // threads in all, shared by the jobs; 0: all cores
  // Memory the jobs may hold at once: no more jobs run than fit, by processMemoryBytes() of the
  // largest stack (at least one job always runs). 0: half the physical memory.
  std::uint64_t memory_budget_bytes = 0;
  std::optional<std::filesystem::path> calibration_file;
  std::optional<double> threshold_cd_m2;  // a constant glare limit instead of the α curve
  bool show_progress = true;
  bool float32 = false;  // each result's images at full float32 precision (ProcessOptions)
  // Rows of different cameras, frame sizes or calibrations in one table (mixedFields()) are
  // refused unless allowed: their fits would describe no one module measurement.
  bool allow_mixed = false;
  // α for stacks that record none (sweep --alpha-from), by the stack directory's name: given to
  // process as --alpha (result.json's alpha_source "given"); one that contradicts a stack's own
  // α skips that stack.
  std::map<std::string, double> given_alpha_deg;
};

// The α table of `sweep --alpha-from`: CSV with a header naming `stack` (a stack directory's
// name) and `alpha_deg` columns (others ignored, '#' lines allowed), α in [0, 90), each stack
// once. Errors name the file and line.
Result<std::map<std::string, double>> readAlphaTable(const std::filesystem::path& path);

struct SkippedStack {
  std::filesystem::path stack;
  Error error;
};

struct SweepSummary {
  unsigned jobs = 0;                     // stacks processed at once
  std::uint64_t stack_memory_bytes = 0;  // the largest stack's processMemoryBytes() (0: unknown)
  SweepTable table;
  std::vector<SkippedStack> skipped;
  std::filesystem::path sweep_csv;
  ContourTable contours;  // the rows' stacks' ladders (contours.csv)
  std::filesystem::path contours_csv;
};

inline constexpr const char* kSweepTableFileName = "sweep.csv";
inline constexpr const char* kSweepResultsDirectory = "results";

struct StackSearch {
  std::vector<std::filesystem::path> stacks;
  std::vector<SkippedStack> skipped;  // inputs that are neither a stack nor hold any
};

// The stacks named by `inputs`: a stack directory stands for itself, any other directory for
// the directories directly inside it that hold a stack.json (sorted by name; a broken one is
// found here and reported when processing it fails).
StackSearch findStacks(const std::vector<std::filesystem::path>& inputs);

// About the most memory `process` of this stack holds at once, from its manifest (the frames) and
// its first frame's header (their size); nothing when either cannot be read (processing it will
// say why).
std::optional<std::uint64_t> processMemoryBytes(const std::filesystem::path& stack);

// Processes the stacks and writes the table, listing every skipped input and stack. Fails only
// when no stack could be processed (with the first error) or the table cannot be written.
Result<SweepSummary> runSweep(const StackSearch& search, const SweepOptions& options);

// What differs among the rows ("camera (sim SIM-0001, aravis 40012345); calibration (...)"), or
// empty when they share one camera, frame size and calibration. Rows that do not say (tables of
// other tools) are not compared.
std::string mixedFields(const SweepTable& table);

// `sweep --strict`: the first skipped stack's error (its code), else kBadInput naming the first
// suspect row (frames that disagree) and why, else nothing.
Status checkStrict(const SweepSummary& summary);

}  // namespace glarecam::pipeline
