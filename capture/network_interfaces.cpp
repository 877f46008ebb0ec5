#include "capture/network_interfaces.h"

#include <arpa/inet.h>
#include <ifaddrs.h>
#include <net/if.h>
#include <netinet/in.h>

#include <bit>

namespace glarecam::capture {

namespace {
constexpr std::uint32_t kLoopbackNet = 0x7f000000;  // 127.0.0.0/8 (RFC 1122)
constexpr std::uint32_t kLoopbackMask = 0xff000000;
}  // namespace

std::vector<NetworkInterface> hostInterfaces() {
  std::vector<NetworkInterface> interfaces;
  ifaddrs* list = nullptr;
  if (getifaddrs(&list) != 0) return interfaces;
  for (const ifaddrs* entry = list; entry != nullptr; entry = entry->ifa_next) {
    if (entry->ifa_addr == nullptr || entry->ifa_addr->sa_family != AF_INET) continue;
    const auto* address = reinterpret_cast<const sockaddr_in*>(entry->ifa_addr);
    const auto* netmask = reinterpret_cast<const sockaddr_in*>(entry->ifa_netmask);
    interfaces.push_back({.name = entry->ifa_name,
                          .address = ntohl(address->sin_addr.s_addr),
                          .netmask = netmask != nullptr ? ntohl(netmask->sin_addr.s_addr) : 0,
                          .loopback = (entry->ifa_flags & IFF_LOOPBACK) != 0,
                          .up = (entry->ifa_flags & IFF_UP) != 0});
  }
  freeifaddrs(list);
  return interfaces;
}

std::optional<std::uint32_t> parseIpv4(std::string_view text) {
  const std::string copy(text);
  in_addr parsed{};
  if (inet_pton(AF_INET, copy.c_str(), &parsed) != 1) return std::nullopt;
  return ntohl(parsed.s_addr);
}

std::string formatIpv4(std::uint32_t address) {
  return std::to_string(address >> 24) + "." + std::to_string((address >> 16) & 0xff) + "." +
         std::to_string((address >> 8) & 0xff) + "." + std::to_string(address & 0xff);
}

std::optional<NetworkInterface> streamInterfaceFor(
    std::uint32_t device_address, const std::vector<NetworkInterface>& interfaces) {
  const bool loopback_device = (device_address & kLoopbackMask) == kLoopbackNet;
  std::optional<NetworkInterface> best;
  int best_prefix = -1;
  for (const NetworkInterface& candidate : interfaces) {
    if (!candidate.up) continue;
    if (loopback_device) {
      if (candidate.loopback && !best) best = candidate;
      continue;
    }
    if (candidate.loopback || candidate.netmask == 0) continue;
    if ((candidate.address & candidate.netmask) != (device_address & candidate.netmask)) continue;
    const int prefix = std::popcount(candidate.netmask);
    if (prefix > best_prefix) {
      best = candidate;
      best_prefix = prefix;
    }
  }
  return best;
}

std::string describeInterface(const NetworkInterface& interface) {
  return interface.name + " (" + formatIpv4(interface.address) + ")";
}

}  // namespace glarecam::capture
