#include "daemon/status/status_page.h"

#include <fmt/format.h>

#include <chrono>
#include <cmath>

#include "core/json.h"
#include "core/time.h"
#include "core/version.h"
#include "daemon/storage/output_tree.h"

namespace glarecam::daemon {

namespace {

using nlohmann::json;

// The rig's states, as rigActivity() names them, in the order /metrics lists them.
constexpr std::array<const char*, 5> kStates{"starting", "capturing", "paused", "fault",
                                             "stopping"};

std::string isoSeconds(UtcTime time) {
  return formatIsoTime(std::chrono::floor<std::chrono::seconds>(time));
}

std::string isoSeconds(std::chrono::system_clock::time_point time) {
  return isoSeconds(std::chrono::time_point_cast<std::chrono::microseconds>(time));
}

// A time of the daemon's clock as the page shows it: marked "sim" when it is a time lapse's
// (glarecamd --simulate), which the machine's times of the log are not.
std::string daemonTime(const StatusSnapshot& s, UtcTime time) {
  return isoSeconds(time) + (s.simulated_time ? " sim" : "");
}

// A log entry's time: the machine's, and the simulated clock's beside it, marked.
std::string logTime(const LogEntry& entry) {
  std::string text = isoSeconds(entry.time);
  if (entry.simulated_time) text += " (sim " + isoSeconds(*entry.simulated_time) + ")";
  return text;
}

json optionalText(const std::string& text) { return text.empty() ? json(nullptr) : json(text); }

double unixSeconds(UtcTime time) {
  return std::chrono::duration<double>(time.time_since_epoch()).count();
}

// "Lmax ≥ 5.4e+05 cd/m²" as the brief tells it.
std::string lmaxText(const ResultBrief& brief) {
  const char* bound = brief.lmax_bound == "lower" ? "≥ " : brief.lmax_bound == "upper" ? "≤ " : "";
  return fmt::format("{}{:.4g} cd/m²", bound, brief.lmax_cd_m2);
}

std::string verdictText(const ResultBrief& brief) {
  if (!brief.glare) return "no verdict (no glare limit at this α)";
  return *brief.glare ? "glare: Lmax above the limit" : "no glare: Lmax below the limit";
}

std::string dayStacksText(const StatusSnapshot& s) {
  if (s.state.last_day && s.state.last_day->day == s.today)
    return fmt::format("{}", s.state.last_day->stacks);
  return "none processed yet today";
}

}  // namespace

std::string htmlEscape(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (const char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&#39;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

std::optional<std::filesystem::path> statusPicture(const StatusSnapshot& s, StatusPicture picture) {
  switch (picture) {
    case StatusPicture::kLastStack:
      if (!s.state.last_result || s.state.last_result->images_pruned) return std::nullopt;
      return s.state.last_result->directory / "luminance.png";
    case StatusPicture::kDatasheet:
      if (s.output_root.empty() || s.today.empty()) return std::nullopt;
      return s.output_root / kDaysDirectory / s.today / kDatasheetPictureName;
  }
  return std::nullopt;
}

std::string statusPictureMissing(const StatusSnapshot& s, StatusPicture picture) {
  if (picture == StatusPicture::kDatasheet) return "no data sheet today yet";
  if (!s.state.last_result) return "no stack processed yet";
  if (s.state.last_result->images_pruned)
    return fmt::format("the images of {} were pruned by retention (its numbers stay)",
                       s.state.last_result->stack_id);
  return fmt::format("no picture of {}", s.state.last_result->stack_id);
}

json statusJson(const StatusSnapshot& s, const std::vector<LogEntry>& log) {
  const DaemonState& st = s.state;
  const RigActivity activity = rigActivity(st);
  json last_stack = nullptr;
  if (st.last_stack) {
    last_stack = {{"id", *st.last_stack},
                  {"captured_at",
                   st.last_capture_time ? json(isoSeconds(*st.last_capture_time)) : json(nullptr)},
                  {"alpha_deg", finiteOrNull(st.last_alpha_deg)}};
  }
  json last_result = nullptr;
  if (st.last_result) {
    const ResultBrief& b = st.last_result->brief;
    last_result = {
        {"id", st.last_result->stack_id},
        {"alpha_deg", finiteOrNull(b.alpha_deg)},
        {"lmax_cd_m2", b.lmax_cd_m2},
        {"lmax_bound", optionalText(b.lmax_bound)},
        {"limit_cd_m2", finiteOrNull(b.limit_cd_m2)},
        {"glare", jsonOrNull(b.glare)},
        {"images_pruned", st.last_result->images_pruned},
        {"picture", st.last_result->images_pruned ? json(nullptr) : json("/last-stack.png")}};
  }
  json disk = {{"root", s.output_root.string()},
               {"reserve_bytes", s.reserve_bytes},
               {"fault", optionalText(st.disk_fault)}};
  if (st.disk) {
    disk["free_bytes"] = st.disk->free_bytes;
    disk["total_bytes"] = st.disk->total_bytes;
    disk["read_only"] = st.disk->read_only;
  } else {
    disk["free_bytes"] = disk["total_bytes"] = disk["read_only"] = nullptr;
  }
  json illuminance = {{"instrument", optionalText(st.illuminance_instrument)},
                      {"fault", optionalText(st.illuminance_fault)},
                      {"failures", st.illuminance_failures},
                      {"last", nullptr}};
  if (st.last_source_illuminance) {
    illuminance["last"] = toJson(*st.last_source_illuminance);
    illuminance["last"]["time"] =
        st.last_illuminance_time ? json(isoSeconds(*st.last_illuminance_time)) : json(nullptr);
  }
  json entries = json::array();
  for (const LogEntry& e : log) {
    json entry = {{"time", isoSeconds(e.time)}, {"level", e.level}, {"text", e.text}};
    if (e.simulated_time) entry["simulated_time"] = isoSeconds(*e.simulated_time);
    entries.push_back(std::move(entry));
  }
  return {
      {"schema", kStatusSchema},
      {"version", kVersion},
      {"time", isoSeconds(s.now)},
      {"simulated_time", s.simulated_time},
      {"state", activity.state},
      {"reason", optionalText(activity.reason)},
      {"status_line", st.status},
      {"schedule", s.schedule},
      {"next",
       {{"time", st.next_capture_time ? json(isoSeconds(*st.next_capture_time)) : json(nullptr)},
        {"alpha_deg", finiteOrNull(st.next_target_deg)}}},
      {"last_stack", last_stack},
      {"last_result", last_result},
      {"today",
       {{"day", s.today},
        {"stacks",
         st.last_day && st.last_day->day == s.today ? json(st.last_day->stacks) : json(0)},
        {"datasheet", "/datasheet.png"}}},
      {"camera",
       {{"uri", s.camera_uri}, {"open", s.camera_open}, {"fault", optionalText(st.camera_fault)}}},
      {"inclinometer",
       {{"uri", optionalText(s.inclinometer_uri)}, {"fault", optionalText(st.inclinometer_fault)}}},
      {"illuminance", illuminance},
      {"clock",
       {{"synchronised", s.clock_synchronised}, {"warning", optionalText(st.clock_warning)}}},
      {"disk", disk},
      {"retention",
       {{"policy", s.retention_policy},
        {"last_action", optionalText(st.retention_last)},
        {"last_action_time",
         st.retention_last_time ? json(isoSeconds(*st.retention_last_time)) : json(nullptr)},
        {"shortfall", optionalText(st.retention_shortfall)},
        {"day_overflows", st.retention_day_overflows},
        {"budget_warning", optionalText(st.retention_budget_warning)},
        {"deleted",
         {{"stacks", st.stacks_deleted},
          {"result_images", st.result_images_pruned},
          {"results", st.results_deleted},
          {"days", st.days_deleted}}}}},
      {"counters",
       {{"stacks_captured", st.stacks_captured},
        {"stacks_written", st.stacks_written},
        {"stacks_processed", st.stacks_processed},
        {"stacks_failed", st.stacks_failed},
        {"captures_skipped", st.captures_skipped},
        {"paused_seconds", st.paused_seconds},
        {"watchdog_pings", st.watchdog_pings},
        {"reloads", st.reloads}}},
      {"log", entries},
  };
}

std::string statusMetrics(const StatusSnapshot& s) {
  const DaemonState& st = s.state;
  std::string out;
  const auto metric = [&out](const char* name, const char* type, const char* help, auto value) {
    out += fmt::format("# HELP {} {}\n# TYPE {} {}\n{} {}\n", name, help, name, type, name, value);
  };
  out += "# HELP glarecam_info glarecamd's version.\n# TYPE glarecam_info gauge\n";
  out += fmt::format("glarecam_info{{version=\"{}\"}} 1\n", kVersion);
  const std::string state = rigActivity(st).state;
  out +=
      "# HELP glarecam_state What the rig does: 1 for its state, 0 for the others.\n"
      "# TYPE glarecam_state gauge\n";
  for (const char* name : kStates)
    out += fmt::format("glarecam_state{{state=\"{}\"}} {}\n", name, state == name ? 1 : 0);
  metric("glarecam_stacks_captured_total", "counter", "Stacks captured since glarecamd started.",
         st.stacks_captured);
  metric("glarecam_stacks_written_total", "counter", "Stacks written to the output tree.",
         st.stacks_written);
  metric("glarecam_stacks_processed_total", "counter", "Stacks processed into a result.",
         st.stacks_processed);
  metric("glarecam_stacks_failed_total", "counter",
         "Stacks whose write, processing or day products failed.", st.stacks_failed);
  metric("glarecam_captures_skipped_total", "counter", "Scheduled stacks not taken.",
         st.captures_skipped);
  metric("glarecam_paused_seconds_total", "counter",
         "Seconds capture was paused (disk, inclinometer).", st.paused_seconds);
  metric("glarecam_watchdog_pings_total", "counter", "WATCHDOG=1 sent to systemd.",
         st.watchdog_pings);
  out +=
      "# HELP glarecam_retention_deleted_total Entries retention deleted, by kind.\n"
      "# TYPE glarecam_retention_deleted_total counter\n";
  out += fmt::format("glarecam_retention_deleted_total{{kind=\"stack\"}} {}\n", st.stacks_deleted);
  out += fmt::format("glarecam_retention_deleted_total{{kind=\"result_images\"}} {}\n",
                     st.result_images_pruned);
  out +=
      fmt::format("glarecam_retention_deleted_total{{kind=\"result\"}} {}\n", st.results_deleted);
  out += fmt::format("glarecam_retention_deleted_total{{kind=\"day\"}} {}\n", st.days_deleted);
  metric("glarecam_camera_open", "gauge", "1 while the camera is open.", s.camera_open ? 1 : 0);
  metric("glarecam_clock_synchronised", "gauge", "1 while the wall clock is synchronised.",
         s.clock_synchronised ? 1 : 0);
  if (st.disk) {
    metric("glarecam_disk_free_bytes", "gauge", "Free space on the output's filesystem.",
           st.disk->free_bytes);
    metric("glarecam_disk_total_bytes", "gauge", "Size of the output's filesystem.",
           st.disk->total_bytes);
  }
  metric("glarecam_disk_reserve_bytes", "gauge", "Free space below which capture pauses.",
         s.reserve_bytes);
  if (st.last_capture_time)
    metric("glarecam_last_capture_timestamp_seconds", "gauge",
           "Unix time of the last stack's bracket.",
           fmt::format("{:.3f}", unixSeconds(*st.last_capture_time)));
  if (!st.illuminance_instrument.empty()) {
    metric("glarecam_source_illuminance_ok", "gauge",
           "1 while the illuminance instrument reads (the stacks are referred).",
           st.illuminance_fault.empty() ? 1 : 0);
    metric("glarecam_source_illuminance_failures_total", "counter",
           "Brackets the illuminance instrument failed (their stacks unreferred).",
           st.illuminance_failures);
  }
  if (st.last_source_illuminance) {
    const SourceIlluminance& source = *st.last_source_illuminance;
    metric("glarecam_source_illuminance_lux", "gauge",
           "Direct normal illuminance of the source during the last bracket it was read (lx).",
           source.illuminance_lx);
    metric("glarecam_source_illuminance_uncertainty_lux", "gauge", "Its standard uncertainty (lx).",
           source.illuminance_u_lx);
    metric("glarecam_source_illuminance_samples", "gauge", "Readings averaged in that bracket.",
           source.samples.value_or(0));
    if (st.last_illuminance_time)
      metric("glarecam_source_illuminance_timestamp_seconds", "gauge",
             "Unix time of that bracket's end.",
             fmt::format("{:.3f}", unixSeconds(*st.last_illuminance_time)));
  }
  if (st.last_result) {
    metric("glarecam_last_lmax_cd_m2", "gauge", "Lmax of the last stack processed (cd/m^2).",
           st.last_result->brief.lmax_cd_m2);
  }
  return out;
}

std::string statusHtml(const StatusSnapshot& s, const std::vector<LogEntry>& log) {
  const DaemonState& st = s.state;
  const RigActivity activity = rigActivity(st);
  const auto e = [](std::string_view text) { return htmlEscape(text); };
  const auto row = [&e](std::string_view name, std::string_view value) {
    return fmt::format("<tr><th>{}</th><td>{}</td></tr>\n", e(name), e(value));
  };
  std::string html =
      fmt::format(R"(<!DOCTYPE html>
<html lang="en">
<head>
<meta charset="utf-8">
<meta http-equiv="refresh" content="{refresh}">
<meta name="viewport" content="width=device-width, initial-scale=1">
<title>glarecam: {state}</title>
<style>
body {{ font-family: sans-serif; margin: 1em; color: #222; background: #fafafa; }}
h1 {{ font-size: 1.3em; margin: 0 0 .3em 0; }}
h2 {{ font-size: 1.05em; margin: 0 0 .4em 0; }}
.state {{ display: inline-block; padding: .15em .6em; border-radius: .3em; color: #fff;
          font-weight: bold; text-transform: uppercase; }}
.capturing {{ background: #2e7d32; }} .paused {{ background: #ef6c00; }}
.fault {{ background: #c62828; }} .starting, .stopping {{ background: #616161; }}
.grid {{ display: flex; flex-wrap: wrap; gap: 1em; }}
section {{ background: #fff; border: 1px solid #ddd; border-radius: .3em; padding: .7em;
           flex: 1 1 22em; }}
table {{ border-collapse: collapse; }}
th {{ text-align: left; padding-right: 1em; font-weight: normal; color: #555;
      vertical-align: top; }}
td {{ vertical-align: top; }}
img {{ max-width: 100%; height: auto; border: 1px solid #ccc; }}
.log td {{ font-family: monospace; font-size: .85em; padding-right: .8em; }}
.warning td, .error td, .critical td {{ color: #c62828; }}
.reason {{ margin: .4em 0; }}
.line {{ color: #555; font-size: .9em; }}
</style>
</head>
<body>
<h1>glarecam rig <span class="state {state}">{state}</span></h1>
)",
                  fmt::arg("refresh", kPageRefreshSeconds), fmt::arg("state", e(activity.state)));
  if (!activity.reason.empty())
    html += fmt::format("<p class=\"reason\">{}</p>\n", e(activity.reason));
  html += fmt::format("<p class=\"line\">{} · {} · glarecam {}</p>\n<div class=\"grid\">\n",
                      e(st.status), e(daemonTime(s, s.now)), e(kVersion));

  html += "<section id=\"last-stack\">\n<h2>Last stack</h2>\n<table>\n";
  if (st.last_stack) {
    html += row("captured", *st.last_stack);
    if (st.last_capture_time) html += row("at", daemonTime(s, *st.last_capture_time));
    html += row("α", st.last_alpha_deg ? fmt::format("{:.2f}°", *st.last_alpha_deg) : "unknown");
  } else {
    html += row("captured", "none yet since glarecamd started");
  }
  if (st.last_result) {
    const ResultBrief& b = st.last_result->brief;
    html += row("processed", st.last_result->stack_id);
    html += row("Lmax", lmaxText(b));
    if (b.limit_cd_m2) html += row("limit", fmt::format("{:.0f} cd/m²", *b.limit_cd_m2));
    html += row("verdict", verdictText(b));
  }
  html += "</table>\n";
  if (st.last_result && st.last_result->images_pruned)
    html += fmt::format("<p class=\"line\">{}</p>\n",
                        e(statusPictureMissing(s, StatusPicture::kLastStack)));
  else if (st.last_result)
    html += fmt::format(
        "<p><a href=\"/last-stack.png?stack={0}\"><img src=\"/last-stack.png?stack={0}\" "
        "alt=\"luminance image of {0} with its glare ellipses (Figure 9)\"></a></p>\n",
        e(st.last_result->stack_id));
  html += "</section>\n";

  html += fmt::format("<section id=\"today\">\n<h2>Today, {}</h2>\n<table>\n", e(s.today));
  html += row("stacks", dayStacksText(s));
  if (!st.day.empty()) html += row("last day rebuilt", st.day);
  html += "</table>\n";
  if (st.last_day && st.last_day->day == s.today && st.last_day->datasheet)
    html += fmt::format(
        "<p><a href=\"/datasheet.png?stacks={0}\"><img src=\"/datasheet.png?stacks={0}\" "
        "alt=\"today's glare data sheet\"></a></p>\n",
        st.last_day->stacks);
  else
    html += "<p>No data sheet yet today (the fits need stacks at four α or more).</p>\n";
  html += "</section>\n";

  html += "<section id=\"rig\">\n<h2>Rig</h2>\n<table>\n";
  html += row("schedule", s.schedule);
  if (st.next_capture_time)
    html += row("next stack",
                daemonTime(s, *st.next_capture_time) +
                    (st.next_target_deg ? fmt::format(" (α {:g}°)", *st.next_target_deg) : ""));
  html += row("camera", s.camera_uri + (s.camera_open ? " (open)" : " (closed)"));
  if (!st.camera_fault.empty()) html += row("camera fault", st.camera_fault);
  html += row("inclinometer", s.inclinometer_uri.empty() ? "none" : s.inclinometer_uri);
  if (!st.inclinometer_fault.empty()) html += row("inclinometer fault", st.inclinometer_fault);
  if (!st.illuminance_instrument.empty()) {
    std::string value = st.illuminance_instrument;
    if (st.last_source_illuminance)
      value +=
          fmt::format(": {} over {} readings{}", describe(*st.last_source_illuminance),
                      st.last_source_illuminance->samples.value_or(0),
                      st.last_illuminance_time ? " at " + daemonTime(s, *st.last_illuminance_time)
                                               : std::string());
    html += row("source illuminance", value);
  }
  if (!st.illuminance_fault.empty())
    html += row("illuminance fault", st.illuminance_fault + " (the stacks are unreferred)");
  html += row("clock", std::string(s.clock_synchronised ? "synchronised" : "not synchronised") +
                           (s.simulated_time ? " (the simulated clock)" : ""));
  if (!st.clock_warning.empty()) html += row("clock warning", st.clock_warning);
  if (!st.gpio_fault.empty()) html += row("GPIO", st.gpio_fault);
  if (!st.worker_fault.empty()) html += row("last failure", st.worker_fault);
  html += row("stacks",
              fmt::format("{} captured, {} written, {} processed, {} failed", st.stacks_captured,
                          st.stacks_written, st.stacks_processed, st.stacks_failed));
  html += "</table>\n</section>\n";

  html += "<section id=\"disk\">\n<h2>Disk</h2>\n<table>\n";
  html += row("output", s.output_root.string());
  if (st.disk) {
    html += row("free", fmt::format("{} of {}{}", formatBytes(st.disk->free_bytes),
                                    formatBytes(st.disk->total_bytes),
                                    st.disk->read_only ? " (read-only)" : ""));
  }
  html += row("reserve", formatBytes(s.reserve_bytes));
  if (!st.disk_fault.empty()) html += row("paused", st.disk_fault);
  html += row("paused in all", fmt::format("{:.0f} s", st.paused_seconds));
  html += row("retention", s.retention_policy);
  html += row("retention's last action",
              st.retention_last.empty()
                  ? std::string("none")
                  : st.retention_last + (st.retention_last_time
                                             ? " at " + daemonTime(s, *st.retention_last_time)
                                             : std::string()));
  if (!st.retention_shortfall.empty()) html += row("retention shortfall", st.retention_shortfall);
  if (!st.retention_budget_warning.empty())
    html += row("retention budget", st.retention_budget_warning);
  html += "</table>\n</section>\n</div>\n";

  html += fmt::format("<section id=\"log\">\n<h2>Log (last {})</h2>\n", kStatusLogEntries);
  if (s.simulated_time)
    html +=
        "<p class=\"line\">Times marked sim are the simulated clock's (glarecamd --simulate); "
        "the others the machine's.</p>\n";
  html += "<table class=\"log\">\n";
  for (auto it = log.rbegin(); it != log.rend(); ++it)
    html += fmt::format("<tr class=\"{}\"><td>{}</td><td>{}</td><td>{}</td></tr>\n", e(it->level),
                        e(logTime(*it)), e(it->level), e(it->text));
  html += "</table>\n</section>\n</body>\n</html>\n";
  return html;
}

}  // namespace glarecam::daemon
