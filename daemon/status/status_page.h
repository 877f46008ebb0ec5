// The status page's views of a snapshot (status_board.h), as pure functions of it, so that every
// state renders in a test without a server:
//
//   /             the page an operator opens: the state and why, the last stack and its Figure-9
//                 picture, today's data sheet, camera, inclinometer, clock, disk and retention,
//                 the last log entries; it reloads itself every kPageRefreshSeconds (a meta
//                 refresh: no JavaScript, no external fonts or styles: a field has no network)
//   /api/status   the same content as JSON (schema glarecam.status/1, docs/operator.md)
//   /metrics      Prometheus's text exposition format 0.0.4: counters and gauges named
//                 glarecam_*, for operators who watch several rigs with the tools they run
//
// The pictures are files the daemon names (statusPicture()), never a path from a request.
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "daemon/status/log_ring.h"
#include "daemon/status/status_board.h"

namespace glarecam::daemon {

inline constexpr int kPageRefreshSeconds = 10;
inline constexpr const char* kStatusSchema = "glarecam.status/1";

// The two pictures the page shows, by their fixed names on the page.
enum class StatusPicture {
  kLastStack,  // /last-stack.png: the last processed stack's luminance.png (Figure 9)
  kDatasheet,  // /datasheet.png: today's data sheet, datasheet.png of days/<today>/
};
// The file behind a picture now, or nullopt when there is none (nothing processed yet, no sheet
// today): the server answers 404 then.
std::optional<std::filesystem::path> statusPicture(const StatusSnapshot& snapshot,
                                                   StatusPicture picture);
// Why there is no picture, for the 404: "no stack processed yet", "the images of … were pruned by
// retention (its numbers stay)", "no data sheet today yet".
std::string statusPictureMissing(const StatusSnapshot& snapshot, StatusPicture picture);

nlohmann::json statusJson(const StatusSnapshot& snapshot, const std::vector<LogEntry>& log);
std::string statusHtml(const StatusSnapshot& snapshot, const std::vector<LogEntry>& log);
std::string statusMetrics(const StatusSnapshot& snapshot);

// `text` with & < > " ' as HTML character references.
std::string htmlEscape(std::string_view text);

}  // namespace glarecam::daemon
