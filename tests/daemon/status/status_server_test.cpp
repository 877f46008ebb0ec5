// The status page's server on a real socket: its five paths, nothing else (traversal in every
// spelling is 404, other methods 405, a body too large 413), and clients that connect and never
// send, or send and never read, neither stall the server for others beyond its timeout nor grow
// it beyond its bound (503 then).
#include "daemon/status/status_server.h"

#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <httplib.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <chrono>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/unique_fd.h"
#include "support/test_support.h"

namespace glarecam::daemon {
namespace {

using namespace std::chrono_literals;
namespace fs = std::filesystem;

// Sends `request` as it is and returns the whole response (until the server closes, or 10 s).
std::string rawRequest(int port, const std::string& request, int timeout_ms = 10000) {
  const UniqueFd fd = testing::connectLoopback(port);
  EXPECT_EQ(send(fd.get(), request.data(), request.size(), MSG_NOSIGNAL),
            static_cast<ssize_t>(request.size()));
  std::string response;
  char buffer[4096];
  for (;;) {
    pollfd p{fd.get(), POLLIN, 0};
    if (poll(&p, 1, timeout_ms) != 1) break;
    const ssize_t n = recv(fd.get(), buffer, sizeof buffer, 0);
    if (n <= 0) break;
    response.append(buffer, static_cast<std::size_t>(n));
  }
  return response;
}

int statusOf(const std::string& response) {
  return response.size() > 12 ? std::stoi(response.substr(9, 3)) : 0;
}

class StatusServerTest : public ::testing::Test {
 protected:
  void SetUp() override {
    fs::create_directories(dir_ / "results" / "s1");
    fs::create_directories(dir_ / "days" / "2026-06-21");
    testing::writeText(dir_ / "results" / "s1" / "luminance.png", "\x89PNG figure 9");
    testing::writeText(dir_ / "days" / "2026-06-21" / "datasheet.png", "\x89PNG sheet");
    testing::writeText(dir_ / "secret.txt", "not for the page");
    StatusSnapshot s;
    s.state.ready = true;
    s.state.status = "ready, every 600 s";
    s.state.stacks_written = 4;
    s.state.last_result =
        LastResult{.stack_id = "s1", .directory = dir_ / "results" / "s1", .brief = {}};
    s.output_root = dir_.path();
    s.today = "2026-06-21";
    board_.publish(s);
    auto server = StatusServer::start({.host = "127.0.0.1", .port = 0}, board_, log_);
    ASSERT_TRUE(server) << server.error().message;
    server_ = std::move(*server);
    port_ = server_->address().port;
    ASSERT_GT(port_, 0);
  }
  httplib::Client client() {
    httplib::Client c("127.0.0.1", port_);
    c.set_read_timeout(10, 0);
    return c;
  }

