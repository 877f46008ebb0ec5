// glarecamd's status page against the daemon as a process, through a real HTTP client: the
// simulated rig's page, API, metrics and pictures while it captures; a paused disk and a fault as
// the page shows them (each from a config's [status] listen); clients that connect and never send
// or never read, while capture and the watchdog go on; and headless Chromium rendering the page
// (skipped, saying why, where Chromium cannot start). Timing only bounds waits.
#include <gtest/gtest.h>
#include <httplib.h>
#include <netinet/in.h>
#include <png.h>

#include <nlohmann/json.hpp>
#include <optional>
#include <regex>
#include <string>
#include <vector>

#include "apps/glarecamd_harness.h"
#include "core/build_config.h"
#include "core/unique_fd.h"
#include "support/test_support.h"

namespace glarecam {
namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;
using Clock = std::chrono::steady_clock;
// The harness (apps/glarecamd_harness.h): NotifySocket, Process, eventually, entries, labRig.
using namespace testing;

constexpr const char* kChromium = "/usr/bin/chromium";

class GlarecamdStatusPage : public ::testing::Test {
 protected:
  std::string log() const { return testing::readText(dir_ / "glarecamd.log"); }
  // The port glarecamd logged ("status page at http://127.0.0.1:PORT/"), once it has.
  int port() {
    int found = 0;
    eventually(
        [&] {
          std::smatch m;
          const std::string text = log();
          if (std::regex_search(text, m,
                                std::regex(R"(status page at http://127\.0\.0\.1:(\d+)/)")))
            found = std::stoi(m[1]);
          return found > 0;
        },
        kStartTimeout);
    return found;
  }
  nlohmann::json api(int port) {
    httplib::Client client("127.0.0.1", port);
    client.set_read_timeout(10, 0);
    const auto response = client.Get("/api/status");
    if (!response || response->status != 200) return nullptr;
    return nlohmann::json::parse(response->body, nullptr, false);
  }
  // Polls /api/status until `condition` holds of it, reading `notify` meanwhile (as systemd
  // does: a notify socket nobody reads fills, and sd_notify() then blocks the daemon).
  template <typename Condition>
  nlohmann::json apiUntil(int port, Condition condition, std::chrono::seconds timeout,
                          NotifySocket* notify = nullptr) {
    nlohmann::json last;
    eventually(
        [&] {
          if (notify)
            while (notify->receive(0ms)) {
            }
          last = api(port);
          return !last.is_null() && !last.is_discarded() && condition(last);
        },
        timeout);
    return last;
  }
  // glarecamd on the lab rig with the simulated camera, `sections` and the page on a free port;
  // the port it took.
  int startLabRig(std::optional<Process>& process, const std::string& sections) {
    testing::writeText(dir_ / "rig.toml", labRig("sim:size=320x256") + sections +
                                              "[status]\nlisten = \"127.0.0.1:0\"\n");
    process.emplace(
        std::vector<std::string>{GLARECAMD_PATH, "--config", (dir_ / "rig.toml").string()},
        std::vector<std::string>{}, dir_ / "glarecamd.log");
    return port();
  }
  testing::TempDir dir_;
};

bool isPng(const std::string& bytes) { return bytes.starts_with("\x89PNG\r\n\x1a\n"); }

// The simulated rig with --status: the page while it captures, its pictures, and clients that
// never send or never read, while stacks land and the watchdog is fed every second
// (WATCHDOG_USEC 2 s).
TEST_F(GlarecamdStatusPage, TheSimulatedRigsPageWhileItCaptures) {
  NotifySocket notify(dir_ / "notify.sock");
  const fs::path out = dir_ / "out";
  Process process({GLARECAMD_PATH, "--simulate", "--output", out.string(), "--camera",
                   "sim:size=320x256", "--time-lapse", "300", "--status", "127.0.0.1:0"},
                  {"NOTIFY_SOCKET=" + notify.path().string(), "WATCHDOG_USEC=2000000"},
                  dir_ / "glarecamd.log");
  const int port = this->port();
  ASSERT_GT(port, 0) << log();
  // Four stacks of a morning: a data sheet.
  const auto status = apiUntil(
      port, [](const nlohmann::json& j) { return j["today"]["stacks"].get<int>() >= 4; }, 180s,
      &notify);
  ASSERT_GE(status["today"]["stacks"].get<int>(), 4) << log();
  EXPECT_EQ(status["schema"], "glarecam.status/1");
  EXPECT_EQ(status["state"], "capturing") << status.dump(2);
  EXPECT_EQ(status["camera"]["uri"], "sim:size=320x256");
  EXPECT_EQ(status["camera"]["open"], true);
  EXPECT_GT(status["last_result"]["lmax_cd_m2"].get<double>(), 0);
  EXPECT_TRUE(status["last_result"]["glare"].is_boolean());
  EXPECT_GT(status["disk"]["free_bytes"].get<double>(), 0);
  EXPECT_FALSE(status["log"].empty());
  // Its simulated pyrheliometer, read over Modbus TCP on loopback during each bracket.
  EXPECT_TRUE(status["illuminance"]["fault"].is_null()) << status["illuminance"].dump();
#if GLARECAM_WITH_MODBUS
  EXPECT_EQ(status["illuminance"]["last"]["origin"], "sensor") << status["illuminance"].dump();
  EXPECT_GT(status["illuminance"]["last"]["illuminance_lx"].get<double>(), 0);
#endif
  httplib::Client client("127.0.0.1", port);
  client.set_read_timeout(10, 0);
  auto page = client.Get("/");
  ASSERT_TRUE(page);
  EXPECT_EQ(page->status, 200);
  EXPECT_NE(page->body.find("<span class=\"state capturing\">capturing</span>"), std::string::npos);
  auto figure = client.Get("/last-stack.png");
  ASSERT_TRUE(figure);
  EXPECT_EQ(figure->status, 200);
  EXPECT_TRUE(isPng(figure->body));
  auto sheet = client.Get("/datasheet.png");
  ASSERT_TRUE(sheet);
  EXPECT_EQ(sheet->status, 200) << sheet->body;
  EXPECT_TRUE(isPng(sheet->body));
  auto metrics = client.Get("/metrics");
  ASSERT_TRUE(metrics);
  EXPECT_NE(metrics->body.find("glarecam_stacks_processed_total "), std::string::npos);
#if GLARECAM_WITH_MODBUS
  EXPECT_NE(metrics->body.find("\nglarecam_source_illuminance_lux "), std::string::npos);
  EXPECT_NE(metrics->body.find("\nglarecam_source_illuminance_ok 1\n"), std::string::npos);
#endif
  for (const char* path :
       {"/../glarecamd-simulated.toml", "/%2e%2e/glarecamd-simulated.toml", "/stacks/", "/days/"}) {
    auto bad = client.Get(path);
    ASSERT_TRUE(bad) << path;
    EXPECT_EQ(bad->status, 404) << path;
  }

  // Clients that connect and never send, and clients that ask for the picture and never read:
  // the daemon's loop neither knows nor waits.
  std::vector<UniqueFd> silent, unread;
  for (int i = 0; i < 6; ++i) silent.push_back(testing::connectLoopback(port));
  for (int i = 0; i < 3; ++i) {
    unread.push_back(testing::connectLoopback(port));
    const std::string request = "GET /datasheet.png HTTP/1.1\r\nHost: rig\r\n\r\n";
    send(unread.back().get(), request.data(), request.size(), MSG_NOSIGNAL);
  }
  const auto watch_start = Clock::now();
  const std::size_t before = entries(out / "stacks", false).size();
  while (Clock::now() - watch_start < 8s) notify.receive(100ms);
  std::vector<Clock::time_point> pings;
  for (const auto& m : notify.received())
    if (m.message == "WATCHDOG=1" && m.at >= watch_start) pings.push_back(m.at);
  ASSERT_GE(pings.size(), 4u) << log();
  for (std::size_t i = 1; i < pings.size(); ++i)
    EXPECT_LT(pings[i] - pings[i - 1], 2s) << "a ping missed while clients stalled the page";
  // A stack lands while they stall it (the time lapse's α crossings come 4–9 s apart: around
  // noon the 8 s above can fall between two).
  EXPECT_TRUE(eventually([&] { return entries(out / "stacks", false).size() > before; }, 60s))
      << "no stack while clients stalled";
  // And the page answers again once they are dropped (kStatusTimeout, 5 s).
  EXPECT_FALSE(apiUntil(
                   port, [](const nlohmann::json&) { return true; }, 30s, &notify)
                   .is_null());
  process.signal(SIGTERM);
  EXPECT_EQ(process.wait(60s), 0) << log();
}

// A disk below its reserve: the page says paused, and why, in the status line's words.
TEST_F(GlarecamdStatusPage, APausedDiskIsShown) {
  std::optional<Process> process;
  const int port = startLabRig(
      process, "[schedule]\ninterval_s = 5\n[output]\nroot = \"out\"\nreserve_mb = 1073741824\n");
  ASSERT_GT(port, 0) << log();
  const auto status = apiUntil(
      port, [](const nlohmann::json& j) { return j["state"] == "paused"; }, 60s);
  ASSERT_EQ(status["state"], "paused") << status.dump(2) << log();
  EXPECT_TRUE(status["reason"].get<std::string>().starts_with("disk: ")) << status["reason"];
  EXPECT_NE(status["reason"].get<std::string>().find("below the 1.0 PiB reserve"),
            std::string::npos)
      << status["reason"];
  EXPECT_NE(status["status_line"].get<std::string>().find(status["reason"].get<std::string>()),
            std::string::npos);
  EXPECT_EQ(status["counters"]["stacks_captured"], 0);
  httplib::Client client("127.0.0.1", port);
  auto page = client.Get("/");
  ASSERT_TRUE(page);
  EXPECT_NE(page->body.find("<span class=\"state paused\">paused</span>"), std::string::npos);
  EXPECT_NE(page->body.find("below the 1.0 PiB reserve"), std::string::npos);
  auto metrics = client.Get("/metrics");
  ASSERT_TRUE(metrics);
  EXPECT_NE(metrics->body.find("glarecam_state{state=\"paused\"} 1"), std::string::npos);
  process->signal(SIGTERM);
  EXPECT_EQ(process->wait(60s), 0) << log();
}

// An implausible tilt (the lab rig's module stands at 50°, beyond max_tilt_deg 10): a fault, and
// stacks go on with α unknown, as [faults] inclinometer = "continue" says.
TEST_F(GlarecamdStatusPage, AFaultIsShown) {
  std::optional<Process> process;
  const int port = startLabRig(process,
                               "[schedule]\ninterval_s = 2\n[output]\nroot = \"out\"\nreserve_mb = "
                               "1\n[faults]\nmax_tilt_deg = 10\n");
  ASSERT_GT(port, 0) << log();
  const auto status = apiUntil(
      port,
      [](const nlohmann::json& j) {
        return j["state"] == "fault" && j["counters"]["stacks_captured"].get<int>() >= 1;
      },
      90s);
  ASSERT_EQ(status["state"], "fault") << status.dump(2) << log();
  EXPECT_TRUE(status["reason"].get<std::string>().starts_with("inclinometer: "))
      << status["reason"];
  EXPECT_FALSE(status["inclinometer"]["fault"].is_null());
  httplib::Client client("127.0.0.1", port);
  auto page = client.Get("/");
  ASSERT_TRUE(page);
  EXPECT_NE(page->body.find("<span class=\"state fault\">fault</span>"), std::string::npos);
  EXPECT_NE(page->body.find("inclinometer fault"), std::string::npos);
  process->signal(SIGTERM);
  EXPECT_EQ(process->wait(60s), 0) << log();
}

// The fraction of a screenshot's pixels that differ from its most common colour.
double nonBackgroundFraction(const fs::path& png) {
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_file(&image, png.c_str())) return 0;
  image.format = PNG_FORMAT_RGB;
  std::vector<unsigned char> pixels(PNG_IMAGE_SIZE(image));
  if (!png_image_finish_read(&image, nullptr, pixels.data(), 0, nullptr)) return 0;
  std::map<std::uint32_t, std::size_t> counts;
  for (std::size_t i = 0; i + 2 < pixels.size(); i += 3)
    ++counts[(std::uint32_t(pixels[i]) << 16) | (pixels[i + 1] << 8) | pixels[i + 2]];
  std::size_t background = 0;
  for (const auto& [colour, count] : counts) background = std::max(background, count);
  const std::size_t total = pixels.size() / 3;
  return total ? 1.0 - double(background) / double(total) : 0;
}

