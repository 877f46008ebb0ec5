#include "daemon/status/daemon_status.h"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <vector>

namespace glarecam::daemon {

void recordWorkerEvent(DaemonState& state, const WorkerEvent& event, bool kept_remaining) {
  const bool written = event.stage == WorkerEvent::Stage::kWritten;
  if (event.error && !event.last && event.stage != WorkerEvent::Stage::kPublished) {
    // Kept by the worker: capture pauses until the disk takes a write again.
    state.disk_fault = written ? fmt::format("{}{}; it is kept until the disk takes it",
                                             kWriteFailed, event.error->message)
                               : fmt::format("{}{}; it is processed again once the disk takes it",
                                             kProcessingFailed, event.error->message);
    spdlog::error("glarecamd: {}: {}", event.stack_id, state.disk_fault);
    return;
  }
  // The last kept stack written or processed, or its processing given up (it is on disk, safe,
  // for the next start): the pause for them ends. A write given up keeps the pause: the disk
  // takes no stacks.
  const bool kept_done = event.stage != WorkerEvent::Stage::kPublished && !(event.error && written);
  if (kept_done && isKeptStackFault(state.disk_fault) && !kept_remaining) {
    spdlog::info("glarecamd: disk: the kept stacks are {}; capture resumes",
                 event.error ? "left for the next start"
                 : written   ? "written"
                             : "processed");
    state.disk_fault.clear();
  }
  if (event.error) {
    ++state.stacks_failed;
    state.worker_fault = event.error->message;
    spdlog::error("glarecamd: {}: {}", event.stack_id, event.error->message);
    return;
  }
  switch (event.stage) {
    case WorkerEvent::Stage::kWritten:
      ++state.stacks_written;
      spdlog::info("glarecamd: wrote {}", event.path.string());
      return;
    case WorkerEvent::Stage::kProcessed:
      ++state.stacks_processed;
      if (event.result)
        state.last_result = {
            .stack_id = event.stack_id, .directory = event.path, .brief = *event.result};
      spdlog::info("glarecamd: processed {}", event.detail);
      break;
    case WorkerEvent::Stage::kPublished:
      recordDay(state, {.day = event.path.filename().string(),
                        .directory = event.path,
                        .stacks = event.day_stacks,
                        .datasheet = event.day_datasheet,
                        .detail = event.detail});
      spdlog::info("glarecamd: day {}", state.day);
      break;
  }
  state.worker_fault.clear();
}

void recordDay(DaemonState& state, const DaySummary& day) {
  state.last_day = {
      .day = day.day, .directory = day.directory, .stacks = day.stacks, .datasheet = day.datasheet};
  state.day = fmt::format("{}: {}", day.day, day.detail);
}

void recordRetention(DaemonState& state, const RetentionSummary& summary, bool disk_checked) {
  for (const RetentionDeletion& deleted : summary.deleted) {
    if (deleted.kind == kDeletedStack) ++state.stacks_deleted;
    if (deleted.kind == kDeletedResultImages) ++state.result_images_pruned;
    if (deleted.kind == kDeletedResult) ++state.results_deleted;
    if (deleted.kind == kDeletedDay) ++state.days_deleted;
    // The last result's picture is gone with its images; its numbers stay on the page.
    if (state.last_result && state.last_result->stack_id == deleted.name &&
        (deleted.kind == kDeletedResultImages || deleted.kind == kDeletedResult))
      state.last_result->images_pruned = true;
  }
  if (!summary.deleted.empty()) {
    const RetentionDeletion& last = summary.deleted.back();
    state.retention_last = fmt::format("deleted {} {} ({}): {}", last.kind, last.name,
                                       formatBytes(last.bytes), last.reason);
    if (summary.deleted.size() > 1)
      state.retention_last +=
          fmt::format(", with {} more ({} freed in all)", summary.deleted.size() - 1,
                      formatBytes(summary.freed_bytes));
  }
  for (const std::string& error : summary.errors) spdlog::warn("glarecamd: retention: {}", error);
  const auto reserve = [](const std::string& shortfall) {
    return shortfall.find("reserve") != std::string::npos;
  };
  if (!disk_checked && summary.shortfall.empty() && reserve(state.retention_shortfall)) return;
  // Logged when it starts, ends or changes kind, not for every stack or byte.
  const bool changed = summary.shortfall.empty() != state.retention_shortfall.empty() ||
                       reserve(summary.shortfall) != reserve(state.retention_shortfall);
  if (changed && summary.shortfall.empty())
    spdlog::info("glarecamd: retention: within its limits again");
  else if (changed)
    spdlog::warn("glarecamd: retention: {}", summary.shortfall);
  state.retention_shortfall = summary.shortfall;
  state.retention_day_overflows = summary.day_overflows;
}

namespace {

std::string seconds(UtcTime time) {
  return formatIsoTime(std::chrono::floor<std::chrono::seconds>(time));
}

const char* phase(const DaemonState& state) {
  if (state.stopping) return "stopping";
  if (!state.ready) return "starting";
  if (state.capturing) return "capturing";
  if (capturePaused(state)) return "paused";
  if (!state.camera_fault.empty()) return "waiting for the camera";
  return "ready";
}

}  // namespace

bool capturePaused(const DaemonState& state) {
  return !state.disk_fault.empty() ||
         (state.inclinometer_pauses && !state.inclinometer_fault.empty());
}

std::vector<std::string> statusFaults(const DaemonState& state) {
  std::vector<std::string> faults;
  const auto add = [&faults](const std::string& prefix, const std::string& text) {
    if (!text.empty()) faults.push_back(prefix + text);
  };
  add("camera: ", state.camera_fault);
  add("disk: ", state.disk_fault);
  add("inclinometer: ", state.inclinometer_fault);
  add("illuminance: ", state.illuminance_fault);
  add("clock: ", state.clock_warning);
  add("GPIO: ", state.gpio_fault);
  add("config: ", state.config_warning);
  add("worker: ", state.worker_fault);
  add("retention: ", state.retention_shortfall);
  return faults;
}

RigActivity rigActivity(const DaemonState& state) {
  const std::string reason = fmt::format("{}", fmt::join(statusFaults(state), "; "));
  if (state.stopping) return {"stopping", reason};
  if (!state.camera_fault.empty()) return {"fault", reason};
  if (capturePaused(state)) return {"paused", reason};
  // A clock not synchronised or a budget retention cannot keep are warnings: stacks go on.
  const bool fault = !state.inclinometer_fault.empty() || !state.gpio_fault.empty() ||
                     !state.config_warning.empty() || !state.worker_fault.empty();
  if (fault) return {"fault", reason};
  if (!state.ready) return {"starting", reason};
  return {"capturing", reason};
}

std::string statusLine(const DaemonState& state, const std::string& schedule) {
  std::vector<std::string> parts{fmt::format("{}, {}", phase(state), schedule)};
  if (state.last_stack) {
    std::string last = "last " + *state.last_stack;
    if (state.last_alpha_deg) last += fmt::format(" (α {:.2f}°)", *state.last_alpha_deg);
    if (state.last_capture_time) last += " at " + seconds(*state.last_capture_time);
    parts.push_back(std::move(last));
  }
  if (state.next_capture_time && !state.stopping) {
    std::string next = "next at " + seconds(*state.next_capture_time);
    if (state.next_target_deg) next += fmt::format(" (α {:g}°)", *state.next_target_deg);
    parts.push_back(std::move(next));
  }
  std::vector<std::string> faults = statusFaults(state);
  // The retention shortfall goes last, after why a stack was skipped.
  std::optional<std::string> retention;
  if (!state.retention_shortfall.empty()) {
    retention = std::move(faults.back());
    faults.pop_back();
  } else if (state.stacks_deleted + state.result_images_pruned + state.results_deleted +
                 state.days_deleted >
             0) {
    retention = fmt::format("retention deleted {} stacks, {} result images, {} results, {} days",
                            state.stacks_deleted, state.result_images_pruned, state.results_deleted,
                            state.days_deleted);
  }
  parts.insert(parts.end(), faults.begin(), faults.end());
  if (!state.skip_reason.empty()) parts.push_back("skipped: " + state.skip_reason);
  if (retention) parts.push_back(std::move(*retention));
  return fmt::format("{}", fmt::join(parts, "; "));
}

rig::RigState ledState(const DaemonState& state, bool capturing) {
  if (capturing) return rig::RigState::capturing();
  if (!state.camera_fault.empty()) return rig::RigState::faulted(rig::FaultCode::kCamera);
  if (!state.disk_fault.empty()) return rig::RigState::faulted(rig::FaultCode::kDisk);
  if (!state.inclinometer_fault.empty())
    return rig::RigState::faulted(rig::FaultCode::kInclinometer);
  if (!state.clock_warning.empty()) return rig::RigState::faulted(rig::FaultCode::kClock);
  return rig::RigState::ready();
}

}  // namespace glarecam::daemon
