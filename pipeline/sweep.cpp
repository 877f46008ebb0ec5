#include "pipeline/sweep.h"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <spdlog/spdlog.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <charconv>
#include <future>
#include <mutex>
#include <set>

#include "core/atomic_file.h"
#include "core/csv.h"
#include "core/image_io.h"
#include "core/json.h"
#include "core/parallel.h"
#include "core/progress.h"
#include "core/stack_manifest.h"
#include "pipeline/contour_table.h"
#include "pipeline/datasheet.h"
#include "pipeline/glare_profile.h"
#include "pipeline/process_stack.h"

namespace glarecam::pipeline {

namespace fs = std::filesystem;

namespace {

std::string baseName(const fs::path& stack) {
  const std::string name = stack.filename().string();
  return name.empty() || name == "." || name == ".." ? "stack" : name;
}

// A result directory per stack, named after it; a stack whose name is taken gets the first free
// "-2", "-3", … (free also of the names other stacks have as they are).
std::vector<fs::path> resultDirectories(const std::vector<fs::path>& stacks, const fs::path& out) {
  std::set<std::string> taken;
  for (const fs::path& stack : stacks) taken.insert(baseName(stack));
  std::set<std::string> used;
  std::vector<fs::path> directories;
  for (const fs::path& stack : stacks) {
    const std::string base = baseName(stack);
    std::string name = base;
    for (int n = 2; used.contains(name) || (name != base && taken.contains(name)); ++n)
      name = base + "-" + std::to_string(n);
    used.insert(name);
    directories.push_back(out / kSweepResultsDirectory / name);
  }
  return directories;
}

// Peak memory of `process` per pixel (measured as peak resident size less the executable's own,
// --threads 1 and 2): 46 bytes at 1224x1024 and 39 at 2592x1944 with 6 frames, of which 2 a frame
// for the decoded frames and the rest the merge's images, the encoders' copies and the encoded
// files. A lobe many pixels across adds its smoothed contour field (pipeline/level_field.h: a
// copy of the luminance and double sums over the region's box): 48 bytes at 2592x1944 with the
// lobe 1300 px across its limit contour (peak resident 241 MB against 166 MB for a small lobe).
// Rounded up: a budget errs on the safe side.
constexpr std::uint64_t kProcessBytesPerPixel = 52;
constexpr std::uint64_t kFrameBytesPerPixel = 2;

std::uint64_t physicalMemoryBytes() {
  const long pages = sysconf(_SC_PHYS_PAGES), page_bytes = sysconf(_SC_PAGE_SIZE);
  return pages > 0 && page_bytes > 0 ? static_cast<std::uint64_t>(pages) * page_bytes : 0;
}

// The jobs that fit in the budget, at least one.
unsigned jobsWithinMemory(unsigned jobs, const std::vector<fs::path>& stacks,
                          const SweepOptions& options, std::uint64_t& stack_bytes) {
  stack_bytes = 0;
  for (const fs::path& stack : stacks)
    stack_bytes = std::max(stack_bytes, processMemoryBytes(stack).value_or(0));
  const std::uint64_t budget =
      options.memory_budget_bytes != 0 ? options.memory_budget_bytes : physicalMemoryBytes() / 2;
  if (stack_bytes == 0 || budget == 0) return jobs;
  const auto fitting = static_cast<unsigned>(std::min<std::uint64_t>(budget / stack_bytes, jobs));
  return std::max(1u, fitting);
}

// A stack without a valid α is refused before the seconds of processing it.
Status checkAlpha(const fs::path& stack) {
  const auto manifest = readJsonFile(stack / kManifestFileName);
  if (!manifest) return {};  // processStack names what is wrong
  const auto alpha =
      JsonReader(*manifest, std::string(kManifestFileName)).optionalNumber("alpha_deg");
  if (!alpha) return {};  // likewise
  return validateSweepAlpha(*alpha);
}

// One processed stack: its row of sweep.csv and its rows of contours.csv.
struct SweptStack {
  SweepRow row;
  std::vector<ContourRow> contours;
};

Result<SweptStack> processOne(const fs::path& stack, const fs::path& result_directory,
                              const SweepOptions& options, unsigned threads_per_job) {
  const auto given = options.given_alpha_deg.find(stack.filename().string());
  const std::optional<double> given_alpha_deg =
      given != options.given_alpha_deg.end() ? std::optional(given->second) : std::nullopt;
  if (!given_alpha_deg) GLARECAM_CHECK(checkAlpha(stack));  // the caller names the stack
  ProcessOptions process{.calibration_file = options.calibration_file,
                         .output_directory = result_directory,
                         .threshold_cd_m2 = options.threshold_cd_m2,
                         .thresholds_cd_m2 = {},
                         .alpha_deg = given_alpha_deg,
                         .threads = threads_per_job,
                         .show_progress = false,
                         .float32 = options.float32,
                         .calibration_use = {}};
  // Runs on a worker thread: an exception (out of memory, a bug) must skip this stack, not
  // terminate the process and lose every other stack's work.
  return catchExceptions([&]() -> Result<SweptStack> {
    auto summary = processStack(stack, process);
    if (!summary) return std::unexpected(summary.error());
    SweptStack swept;
    GLARECAM_ASSIGN(swept.row, sweepRowFromResult(summary->result, stack.string()));
    swept.contours = contourRowsFromResult(summary->result);
    return swept;
  });
}

// An output directory reused from an earlier sweep keeps that sweep's data sheet and results of
// stacks not in this one: nothing is deleted (they may be wanted), but a reader must not take them
// for this sweep's.
void warnAboutEarlierOutputs(const fs::path& out, const std::vector<fs::path>& results) {
  for (const char* name : {kDatasheetPdf, kGlareProfileFileName}) {
    if (fs::exists(out / name))
      spdlog::warn("sweep: {} is from an earlier run: run glarecam datasheet again",
                   (out / name).string());
  }
  std::error_code ec;
  int others = 0;
  for (const auto& entry : fs::directory_iterator(out / kSweepResultsDirectory, ec)) {
    if (entry.path().filename().string().starts_with(kTemporaryPrefix)) continue;
    others += std::find(results.begin(), results.end(), entry.path()) == results.end();
  }
  if (others > 0)
    spdlog::warn("sweep: {} holds {} result(s) of stacks not in this sweep (an earlier run)",
                 (out / kSweepResultsDirectory).string(), others);
}

// The error the whole sweep fails with when nothing could be processed: bad input if every
// stack was bad input, otherwise the first other failure.
Error noStackError(const std::vector<SkippedStack>& skipped) {
  for (const SkippedStack& s : skipped) {
    if (s.error.code != ErrorCode::kBadInput)
      return withContext(s.error, "no stack could be processed; " + s.stack.string());
  }
  return withContext(skipped.front().error,
                     "no stack could be processed; " + skipped.front().stack.string());
}

}  // namespace

namespace {

// "a/s1/" and "a/./s1" as "a/s1", so that the name is the directory's.
fs::path normalised(const fs::path& input) {
  fs::path path = input.lexically_normal();
  return path.filename().empty() && path.has_parent_path() ? path.parent_path() : path;
}

// Drops stacks named twice (through different spellings), keeping the first.
std::vector<fs::path> withoutDuplicates(const std::vector<fs::path>& stacks) {
  std::vector<fs::path> unique, seen;
  for (const fs::path& stack : stacks) {
    std::error_code ec;
    fs::path identity = fs::weakly_canonical(stack, ec);
    if (ec) identity = fs::absolute(stack);
    if (std::find(seen.begin(), seen.end(), identity) != seen.end()) {
      spdlog::warn("sweep: {} given twice, processed once", stack.string());
      continue;
    }
    seen.push_back(identity);
    unique.push_back(stack);
  }
  return unique;
}

}  // namespace

StackSearch findStacks(const std::vector<fs::path>& raw_inputs) {
  std::vector<fs::path> inputs;
  for (const fs::path& input : raw_inputs) inputs.push_back(normalised(input));
  StackSearch search;
  auto skip = [&](const fs::path& input, Error error) {
    search.skipped.push_back({input, std::move(error)});
  };
  for (const fs::path& input : inputs) {
    std::error_code ec;
    if (fs::is_regular_file(input / kManifestFileName, ec)) {
      search.stacks.push_back(input);
      continue;
    }
    if (!fs::is_directory(input, ec)) {
      skip(input, {ErrorCode::kBadInput, "no such stack or directory of stacks"});
      continue;
    }
    std::vector<fs::path> inside;
    for (const auto& entry : fs::directory_iterator(input, ec)) {
      std::error_code unreadable;  // an unreadable child is not a stack, not a listing failure
      if (fs::is_regular_file(entry.path() / kManifestFileName, unreadable))
        inside.push_back(entry.path());
    }
    if (ec) {
      skip(input, {ErrorCode::kIo, "cannot list: " + ec.message()});
    } else if (inside.empty()) {
      skip(input,
           {ErrorCode::kBadInput, "neither a stack (no stack.json) nor a directory of stacks"});
    }
    std::sort(inside.begin(), inside.end());
    search.stacks.insert(search.stacks.end(), inside.begin(), inside.end());
  }
  search.stacks = withoutDuplicates(search.stacks);
  return search;
}

Result<SweepSummary> runSweep(const StackSearch& search, const SweepOptions& options) {
  const std::vector<fs::path>& stacks = search.stacks;
  GLARECAM_CHECK(ensureDirectory(options.output_directory));  // before the minutes of processing
  SweepSummary summary;
  summary.skipped = search.skipped;
  if (stacks.empty()) {
    if (summary.skipped.empty()) return badInput("no stacks to sweep");
    return std::unexpected(noStackError(summary.skipped));
  }
  const unsigned threads = options.threads ? options.threads : availableThreads();
  const auto most_jobs = static_cast<unsigned>(std::min<std::size_t>(stacks.size(), threads));
  std::uint64_t stack_bytes = 0;
  const unsigned jobs =
      jobsWithinMemory(std::clamp(options.jobs ? options.jobs : threads, 1u, most_jobs), stacks,
                       options, stack_bytes);
  summary.jobs = jobs;
  summary.stack_memory_bytes = stack_bytes;
  spdlog::info("sweep: {} stacks, {} at once with {} threads each (about {} MB each)",
               stacks.size(), jobs, std::max(1u, threads / jobs), stack_bytes >> 20);
  const unsigned threads_per_job = std::max(1u, threads / jobs);
  const std::vector<fs::path> results = resultDirectories(stacks, options.output_directory);
  for (const auto& [name, alpha_deg] : options.given_alpha_deg) {
    if (std::ranges::none_of(stacks, [&](const fs::path& s) { return s.filename() == name; }))
      spdlog::warn("sweep: --alpha-from names {} (α {:g}°), which is not among the stacks", name,
                   alpha_deg);
  }

  std::vector<std::optional<Result<SweptStack>>> outcomes(stacks.size());
  std::atomic<std::size_t> next{0};
  std::mutex progress_mutex;
  Progress progress("sweep", static_cast<int>(stacks.size()), options.show_progress);
  auto worker = [&] {
    for (std::size_t i; (i = next++) < stacks.size();) {
      outcomes[i] = processOne(stacks[i], results[i], options, threads_per_job);
      const std::lock_guard lock(progress_mutex);
      progress.advance(stacks[i].filename().string());
    }
  };
  {
    // Each job's thread gets its share of the threads (processStack sets it again from
    // threads_per_job); the caller is the first job.
    std::vector<std::future<void>> others;
    for (unsigned j = 1; j < jobs; ++j) others.push_back(runTask(threads_per_job, worker));
    worker();
    for (std::future<void>& job : others) job.get();
  }
  progress.finish();

  for (std::size_t i = 0; i < stacks.size(); ++i) {
    if (*outcomes[i]) {
      summary.table.rows.push_back(std::move((*outcomes[i])->row));
      for (ContourRow& row : (*outcomes[i])->contours)
        summary.contours.rows.push_back(std::move(row));
    } else {
      summary.skipped.push_back({stacks[i], outcomes[i]->error()});
    }
  }
  for (const SkippedStack& s : summary.skipped) {
    spdlog::warn("sweep: skipped {}: {}", s.stack.string(), s.error.message);
    summary.table.notes.push_back("skipped " + s.stack.string() + ": " + s.error.message);
  }
  if (summary.table.rows.empty()) return std::unexpected(noStackError(summary.skipped));
  if (const std::string mixed = mixedFields(summary.table); !mixed.empty()) {
    if (!options.allow_mixed)
      return badInput("sweep: the stacks differ in " + mixed +
                      ": one table is one module measured with one camera and calibration "
                      "(--mixed to write it anyway)");
    spdlog::warn("sweep: the stacks differ in {} (--mixed)", mixed);
    summary.table.notes.push_back("mixed: the stacks differ in " + mixed);
  }
  if (const std::string mixed = mixedReferences(summary.table); !mixed.empty()) {
    if (!options.allow_mixed)
      return badInput(
          "sweep: the stacks' luminances are not referred to one illuminance (" + mixed +
          "): give every stack its source illuminance, or --mixed to write the "
          "table anyway (docs/method.md \"Reference illuminance and the contour ladder\")");
    spdlog::warn("sweep: the stacks are referred differently: {} (--mixed)", mixed);
    summary.table.notes.push_back("mixed references: " + mixed);
  }
  summary.sweep_csv = options.output_directory / kSweepTableFileName;
  GLARECAM_CHECK(writeFileAtomic(summary.sweep_csv, formatSweepTable(summary.table)));
  summary.contours_csv = options.output_directory / kContourTableFileName;
  GLARECAM_CHECK(writeFileAtomic(summary.contours_csv, formatContourTable(summary.contours)));
  warnAboutEarlierOutputs(options.output_directory, results);
  return summary;
}

std::optional<std::uint64_t> processMemoryBytes(const fs::path& stack) {
  auto document = readJsonFile((stack / kManifestFileName).string());
  if (!document) return std::nullopt;
  auto manifest = parseManifest(*document, (stack / kManifestFileName).string());
  if (!manifest || manifest->frames.empty()) return std::nullopt;
  auto size = readFrameSize(stack / manifest->frames.front().file);
  if (!size) return std::nullopt;
  const auto pixels = static_cast<std::uint64_t>(size->width) * size->height;
  return pixels * (kProcessBytesPerPixel + kFrameBytesPerPixel * manifest->frames.size());
}

Result<std::map<std::string, double>> readAlphaTable(const fs::path& path) {
  std::map<std::string, double> alpha_by_stack;
  std::optional<std::size_t> stack_column, alpha_column;
  GLARECAM_CHECK(readCsvFile(path, "α table", [&](std::vector<std::string>& fields) -> Status {
    if (!stack_column) {
      for (std::size_t i = 0; i < fields.size(); ++i) {
        if (fields[i] == "stack") stack_column = i;
        if (fields[i] == "alpha_deg") alpha_column = i;
      }
      if (!stack_column || !alpha_column)
        return badInput("the header must name the columns stack and alpha_deg");
      return {};
    }
    if (fields.size() <= std::max(*stack_column, *alpha_column))
      return badInput("fewer fields than the header");
    const std::string& stack = fields[*stack_column];
    const std::string& text = fields[*alpha_column];
    double alpha_deg = 0;
    const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), alpha_deg);
    if (stack.empty() || error != std::errc() || end != text.data() + text.size())
      return badInput(
          fmt::format("expected a stack name and a number, got \"{}\", \"{}\"", stack, text));
    GLARECAM_CHECK(validateSweepAlpha(alpha_deg));
    if (!alpha_by_stack.emplace(stack, alpha_deg).second)
      return badInput(fmt::format("stack {} is given twice", stack));
    return {};
  }));
  if (!stack_column) return badInput(path.string() + ": empty α table (no header)");
  return alpha_by_stack;
}