// Headless Chromium (Debian's) loads the page, its pictures and styles, and its screenshot is
// not blank: more than 5 % of the pixels differ from the background (the page's text, the
// state's badge, the Figure-9 picture and the data sheet cover far more).
TEST_F(GlarecamdStatusPage, HeadlessChromiumRendersThePage) {
  if (!fs::exists(kChromium)) GTEST_SKIP() << kChromium << " is not installed (Debian: chromium)";
  const fs::path out = dir_ / "out";
  Process process({GLARECAMD_PATH, "--simulate", "--output", out.string(), "--camera",
                   "sim:size=320x256", "--time-lapse", "300", "--status", "127.0.0.1:0"},
                  {}, dir_ / "glarecamd.log");
  const int port = this->port();
  ASSERT_GT(port, 0) << log();
  ASSERT_FALSE(
      apiUntil(
          port, [](const nlohmann::json& j) { return j["today"]["stacks"].get<int>() >= 4; }, 180s)
          .is_null())
      << log();
  const fs::path shot = dir_ / "page.png";
  // The flags of a closed network: without the background-networking ones Chromium tries to
  // reach Google's hosts at every start.
  const std::string command = std::string("timeout 120 ") + kChromium +
                              " --headless --no-sandbox --disable-gpu --disable-quic "
                              "--no-first-run --disable-background-networking "
                              "--disable-component-update --disable-sync --user-data-dir=" +
                              (dir_ / "chromium").string() + " --window-size=1280,1600 " +
                              "--screenshot=" + shot.string() +
                              " http://127.0.0.1:" + std::to_string(port) + "/ >" +
                              (dir_ / "chromium.log").string() + " 2>&1";
  const int ran = std::system(command.c_str());
  if (ran != 0 || !fs::exists(shot))
    GTEST_SKIP() << "Chromium could not start here (exit " << ran
                 << "): " << testing::readText(dir_ / "chromium.log").substr(0, 2000);
  EXPECT_GT(nonBackgroundFraction(shot), 0.05) << shot;
  process.signal(SIGTERM);
  EXPECT_EQ(process.wait(60s), 0) << log();
}

}  // namespace
}  // namespace glarecam
