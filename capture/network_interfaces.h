// Which of this host's network interfaces a GigE Vision camera's stream should come to: the one
// whose IPv4 subnet holds the camera's address (the longest prefix when several do), a loopback
// interface for a loopback address. Aravis, left to itself, streams to the interface on which
// discovery first heard the camera; on a host with several interfaces (a camera NIC, a management
// NIC, Wi-Fi) that can be one from which the stream never arrives (issue 21: a camera on
// 127.0.0.1 heard through eth0). The Aravis backend opens a GigE camera on the interface chosen
// here; `glarecam cameras` and `glarecam doctor` name it.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace glarecam::capture {

struct NetworkInterface {
  std::string name;           // "eth0"
  std::uint32_t address = 0;  // IPv4, host byte order
  std::uint32_t netmask = 0;  // host byte order
  bool loopback = false;
  bool up = true;
};

// The IPv4 interfaces of this host that are up (getifaddrs); empty when it fails.
std::vector<NetworkInterface> hostInterfaces();

// "192.168.1.20" → host-order address; nullopt for anything but a dotted IPv4 address.
std::optional<std::uint32_t> parseIpv4(std::string_view text);
std::string formatIpv4(std::uint32_t address);

// The interface `device_address` streams to, among `interfaces` (those down ignored): the one
// whose subnet holds it, the longest prefix first; for an address in 127.0.0.0/8, a loopback
// interface. nullopt when none does (a routed camera: the caller lets Aravis choose).
std::optional<NetworkInterface> streamInterfaceFor(std::uint32_t device_address,
                                                   const std::vector<NetworkInterface>& interfaces);

// "lo (127.0.0.1)", as `cameras` and `doctor` print it.
std::string describeInterface(const NetworkInterface& interface);

}  // namespace glarecam::capture
