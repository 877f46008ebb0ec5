// [status] listen and --status: literal addresses and a port, and a clear error for the rest.
#include "daemon/status/listen_address.h"

#include <gtest/gtest.h>

namespace glarecam::daemon {
namespace {

TEST(ListenAddress, Ipv4AndBracketedIpv6WithAPort) {
  auto v4 = parseListenAddress("127.0.0.1:8080");
  ASSERT_TRUE(v4) << v4.error().message;
  EXPECT_EQ(v4->host, "127.0.0.1");
  EXPECT_EQ(v4->port, 8080);
  EXPECT_FALSE(v4->ipv6());
  EXPECT_EQ(v4->text(), "127.0.0.1:8080");
  auto v6 = parseListenAddress("[::1]:9100");
  ASSERT_TRUE(v6) << v6.error().message;
  EXPECT_EQ(v6->host, "::1");
  EXPECT_TRUE(v6->ipv6());
  EXPECT_EQ(v6->text(), "[::1]:9100");
  auto any = parseListenAddress("0.0.0.0:0");
  ASSERT_TRUE(any);
  EXPECT_EQ(any->port, 0);
}

TEST(ListenAddress, AnythingElseIsBadInputSayingWhy) {
  const std::pair<const char*, const char*> cases[] = {
      {"127.0.0.1", "no port"},
      {":8080", "no address"},
      {"localhost:8080", "host names are not looked up"},
      {"::1:8080", "not an IPv6 address in brackets"},
      {"[127.0.0.1]:8080", "not an IPv6 address in brackets"},
      {"300.1.2.3:80", "not an IPv4 address"},
      {"127.0.0.1:65536", "from 0 to 65535"},
      {"127.0.0.1:-1", "from 0 to 65535"},
      {"127.0.0.1:80x", "from 0 to 65535"},
      {"127.0.0.1:", "from 0 to 65535"},
      {"", "no port"},
  };
  for (const auto& [text, why] : cases) {
    auto parsed = parseListenAddress(text);
    ASSERT_FALSE(parsed) << text;
    EXPECT_EQ(parsed.error().code, ErrorCode::kBadInput);
    EXPECT_NE(parsed.error().message.find(why), std::string::npos)
        << text << ": " << parsed.error().message;
    EXPECT_NE(parsed.error().message.find("127.0.0.1:8080"), std::string::npos);
  }
}

}  // namespace
}  // namespace glarecam::daemon
