#include "daemon/status/status_server.h"

#include <fmt/format.h>
#include <httplib.h>
#include <spdlog/spdlog.h>
#include <sys/socket.h>

#include <atomic>
#include <cerrno>
#include <condition_variable>
#include <cstring>
#include <deque>
#include <fstream>
#include <functional>
#include <mutex>
#include <optional>
#include <thread>
#include <vector>

#include "core/json.h"
#include "daemon/status/status_page.h"

namespace glarecam::daemon {

namespace {

// Set on the listening thread while it answers a connection itself because every thread is busy
// and the queue is full: that connection gets 503.
thread_local bool t_overloaded = false;

// cpp-httplib's ThreadPool with a bound on the connections waiting: beyond it, the listening
// thread serves the newest connection itself (with a 503), so that it accepts no more until that
// one is done and further clients wait in the kernel's listen backlog.
class BoundedPool final : public httplib::TaskQueue {
 public:
  BoundedPool(std::size_t threads, std::size_t max_queued) : max_queued_(max_queued) {
    for (std::size_t i = 0; i < threads; ++i) threads_.emplace_back([this] { work(); });
  }
  ~BoundedPool() override { shutdown(); }

  void enqueue(std::function<void()> fn) override {
    {
      const std::lock_guard lock(mutex_);
      if (jobs_.size() < max_queued_) {
        jobs_.push_back(std::move(fn));
        wake_.notify_one();
        return;
      }
    }
    t_overloaded = true;
    fn();
    t_overloaded = false;
  }

  void shutdown() override {
    {
      const std::lock_guard lock(mutex_);
      if (shutdown_) return;
      shutdown_ = true;
    }
    wake_.notify_all();
    for (std::thread& t : threads_) t.join();
  }

 private:
  void work() {
    for (;;) {
      std::function<void()> fn;
      {
        std::unique_lock lock(mutex_);
        wake_.wait(lock, [this] { return shutdown_ || !jobs_.empty(); });
        if (jobs_.empty()) return;  // shutting down, every accepted connection served
        fn = std::move(jobs_.front());
        jobs_.pop_front();
      }
      fn();
    }
  }

  const std::size_t max_queued_;
  std::mutex mutex_;
  std::condition_variable wake_;
  std::deque<std::function<void()>> jobs_;
  bool shutdown_ = false;
  std::vector<std::thread> threads_;
};

// The whole file, or nullopt when it cannot be read or is larger than kStatusMaxFileBytes.
std::optional<std::string> readSmallFile(const std::filesystem::path& path) {
  std::error_code error;
  const auto size = std::filesystem::file_size(path, error);
  if (error || size > kStatusMaxFileBytes || !std::filesystem::is_regular_file(path, error))
    return std::nullopt;
  std::ifstream in(path, std::ios::binary);
  std::string bytes(size, '\0');
  if (!in.read(bytes.data(), static_cast<std::streamsize>(size))) return std::nullopt;
  return bytes;
}

void notFound(httplib::Response& response, std::string_view what) {
  response.status = 404;
  response.set_content(fmt::format("404 not found: {}\n", what), "text/plain; charset=utf-8");
}

}  // namespace

class StatusServer::Impl {
 public:
  Impl(const StatusBoard& board, std::shared_ptr<LogRing> log)
      : board_(board), log_(std::move(log)) {}

  ~Impl() {
    server_.stop();
    if (thread_.joinable()) thread_.join();
  }

  Status listen(const ListenAddress& address) {
    configure();
    if (address.ipv6()) server_.set_address_family(AF_INET6);
    errno = 0;
    int port = address.port;
    bool bound = false;
    if (address.port == 0) {
      port = server_.bind_to_any_port(address.host);
      bound = port > 0;
    } else {
      bound = server_.bind_to_port(address.host, address.port);
    }
    if (!bound)
      return fail(ErrorCode::kIo,
                  fmt::format("status page: cannot listen on {}{}", address.text(),
                              errno ? fmt::format(" ({})", std::strerror(errno)) : ""));
    address_ = address;
    address_.port = port;
    thread_ = std::thread([this] {
      if (!server_.listen_after_bind())
        spdlog::error("glarecamd: status page: stopped listening on {}", address_.text());
      ended_ = true;
    });
    // cpp-httplib's stop() does nothing until its loop runs: a server destroyed before then would
    // never stop. The loop runs within microseconds, or listen_after_bind() returns at once.
    while (!server_.is_running() && !ended_)
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    if (!server_.is_running())
      return fail(ErrorCode::kIo, "status page: the server did not start on " + address_.text());
    return {};
  }

  const ListenAddress& address() const { return address_; }

 private:
  std::shared_ptr<const StatusSnapshot> snapshot() const { return board_.latest(); }
  std::vector<LogEntry> logEntries() const {
    return log_ ? log_->entries() : std::vector<LogEntry>{};
  }