  testing::TempDir dir_;
  StatusBoard board_;
  std::shared_ptr<LogRing> log_ = std::make_shared<LogRing>();
  std::unique_ptr<StatusServer> server_;
  int port_ = 0;
};

TEST_F(StatusServerTest, ServesThePageTheApiTheMetricsAndThePictures) {
  auto c = client();
  auto page = c.Get("/");
  ASSERT_TRUE(page);
  EXPECT_EQ(page->status, 200);
  EXPECT_EQ(page->get_header_value("Content-Type"), "text/html; charset=utf-8");
  EXPECT_EQ(page->get_header_value("Cache-Control"), "no-store");
  EXPECT_NE(page->get_header_value("Content-Security-Policy").find("default-src 'none'"),
            std::string::npos);
  EXPECT_NE(page->body.find("capturing"), std::string::npos);
  auto api = c.Get("/api/status");
  ASSERT_TRUE(api);
  EXPECT_EQ(api->status, 200);
  EXPECT_EQ(nlohmann::json::parse(api->body)["counters"]["stacks_written"], 4);
  auto metrics = c.Get("/metrics");
  ASSERT_TRUE(metrics);
  EXPECT_EQ(metrics->get_header_value("Content-Type"), "text/plain; version=0.0.4; charset=utf-8");
  EXPECT_NE(metrics->body.find("glarecam_stacks_written_total 4"), std::string::npos);
  auto figure = c.Get("/last-stack.png?stack=s1");
  ASSERT_TRUE(figure);
  EXPECT_EQ(figure->status, 200);
  EXPECT_EQ(figure->get_header_value("Content-Type"), "image/png");
  EXPECT_EQ(figure->body, "\x89PNG figure 9");
  auto sheet = c.Get("/datasheet.png");
  ASSERT_TRUE(sheet);
  EXPECT_EQ(sheet->body, "\x89PNG sheet");
  auto head = c.Head("/");
  ASSERT_TRUE(head);
  EXPECT_EQ(head->status, 200);
  EXPECT_TRUE(head->body.empty());
}

TEST_F(StatusServerTest, APictureNotThereIs404) {
  fs::remove(dir_ / "days" / "2026-06-21" / "datasheet.png");
  auto c = client();
  auto sheet = c.Get("/datasheet.png");
  ASSERT_TRUE(sheet);
  EXPECT_EQ(sheet->status, 404);
  EXPECT_NE(sheet->body.find("no data sheet today yet"), std::string::npos);
}

// No path of a request reaches the filesystem, however it is spelled.
TEST_F(StatusServerTest, TraversalInEverySpellingIs404AndListsNothing) {
  for (const char* path :
       {"/../secret.txt", "/%2e%2e/secret.txt", "/%2E%2E%2Fsecret.txt", "/..%2fsecret.txt",
        "/last-stack.png/../secret.txt", "/results/s1/luminance.png", "/secret.txt", "//secret.txt",
        "/days/", "/results/", "/api/status/../../secret.txt", "/%00/etc/passwd", "/etc/passwd",
        "/....//secret.txt", "/index.html", "/api"}) {
    const std::string response = rawRequest(
        port_, std::string("GET ") + path + " HTTP/1.1\r\nHost: x\r\nConnection: close\r\n\r\n");
    EXPECT_EQ(statusOf(response), 404) << path << ":\n" << response.substr(0, 200);
    EXPECT_EQ(response.find("not for the page"), std::string::npos) << path;
  }
}

TEST_F(StatusServerTest, OnlyGetAndHeadAreAnswered) {
  for (const char* method : {"POST", "PUT", "DELETE", "PATCH", "OPTIONS"}) {
    const std::string response = rawRequest(
        port_, std::string(method) +
                   " / HTTP/1.1\r\nHost: x\r\nConnection: close\r\nContent-Length: 0\r\n\r\n");
    EXPECT_EQ(statusOf(response), 405) << method << ":\n" << response.substr(0, 200);
    EXPECT_NE(response.find("Allow: GET, HEAD"), std::string::npos) << method;
  }
  // A body is never read: a GET's is ignored, any other method is refused before it is read
  // (a client announcing a gigabyte gets its 405 at once).
  const std::string gigabyte =
      rawRequest(port_,
                 "PUT / HTTP/1.1\r\nHost: x\r\nConnection: close\r\nContent-Length: "
                 "1073741824\r\n\r\npartial");
  EXPECT_EQ(statusOf(gigabyte), 405) << gigabyte.substr(0, 200);
  const std::string with_body = rawRequest(
      port_,
      "GET /metrics HTTP/1.1\r\nHost: x\r\nConnection: close\r\nContent-Length: 5\r\n\r\nhello");
  EXPECT_EQ(statusOf(with_body), 200) << with_body.substr(0, 200);
  const std::string long_uri =
      "GET /" + std::string(20000, 'a') + " HTTP/1.1\r\nHost: x\r\nConnection: close\r\n\r\n";
  EXPECT_NE(statusOf(rawRequest(port_, long_uri)), 200);
}

// The number of descriptors this process has open.
std::size_t openDescriptors() {
  std::size_t count = 0;
  for ([[maybe_unused]] const auto& entry : fs::directory_iterator("/proc/self/fd")) ++count;
  return count;
}

// Clients that connect and send nothing hold a thread until kStatusTimeout at most, and the
// server takes no more of them than its threads, its queue and the one its listening thread
// answers itself (the rest wait in the kernel's backlog); once they are dropped the page is
// served again. Times here only bound waits.
TEST_F(StatusServerTest, SilentClientsAreBoundedAndDropped) {
  const std::size_t before = openDescriptors();
  std::vector<UniqueFd> silent;
  const auto connectSilent = [&](std::size_t n) {
    for (std::size_t i = 0; i < n; ++i) {
      silent.push_back(testing::connectLoopback(port_));
      std::this_thread::sleep_for(5ms);  // time to accept each, if the server would
    }
    std::this_thread::sleep_for(300ms);
  };
  // Every thread busy with a silent client, every queue place taken by one: the next client,
  // one that asks, is answered 503 by the listening thread at once. (Were the server slower to
  // hand connections to its threads than these sleeps, it would be queued behind silent clients
  // and answered 200 after up to 4 rounds of kStatusTimeout: hence 30 s.)
  connectSilent(kStatusThreads);
  connectSilent(kStatusQueuedConnections);
  const std::string busy =
      rawRequest(port_, "GET / HTTP/1.1\r\nHost: x\r\nConnection: close\r\n\r\n", 30000);
  EXPECT_TRUE(statusOf(busy) == 503 || statusOf(busy) == 200) << busy.substr(0, 200);
  if (statusOf(busy) == 503) {
    EXPECT_NE(busy.find("Retry-After: 5"), std::string::npos) << busy;
  }
  // More: the listening thread holds the first of them while it waits for a request, and the
  // rest wait in the kernel's backlog (cpp-httplib listens with a backlog of 5), not in this
  // process. Beyond the backlog a connect waits for its SYN's retransmission (1 s, 3 s, ...), so
  // a few more than it holds are enough and keep the test short.
  constexpr std::size_t kOverflow = 8;
  connectSilent(kOverflow);
  // This process holds both ends: the clients' and what the server accepted.
  const std::size_t accepted = openDescriptors() - before - silent.size();
  EXPECT_LE(accepted, kStatusThreads + kStatusQueuedConnections + 1);
  EXPECT_GE(accepted, kStatusThreads);
  silent.clear();
  auto c = client();
  auto page = c.Get("/");
  ASSERT_TRUE(page);
  EXPECT_EQ(page->status, 200);
}

// A client that asks for a picture and never reads fills its socket's buffers and is dropped
// after kStatusTimeout; meanwhile the others are served.
TEST_F(StatusServerTest, AClientThatNeverReadsDoesNotStallTheOthers) {
  testing::writeText(dir_ / "results" / "s1" / "luminance.png", std::string(8 << 20, 'p'));
  std::vector<UniqueFd> stuck;
  for (int i = 0; i < 2; ++i) {
    stuck.push_back(testing::connectLoopback(port_));
    const std::string request =
        "GET /last-stack.png HTTP/1.1\r\nHost: x\r\nConnection: close\r\n\r\n";
    send(stuck.back().get(), request.data(), request.size(), MSG_NOSIGNAL);
  }
  std::this_thread::sleep_for(300ms);
  auto c = client();
  auto api = c.Get("/api/status");
  ASSERT_TRUE(api);
  EXPECT_EQ(api->status, 200);
}

TEST(StatusServer, AnAddressItCannotListenOnIsAnErrorNamingIt) {
  StatusBoard board;
  auto first = StatusServer::start({.host = "127.0.0.1", .port = 0}, board, nullptr);
  ASSERT_TRUE(first);
  const int taken = (*first)->address().port;
  auto second = StatusServer::start({.host = "127.0.0.1", .port = taken}, board, nullptr);
  ASSERT_FALSE(second);
  EXPECT_EQ(second.error().code, ErrorCode::kIo);
  EXPECT_NE(second.error().message.find("cannot listen on 127.0.0.1:" + std::to_string(taken)),
            std::string::npos)
      << second.error().message;
  auto foreign = StatusServer::start({.host = "192.0.2.77", .port = 0}, board, nullptr);
  ASSERT_FALSE(foreign);  // not an address of this host
  EXPECT_NE(foreign.error().message.find("192.0.2.77"), std::string::npos);
}

TEST(StatusServer, BeforeTheFirstSnapshotItSays503) {
  StatusBoard board;
  auto server = StatusServer::start({.host = "127.0.0.1", .port = 0}, board, nullptr);
  ASSERT_TRUE(server);
  httplib::Client c("127.0.0.1", (*server)->address().port);
  auto page = c.Get("/");
  ASSERT_TRUE(page);
  EXPECT_EQ(page->status, 503);
}

}  // namespace
}  // namespace glarecam::daemon
