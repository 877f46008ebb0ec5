#include "capture/network_interfaces.h"

#include <gtest/gtest.h>

namespace glarecam::capture {
namespace {

std::uint32_t ip(const char* text) { return parseIpv4(text).value(); }

// A rig's interfaces: loopback, the management NIC, the camera NIC (a /30 inside a /16 the
// management NIC also reaches), Wi-Fi, and a NIC that is down.
std::vector<NetworkInterface> rig() {
  return {
      {.name = "lo", .address = ip("127.0.0.1"), .netmask = ip("255.0.0.0"), .loopback = true},
      {.name = "eth0", .address = ip("10.1.0.5"), .netmask = ip("255.255.0.0")},
      {.name = "eth1", .address = ip("10.1.7.1"), .netmask = ip("255.255.255.252")},
      {.name = "wlan0", .address = ip("192.168.1.40"), .netmask = ip("255.255.255.0")},
      {.name = "eth2", .address = ip("169.254.3.1"), .netmask = ip("255.255.0.0"), .up = false},
  };
}

TEST(NetworkInterfaces, ParsesAndFormatsDottedIpv4Only) {
  EXPECT_EQ(parseIpv4("192.168.1.20"), 0xc0a80114u);
  EXPECT_EQ(formatIpv4(0xc0a80114u), "192.168.1.20");
  for (const char* bad :
       {"", "GV01", "192.168.1", "192.168.1.256", "::1", "192.168.1.20 ", "-1.0.0.0"})
    EXPECT_FALSE(parseIpv4(bad)) << bad;
}

TEST(NetworkInterfaces, LoopbackCameraStreamsToLoopbackWhateverElseIsThere) {
  // Issue 21: a camera on 127.0.0.1, discovered through eth0, streamed to eth0 and never arrived.
  for (const char* address : {"127.0.0.1", "127.0.0.2", "127.255.255.254"}) {
    const auto chosen = streamInterfaceFor(ip(address), rig());
    ASSERT_TRUE(chosen) << address;
    EXPECT_EQ(chosen->name, "lo") << address;
  }
}

TEST(NetworkInterfaces, TheSubnetThatHoldsTheCameraWinsTheLongestPrefixFirst) {
  EXPECT_EQ(streamInterfaceFor(ip("10.1.7.2"), rig())->name, "eth1");  // /30 beats /16
  EXPECT_EQ(streamInterfaceFor(ip("10.1.200.9"), rig())->name, "eth0");
  EXPECT_EQ(streamInterfaceFor(ip("192.168.1.20"), rig())->name, "wlan0");
  EXPECT_EQ(describeInterface(*streamInterfaceFor(ip("10.1.7.2"), rig())), "eth1 (10.1.7.1)");
}

TEST(NetworkInterfaces, NoSubnetHoldsARoutedCameraAndDownInterfacesDoNotCount) {
  EXPECT_FALSE(streamInterfaceFor(ip("172.16.0.9"), rig()));
  EXPECT_FALSE(streamInterfaceFor(ip("169.254.3.7"), rig()));  // eth2 is down
  std::vector<NetworkInterface> no_loopback = rig();
  no_loopback.erase(no_loopback.begin());
  EXPECT_FALSE(streamInterfaceFor(ip("127.0.0.1"), no_loopback));
}

TEST(NetworkInterfaces, ThisHostHasALoopbackInterface) {
  const auto interfaces = hostInterfaces();
  const auto chosen = streamInterfaceFor(ip("127.0.0.1"), interfaces);
  ASSERT_TRUE(chosen) << "no IPv4 loopback interface up here";
  EXPECT_TRUE(chosen->loopback);
}

}  // namespace
}  // namespace glarecam::capture
