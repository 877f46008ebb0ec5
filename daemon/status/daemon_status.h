// What glarecamd is doing, as one value: the loop updates it, STATUS= and the status LED are
// derived from it (pure functions, so that every combination of faults is testable), and tests
// read it.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/source_illuminance.h"
#include "core/time.h"
#include "daemon/stack_worker.h"
#include "daemon/storage/day_products.h"
#include "daemon/storage/retention.h"
#include "rig/gpio/status_led.h"

namespace glarecam::daemon {

// The last day whose products were rebuilt, or read back from disk at start.
struct LastDay {
  std::string day;                  // "2026-06-21"
  std::filesystem::path directory;  // days/<day>/ (datasheet.png)
  std::size_t stacks = 0;
  bool datasheet = false;
};

// What the daemon is doing, for STATUS=, `glarecam doctor`, the status page and tests.
struct DaemonState {
  bool ready = false;      // READY=1 sent
  bool capturing = false;  // a bracket is running
  bool stopping = false;   // SIGTERM received
  std::string status;      // the last STATUS= line
  rig::RigState led = rig::RigState::ready();
  std::optional<std::string> last_stack;
  std::optional<double> last_alpha_deg;
  std::optional<UtcTime> last_capture_time;
  std::optional<UtcTime> next_capture_time;
  std::optional<double> next_target_deg;
  std::string camera_fault;          // why the camera is closed
  std::string disk_fault;            // why capture pauses for the disk
  std::string inclinometer_fault;    // the last read's failure
  std::string clock_warning;         // the clock is not synchronised
  std::string gpio_fault;            // the GPIO could not be opened
  std::string config_warning;        // the last reload failed
  std::string worker_fault;          // the last write, processing or publishing failure
  std::string skip_reason;           // why the last scheduled stack was not taken
  std::string day;                   // the last day's products ("2026-06-21: 16 stacks, ...")
  bool inclinometer_pauses = false;  // capture waits for the inclinometer ([faults])
  std::uint64_t stacks_captured = 0, stacks_written = 0, stacks_processed = 0, stacks_failed = 0;
  std::uint64_t captures_skipped = 0, watchdog_pings = 0, reloads = 0;
  // Retention (retention.h): entries deleted so far, and why it could not free enough (empty
  // when it could, or had nothing to do).
  std::uint64_t stacks_deleted = 0, result_images_pruned = 0, results_deleted = 0, days_deleted = 0;
  // The shortfall is today's stacks alone (the budget is smaller than one day's stacks).
  bool retention_day_overflows = false;
  // The settings check's: max_use_gib cannot hold one day's stacks (day_budget.h), or empty.
  std::string retention_budget_warning;
  std::string retention_shortfall;
  std::string retention_last;  // the last pass that deleted: "deleted stack … (12.0 MiB): …"
  std::optional<UtcTime> retention_last_time;
  // For the status page: the last stack processed, the last day rebuilt, the disk at its last
  // look, and how long capture has been paused in all (disk, inclinometer).
  std::optional<LastResult> last_result;
  std::optional<LastDay> last_day;
  std::optional<DiskState> disk;
  double paused_seconds = 0;
  // The illuminance instrument ([illuminance], illuminance_session.h): what it is, the last
  // bracket's source it gave, and why the last stacks are unreferred (a warning: capture goes on).
  std::string illuminance_instrument;
  std::string illuminance_fault;
  std::optional<SourceIlluminance> last_source_illuminance;
  std::optional<UtcTime> last_illuminance_time;
  std::uint64_t illuminance_failures = 0;
};

// Capture waits: for the disk, or for the inclinometer ([faults] inclinometer = "pause").
bool capturePaused(const DaemonState& state);

// The faults in the words of the status line ("camera: …", "disk: …", "inclinometer: …",
// "illuminance: …" (a warning: the stacks go on, unreferred), "clock: …", "GPIO: …", "config: …",
// "worker: …", "retention: …"), most urgent first.
std::vector<std::string> statusFaults(const DaemonState& state);

// The status page's one word for what the rig does, and why: "stopping"; "fault" while the
// camera is lost; "paused" while capture waits; "fault" while the inclinometer, the GPIO, a
// reload or the worker's last job failed (capture goes on); "starting" until the camera first
// opens; else "capturing" (with a clock or retention warning, if any, as its reason). `reason`:
// statusFaults(), "; "-joined.
struct RigActivity {
  std::string state;
  std::string reason;
};
RigActivity rigActivity(const DaemonState& state);

// How a disk fault from a failed write begins: it ends only when the kept stacks are written.
inline constexpr std::string_view kWriteFailed = "writing a stack failed: ";
// How a disk fault from a refused processing begins (its result could not be written): it ends
// when the kept stacks are processed, or given up and left for the next start.
inline constexpr std::string_view kProcessingFailed = "processing a stack failed: ";
// A disk fault of the worker's kept stacks (either of the above): retried, not probed.
inline bool isKeptStackFault(std::string_view disk_fault) {
  return disk_fault.starts_with(kWriteFailed) || disk_fault.starts_with(kProcessingFailed);
}

// What a report of the stack worker (stack_worker.h) changes in `state`, logged: the counters, a
// disk fault while a stack whose write failed is kept (`kept_remaining`: stacks still kept after
// this report), the worker's last fault, the day's products.
void recordWorkerEvent(DaemonState& state, const WorkerEvent& event, bool kept_remaining);

// What one retention pass changes in `state`: the counts, the shortfall (logged when it starts,
// ends or changes kind; each failed deletion logged as a warning). A pass that did not look at
// the disk (`disk_checked` false) leaves a reserve shortfall as it is.
void recordRetention(DaemonState& state, const RetentionSummary& summary, bool disk_checked = true);

// The day's products as the status shows them (the day's line, its stack count, its sheet), from
// a report of the worker or, for a glarecamd that starts again during a day, from the disk.
void recordDay(DaemonState& state, const DaySummary& day);

// The STATUS= line: what the daemon does, its last and next stack and every fault, e.g.
// "capturing every 600 s; last 20260621T101503Z-a42.30 (α 42.30°) at 10:15:03Z; next at
// 10:25:03Z; camera lost: ...; reopening in 8 s (failure 2 of 8)". `schedule` describes the
// schedule ("every 600 s", "at α targets", "on the button").
std::string statusLine(const DaemonState& state, const std::string& schedule);

// What the LED shows: capturing while a bracket runs, else the most urgent fault (camera, disk,
// inclinometer, clock), else ready.
rig::RigState ledState(const DaemonState& state, bool capturing);

}  // namespace glarecam::daemon
