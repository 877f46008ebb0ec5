#include "daemon/status/listen_address.h"

#include <arpa/inet.h>
#include <fmt/format.h>

#include <charconv>

namespace glarecam::daemon {

namespace {

constexpr int kMaxPort = 65535;

std::unexpected<Error> invalid(std::string_view text, std::string_view why) {
  return badInput(fmt::format(
      "expected ADDRESS:PORT such as 127.0.0.1:8080 or [::1]:8080, got \"{}\" ({})", text, why));
}

}  // namespace

std::string ListenAddress::text() const {
  return ipv6() ? fmt::format("[{}]:{}", host, port) : fmt::format("{}:{}", host, port);
}

Result<ListenAddress> parseListenAddress(std::string_view text) {
  const std::size_t colon = text.rfind(':');
  if (colon == std::string_view::npos) return invalid(text, "no port");
  std::string_view host = text.substr(0, colon);
  const std::string_view port = text.substr(colon + 1);
  const bool bracketed = host.size() >= 2 && host.front() == '[' && host.back() == ']';
  if (bracketed) host = host.substr(1, host.size() - 2);
  if (host.empty()) return invalid(text, "no address");
  ListenAddress address{.host = std::string(host)};
  unsigned char parsed[16];
  const bool v4 = !bracketed && inet_pton(AF_INET, address.host.c_str(), parsed) == 1;
  const bool v6 = bracketed && inet_pton(AF_INET6, address.host.c_str(), parsed) == 1;
  if (!v4 && !v6)
    return invalid(text, bracketed || host.find(':') != std::string_view::npos
                             ? "not an IPv6 address in brackets"
                             : "not an IPv4 address; host names are not looked up");
  const auto [end, error] = std::from_chars(port.data(), port.data() + port.size(), address.port);
  if (port.empty() || error != std::errc() || end != port.data() + port.size() ||
      address.port < 0 || address.port > kMaxPort)
    return invalid(text, "the port must be a number from 0 to 65535");
  return address;
}

}  // namespace glarecam::daemon
