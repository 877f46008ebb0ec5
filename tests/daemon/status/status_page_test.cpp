// The status page's views of a snapshot: the HTML an operator opens (every state, hostile text
// escaped, nothing fetched from elsewhere), /api/status's JSON and /metrics in Prometheus's text
// format, checked line by line against its grammar.
#include "daemon/status/status_page.h"

#include <gtest/gtest.h>

#include <map>
#include <regex>
#include <set>
#include <sstream>

#include "daemon/daemon_test_support.h"

namespace glarecam::daemon {
namespace {

using testing::utc;

StatusSnapshot capturingRig() {
  StatusSnapshot s;
  DaemonState& st = s.state;
  st.ready = true;
  st.status = "ready, at 16 α targets; last 20260621T101503Z-a42.30 (α 42.30°)";
  st.last_stack = "20260621T101503Z-a42.30";
  st.last_alpha_deg = 42.3;
  st.last_capture_time = utc("2026-06-21T10:15:03Z");
  st.next_capture_time = utc("2026-06-21T10:25:03Z");
  st.next_target_deg = 40;
  st.last_result = LastResult{
      .stack_id = "20260621T101503Z-a42.30",
      .directory = "/out/results/20260621T101503Z-a42.30",
      .brief = {.alpha_deg = 42.3, .lmax_cd_m2 = 5.4e5, .limit_cd_m2 = 30000, .glare = true}};
  st.last_day = LastDay{
      .day = "2026-06-21", .directory = "/out/days/2026-06-21", .stacks = 7, .datasheet = true};
  st.disk = DiskState{.free_bytes = 5ull << 30, .total_bytes = 32ull << 30};
  st.stacks_captured = 8;
  st.stacks_written = 8;
  st.stacks_processed = 7;
  st.stacks_failed = 1;
  st.paused_seconds = 12.75;
  st.stacks_deleted = 3;
  st.retention_last = "deleted stack x (12.0 MiB): older than 14 days";
  st.illuminance_instrument = "pyrheliometer modbus:/dev/ttyUSB0@1 (W/m², 93 lm/W)";
  st.last_source_illuminance = SourceIlluminance{.illuminance_lx = 92500,
                                                 .illuminance_u_lx = 8200,
                                                 .origin = IlluminanceOrigin::kSensor,
                                                 .instrument = st.illuminance_instrument,
                                                 .samples = 6,
                                                 .spread_lx = 310};
  st.last_illuminance_time = utc("2026-06-21T10:15:04Z");
  st.illuminance_failures = 2;
  s.schedule = "at 16 α targets";
  s.camera_uri = "aravis:192.168.10.20";
  s.camera_open = true;
  s.inclinometer_uri = "adxl355:/dev/i2c-1@0x1d";
  s.clock_synchronised = true;
  s.output_root = "/out";
  s.reserve_bytes = 1ull << 30;
  s.retention_policy = "stacks 14 days";
  s.now = utc("2026-06-21T10:16:00Z");
  s.today = "2026-06-21";
  return s;
}

std::vector<LogEntry> someLog() {
  return {{.time = std::chrono::system_clock::time_point{}, .level = "info", .text = "first"},
          {.time = std::chrono::system_clock::time_point{}, .level = "error", .text = "last"}};
}

TEST(StatusPage, ShowsTheStateTheLastStackTodayTheRigTheDiskAndTheLog) {
  const std::string html = statusHtml(capturingRig(), someLog());
  for (const char* expected :
       {"<span class=\"state capturing\">capturing</span>",
        "<meta http-equiv=\"refresh\" content=\"10\">", "20260621T101503Z-a42.30", "42.30°",
        "5.4e+05 cd/m²", "glare: Lmax above the limit",
        "<img src=\"/last-stack.png?stack=20260621T101503Z-a42.30\"",
        "<img src=\"/datasheet.png?stacks=7\"", "Today, 2026-06-21", "aravis:192.168.10.20 (open)",
        "adxl355:/dev/i2c-1@0x1d", "synchronised", "5.0 GiB of 32.0 GiB", "1.0 GiB",
        "deleted stack x (12.0 MiB): older than 14 days", "13 s",
        "8 captured, 8 written, "
        "7 processed, 1 failed"})
    EXPECT_NE(html.find(expected), std::string::npos) << expected;
  // Newest log entry first.
  EXPECT_LT(html.find(">last<"), html.find(">first<"));
  // Nothing from elsewhere: no scripts, no external styles, fonts or pictures.
  EXPECT_EQ(html.find("<script"), std::string::npos);
  EXPECT_EQ(html.find("http://"), std::string::npos);
  EXPECT_EQ(html.find("https://"), std::string::npos);
  EXPECT_EQ(html.find("<link"), std::string::npos);
}

// glarecamd --simulate: the page's own times are the simulated clock's, marked sim; the log's are
// the machine's, each with the simulated time beside it.
TEST(StatusPage, SimulatedTimesAreMarkedApartFromTheMachines) {
  StatusSnapshot s = capturingRig();
  s.simulated_time = true;
  const std::vector<LogEntry> log{
      {.time = std::chrono::sys_days(std::chrono::year(2026) / std::chrono::December / 6),
       .simulated_time = utc("2026-06-21T10:15:03Z"),
       .level = "info",
       .text = "captured"}};
  const std::string html = statusHtml(s, log);
  EXPECT_NE(html.find("2026-06-21T10:16:00Z sim"), std::string::npos);          // now
  EXPECT_NE(html.find("2026-06-21T10:25:03Z sim (α 40°)"), std::string::npos);  // next stack
  EXPECT_NE(html.find("2026-12-06T00:00:00Z (sim 2026-06-21T10:15:03Z)"), std::string::npos);
  const nlohmann::json json = statusJson(s, log);
  EXPECT_EQ(json["simulated_time"], true);
  EXPECT_EQ(json["log"][0]["time"], "2026-12-06T00:00:00Z");
  EXPECT_EQ(json["log"][0]["simulated_time"], "2026-06-21T10:15:03Z");
  // The machine's clock: nothing marked.
  EXPECT_EQ(statusHtml(capturingRig(), someLog()).find(" sim"), std::string::npos);
}

TEST(StatusPage, APausedDiskAndALostCameraAreShownWithTheirReasons) {
  StatusSnapshot paused = capturingRig();
  paused.state.disk_fault = "12.0 MiB free on /out, below the 1.0 GiB reserve";
  std::string html = statusHtml(paused, {});
  EXPECT_NE(html.find("<span class=\"state paused\">paused</span>"), std::string::npos);
  EXPECT_NE(html.find("disk: 12.0 MiB free on /out, below the 1.0 GiB reserve"), std::string::npos);
  EXPECT_EQ(statusJson(paused, {})["state"], "paused");

  StatusSnapshot lost = capturingRig();
  lost.camera_open = false;
  lost.state.camera_fault = "lost: no frame within 5 s; reopening in 8 s (failure 2 of 8)";
  html = statusHtml(lost, {});
  EXPECT_NE(html.find("<span class=\"state fault\">fault</span>"), std::string::npos);
  EXPECT_NE(html.find("camera: lost: no frame within 5 s"), std::string::npos);
  EXPECT_NE(html.find("(closed)"), std::string::npos);
  const auto json = statusJson(lost, {});
  EXPECT_EQ(json["state"], "fault");
  EXPECT_EQ(json["camera"]["open"], false);
  EXPECT_EQ(json["reason"], "camera: lost: no frame within 5 s; reopening in 8 s (failure 2 of 8)");
}

TEST(StatusPage, TextFromTheRigIsEscaped) {
  StatusSnapshot s = capturingRig();
  s.state.worker_fault = "<script>alert('x')</script> & \"more\"";
  s.camera_uri = "sim:<b>";
  const std::string html =
      statusHtml(s, {{.time = {}, .level = "error", .text = "<img src=x onerror=y>"}});
  EXPECT_EQ(html.find("<script>"), std::string::npos);
  EXPECT_EQ(html.find("<img src=x"), std::string::npos);
  EXPECT_EQ(html.find("sim:<b>"), std::string::npos);
  EXPECT_NE(html.find("&lt;script&gt;alert(&#39;x&#39;)&lt;/script&gt; &amp; &quot;more&quot;"),
            std::string::npos);
  EXPECT_EQ(htmlEscape("a<b>&\"'"), "a&lt;b&gt;&amp;&quot;&#39;");
}

TEST(StatusPage, BeforeAnyStackThePageSaysSo) {
  StatusSnapshot s;
  s.today = "2026-06-21";
  s.output_root = "/out";
  const std::string html = statusHtml(s, {});
  EXPECT_NE(html.find("<span class=\"state starting\">starting</span>"), std::string::npos);
  EXPECT_NE(html.find("none yet"), std::string::npos);
  EXPECT_NE(html.find("No data sheet yet today"), std::string::npos);
  EXPECT_EQ(html.find("<img"), std::string::npos);
  EXPECT_FALSE(statusPicture(s, StatusPicture::kLastStack));
  const auto json = statusJson(s, {});
  EXPECT_TRUE(json["last_stack"].is_null());
  EXPECT_TRUE(json["last_result"].is_null());
  EXPECT_TRUE(json["disk"]["free_bytes"].is_null());
}

TEST(StatusPage, ThePicturesAreTheFilesTheSnapshotNames) {
  const StatusSnapshot s = capturingRig();
  EXPECT_EQ(statusPicture(s, StatusPicture::kLastStack),
            std::filesystem::path("/out/results/20260621T101503Z-a42.30/luminance.png"));
  EXPECT_EQ(statusPicture(s, StatusPicture::kDatasheet),
            std::filesystem::path("/out/days/2026-06-21/datasheet.png"));
}

// Retention pruned the last result's images (a past day's, on a rig that ran through midnight):
// the page keeps its numbers and says why there is no picture; the JSON and /metrics count it.
TEST(StatusPage, APrunedLastResultKeepsItsNumbersAndSaysWhyThereIsNoPicture) {
  StatusSnapshot s = capturingRig();
  s.state.last_result->images_pruned = true;
  s.state.result_images_pruned = 40;
  EXPECT_FALSE(statusPicture(s, StatusPicture::kLastStack));
  EXPECT_EQ(statusPictureMissing(s, StatusPicture::kLastStack),
            "the images of 20260621T101503Z-a42.30 were pruned by retention (its numbers stay)");
  const std::string html = statusHtml(s, {});
  EXPECT_NE(html.find("were pruned by retention"), std::string::npos);
  EXPECT_EQ(html.find("/last-stack.png"), std::string::npos);
  EXPECT_NE(html.find("5.4e+05 cd/m²"), std::string::npos) << html;
  const auto j = statusJson(s, {});
  EXPECT_EQ(j["last_result"]["images_pruned"], true);
  EXPECT_TRUE(j["last_result"]["picture"].is_null());
  EXPECT_EQ(j["last_result"]["lmax_cd_m2"], 5.4e5);
  EXPECT_EQ(j["retention"]["deleted"]["result_images"], 40);
  EXPECT_EQ(j["retention"]["day_overflows"], false);
  EXPECT_NE(statusMetrics(s).find("glarecam_retention_deleted_total{kind=\"result_images\"} 40\n"),
            std::string::npos);
  EXPECT_EQ(statusPictureMissing(StatusSnapshot{}, StatusPicture::kLastStack),
            "no stack processed yet");
}

TEST(StatusPage, JsonCarriesThePagesContent) {
  const auto j = statusJson(capturingRig(), someLog());
  EXPECT_EQ(j["schema"], kStatusSchema);
  EXPECT_EQ(j["state"], "capturing");
  EXPECT_TRUE(j["reason"].is_null());
  EXPECT_EQ(j["time"], "2026-06-21T10:16:00Z");
  EXPECT_EQ(j["last_stack"]["id"], "20260621T101503Z-a42.30");
  EXPECT_EQ(j["last_stack"]["captured_at"], "2026-06-21T10:15:03Z");
  EXPECT_EQ(j["last_result"]["lmax_cd_m2"], 5.4e5);
  EXPECT_EQ(j["last_result"]["glare"], true);
  EXPECT_EQ(j["last_result"]["limit_cd_m2"], 30000);
  EXPECT_EQ(j["last_result"]["images_pruned"], false);
  EXPECT_EQ(j["last_result"]["picture"], "/last-stack.png");
  EXPECT_EQ(j["today"]["stacks"], 7);
  EXPECT_EQ(j["next"]["alpha_deg"], 40);
  EXPECT_EQ(j["disk"]["free_bytes"], 5ull << 30);
  EXPECT_EQ(j["disk"]["reserve_bytes"], 1ull << 30);
  EXPECT_EQ(j["retention"]["deleted"]["stacks"], 3);
  EXPECT_EQ(j["retention"]["last_action"], "deleted stack x (12.0 MiB): older than 14 days");
  EXPECT_EQ(j["counters"]["stacks_processed"], 7);
  EXPECT_EQ(j["counters"]["paused_seconds"], 12.75);
  ASSERT_EQ(j["log"].size(), 2u);
  EXPECT_EQ(j["log"][1]["level"], "error");
}

// Prometheus's text exposition format 0.0.4: every sample line "name{labels} value", each metric
// family announced by HELP and TYPE before its samples, counters named *_total.
TEST(StatusPage, MetricsFollowThePrometheusTextFormat) {
  const std::string text = statusMetrics(capturingRig());
  const std::regex sample(R"(^([a-zA-Z_:][a-zA-Z0-9_:]*)(\{[a-z_]+="[^"]*"\})? (-?[0-9.e+]+)$)");
  const std::regex help(R"(^# HELP ([a-zA-Z_:][a-zA-Z0-9_:]*) .+$)");
  const std::regex type(R"(^# TYPE ([a-zA-Z_:][a-zA-Z0-9_:]*) (counter|gauge)$)");
  std::map<std::string, std::string> types;
  std::set<std::string> helped;
  std::map<std::string, double> values;
  std::istringstream lines(text);
  std::string line;
  std::smatch m;
  while (std::getline(lines, line)) {
    if (std::regex_match(line, m, help)) {
      helped.insert(m[1]);
    } else if (std::regex_match(line, m, type)) {
      EXPECT_TRUE(helped.count(m[1])) << "TYPE before HELP: " << line;
      types[m[1]] = m[2];
    } else {
      ASSERT_TRUE(std::regex_match(line, m, sample)) << "not a sample: " << line;
      ASSERT_TRUE(types.count(m[1])) << "a sample before its TYPE: " << line;
      values[std::string(m[1]) + std::string(m[2])] = std::stod(m[3]);
    }
  }
  for (const auto& [name, kind] : types)
    EXPECT_EQ(kind == "counter", name.ends_with("_total")) << name;
  EXPECT_EQ(values["glarecam_stacks_written_total"], 8);
  EXPECT_EQ(values["glarecam_stacks_processed_total"], 7);
  EXPECT_EQ(values["glarecam_stacks_failed_total"], 1);
  EXPECT_EQ(values["glarecam_paused_seconds_total"], 12.75);
  EXPECT_EQ(values["glarecam_disk_free_bytes"], double(5ull << 30));
  EXPECT_EQ(values["glarecam_last_capture_timestamp_seconds"], 1782036903.0);
  EXPECT_EQ(values["glarecam_state{state=\"capturing\"}"], 1);
  EXPECT_EQ(values["glarecam_state{state=\"paused\"}"], 0);
  EXPECT_EQ(values["glarecam_retention_deleted_total{kind=\"stack\"}"], 3);
  EXPECT_EQ(values["glarecam_source_illuminance_lux"], 92500);
  EXPECT_EQ(values["glarecam_source_illuminance_uncertainty_lux"], 8200);
  EXPECT_EQ(values["glarecam_source_illuminance_samples"], 6);
  EXPECT_EQ(values["glarecam_source_illuminance_ok"], 1);
  EXPECT_EQ(values["glarecam_source_illuminance_failures_total"], 2);
}

TEST(StatusPage, ShowsTheSourceIlluminanceAndWhyTheStacksAreUnreferred) {
  StatusSnapshot s = capturingRig();
  const std::string page = statusHtml(s, someLog());
  EXPECT_NE(page.find("92.5 ± 8.2 klx (sensor) over 6 readings"), std::string::npos);
  const nlohmann::json json = statusJson(s, someLog());
  EXPECT_EQ(json["illuminance"]["last"]["illuminance_lx"], 92500);
  EXPECT_EQ(json["illuminance"]["last"]["origin"], "sensor");
  EXPECT_TRUE(json["illuminance"]["fault"].is_null());
  s.state.illuminance_fault = "modbus:/dev/ttyUSB0@1: no reply within 500 ms";
  EXPECT_NE(statusHtml(s, someLog()).find("no reply within 500 ms (the stacks are unreferred)"),
            std::string::npos);
  EXPECT_EQ(statusJson(s, someLog())["illuminance"]["fault"], s.state.illuminance_fault);
  const std::string metrics = statusMetrics(s);
  EXPECT_NE(metrics.find("\nglarecam_source_illuminance_ok 0\n"), std::string::npos);
}

}  // namespace
}  // namespace glarecam::daemon