  void configure() {
    server_.new_task_queue = [] {
      return new BoundedPool(kStatusThreads, kStatusQueuedConnections);
    };
    // SO_REUSEADDR only (a restart binds while the old sockets linger in TIME_WAIT), not
    // cpp-httplib's default SO_REUSEPORT too: a second glarecamd would share the port, silently
    // answering half the requests.
    server_.set_socket_options([](socket_t socket) {
      const int yes = 1;
      setsockopt(socket, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof yes);
    });
    server_.set_read_timeout(kStatusTimeout);
    server_.set_write_timeout(kStatusTimeout);
    server_.set_keep_alive_timeout(kStatusKeepAlive.count());
    server_.set_payload_max_length(kStatusMaxBody);
    server_.set_default_headers({
        {"Cache-Control", "no-store"},
        {"X-Content-Type-Options", "nosniff"},
        {"X-Frame-Options", "DENY"},
        {"Content-Security-Policy",
         "default-src 'none'; img-src 'self'; style-src 'unsafe-inline'"},
    });
    server_.set_pre_routing_handler(
        [](const httplib::Request& request, httplib::Response& response) {
          if (t_overloaded) {
            response.status = 503;
            response.set_header("Retry-After", "5");
            response.set_content("503 busy: too many connections to the status page\n",
                                 "text/plain; charset=utf-8");
            return httplib::Server::HandlerResponse::Handled;
          }
          if (request.method != "GET" && request.method != "HEAD") {
            response.status = 405;
            response.set_header("Allow", "GET, HEAD");
            response.set_content("405 method not allowed: the status page is read-only\n",
                                 "text/plain; charset=utf-8");
            return httplib::Server::HandlerResponse::Handled;
          }
          return httplib::Server::HandlerResponse::Unhandled;
        });
    server_.set_error_handler([](const httplib::Request&, httplib::Response& response) {
      if (!response.body.empty()) return;
      response.set_content(fmt::format("{} {}\n", response.status,
                                       response.status == 404 ? "not found" : "bad request"),
                           "text/plain; charset=utf-8");
    });
    server_.set_exception_handler(
        [](const httplib::Request&, httplib::Response& response, std::exception_ptr) {
          response.status = 500;
          response.set_content("500 internal error\n", "text/plain; charset=utf-8");
        });
    server_.set_logger([](const httplib::Request& request, const httplib::Response& response) {
      spdlog::debug("glarecamd: status page: {} {} {}", request.method, request.path,
                    response.status);
    });

    server_.Get("/", [this](const httplib::Request&, httplib::Response& response) {
      const auto s = snapshot();
      if (!s) return unavailable(response);
      response.set_content(statusHtml(*s, logEntries()), "text/html; charset=utf-8");
    });
    server_.Get("/api/status", [this](const httplib::Request&, httplib::Response& response) {
      const auto s = snapshot();
      if (!s) return unavailable(response);
      response.set_content(jsonText(statusJson(*s, logEntries())) + "\n",
                           "application/json; charset=utf-8");
    });
    server_.Get("/metrics", [this](const httplib::Request&, httplib::Response& response) {
      const auto s = snapshot();
      if (!s) return unavailable(response);
      response.set_content(statusMetrics(*s), "text/plain; version=0.0.4; charset=utf-8");
    });
    servePicture("/last-stack.png", StatusPicture::kLastStack);
    servePicture("/datasheet.png", StatusPicture::kDatasheet);
  }

  void servePicture(const char* route, StatusPicture picture) {
    server_.Get(route, [this, picture](const httplib::Request&, httplib::Response& response) {
      const auto s = snapshot();
      if (!s) return notFound(response, statusPictureMissing(StatusSnapshot{}, picture));
      const auto path = statusPicture(*s, picture);
      const auto bytes = path ? readSmallFile(*path) : std::nullopt;
      if (!bytes) return notFound(response, statusPictureMissing(*s, picture));
      response.set_content(*bytes, "image/png");
    });
  }

  static void unavailable(httplib::Response& response) {
    response.status = 503;
    response.set_header("Retry-After", "1");
    response.set_content("503 glarecamd is starting\n", "text/plain; charset=utf-8");
  }

  const StatusBoard& board_;
  std::shared_ptr<LogRing> log_;
  httplib::Server server_;
  ListenAddress address_;
  std::atomic<bool> ended_ = false;
  std::thread thread_;
};

StatusServer::StatusServer(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
StatusServer::~StatusServer() = default;

Result<std::unique_ptr<StatusServer>> StatusServer::start(const ListenAddress& address,
                                                          const StatusBoard& board,
                                                          std::shared_ptr<LogRing> log) {
  auto impl = std::make_unique<Impl>(board, std::move(log));
  GLARECAM_CHECK(impl->listen(address));
  return std::unique_ptr<StatusServer>(new StatusServer(std::move(impl)));
}

const ListenAddress& StatusServer::address() const { return impl_->address(); }

std::string StatusServer::url() const { return fmt::format("http://{}/", address().text()); }

}  // namespace glarecam::daemon
