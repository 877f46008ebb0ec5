// Where glarecamd's status page listens ([status] listen, `glarecamd --status`): a literal IP
// address and a port, "127.0.0.1:8080" or "[::1]:8080". No host names: a rig in a field has no
// name service to ask, and the operator chooses which interface the page is on (docs/operator.md).
#pragma once

#include <string>
#include <string_view>

#include "core/error.h"

namespace glarecam::daemon {

struct ListenAddress {
  std::string host;  // an IPv4 or IPv6 literal, without brackets
  int port = 0;      // 0: any free port (tests), the one taken is logged
  bool ipv6() const { return host.find(':') != std::string::npos; }
  // "127.0.0.1:8080", "[::1]:8080".
  std::string text() const;
  bool operator==(const ListenAddress&) const = default;
};

// kBadInput naming what is wrong: "expected ADDRESS:PORT such as 127.0.0.1:8080, got ...".
Result<ListenAddress> parseListenAddress(std::string_view text);

}  // namespace glarecam::daemon