std::string mixedFields(const SweepTable& table) {
  const std::pair<const char*, std::vector<std::string>> fields[] = {
      {"module", tableModules(table)},
      {"camera", tableCameras(table)},
      {"frame size", tableFrameSizes(table)},
      {"calibration", tableCalibrations(table)}};
  std::string mixed;
  for (const auto& [name, values] : fields) {
    if (values.size() < 2) continue;
    mixed += fmt::format("{}{} ({})", mixed.empty() ? "" : "; ", name, fmt::join(values, ", "));
  }
  return mixed;
}

Status checkStrict(const SweepSummary& summary) {
  if (!summary.skipped.empty()) {
    const SkippedStack& first = summary.skipped.front();
    return std::unexpected(withContext(
        first.error, fmt::format("--strict: {} stack(s) or input(s) skipped, the first {}",
                                 summary.skipped.size(), first.stack.string())));
  }
  const auto suspect = std::ranges::count_if(summary.table.rows, &SweepRow::isSuspect);
  if (suspect == 0) return {};
  const SweepRow& first = *std::ranges::find_if(summary.table.rows, &SweepRow::isSuspect);
  return badInput(fmt::format("--strict: {} suspect row(s), the first {}: {}", suspect, first.stack,
                              first.suspect));
}

}  // namespace glarecam::pipeline
