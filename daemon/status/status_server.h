// glarecamd's status page over HTTP ([status] listen, `glarecamd --status`; docs/operator.md):
// read-only views of the latest StatusSnapshot (status_page.h), served by cpp-httplib on threads
// of its own. Only status_server.cpp includes cpp-httplib.
//
// What a client can do, and what it cannot:
//   - GET (and HEAD) of five fixed paths: /, /api/status, /metrics, /last-stack.png and
//     /datasheet.png; any other path is 404, any other method 405. No path of a request reaches
//     the filesystem: the two pictures are files the snapshot names, no directory is listed.
//   - Bounded: kStatusThreads connections are served at once, kStatusQueuedConnections more wait;
//     beyond that the listening thread answers the newest connection itself with 503 (so a flood
//     of connections waits in the kernel's backlog, not in memory). A request's line and headers
//     are capped by cpp-httplib (8 KiB each), a body at kStatusMaxBody bytes; a client that sends
//     nothing, or never reads, is dropped after kStatusTimeout.
//   - Never in the way of capture: the server only ever takes the board's latest snapshot (a
//     pointer's copy under a mutex) and the log ring's entries; the event loop never waits on it.
#pragma once

#include <chrono>
#include <cstddef>
#include <memory>
#include <string>

#include "core/error.h"
#include "daemon/status/listen_address.h"
#include "daemon/status/log_ring.h"
#include "daemon/status/status_board.h"

namespace glarecam::daemon {

inline constexpr std::size_t kStatusThreads = 4;
inline constexpr std::size_t kStatusQueuedConnections = 16;
inline constexpr std::size_t kStatusMaxBody = 1024;
inline constexpr std::chrono::seconds kStatusTimeout{5};
// A browser keeps a connection open after a page for this long; short, so that a page and its two
// pictures do not hold the threads.
inline constexpr std::chrono::seconds kStatusKeepAlive{1};
// The largest picture served (a data sheet PNG is about 0.5 MiB, a 12 MP luminance.png ~10 MiB).
inline constexpr std::size_t kStatusMaxFileBytes = std::size_t{64} << 20;

class StatusServer {
 public:
  // Listens on `address` and serves from its own threads until destroyed. kIo naming the address
  // when it cannot listen (in use, not an address of this host, not permitted).
  static Result<std::unique_ptr<StatusServer>> start(const ListenAddress& address,
                                                     const StatusBoard& board,
                                                     std::shared_ptr<LogRing> log);
  ~StatusServer();  // stops listening, finishes the requests being served, joins
  StatusServer(const StatusServer&) = delete;
  StatusServer& operator=(const StatusServer&) = delete;

  // The address listened on, with the port taken when port 0 was asked for.
  const ListenAddress& address() const;
  std::string url() const;  // "http://127.0.0.1:8080/"

  class Impl;

 private:
  explicit StatusServer(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace glarecam::daemon
