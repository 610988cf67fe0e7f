// The operator view's listen address: what parses, what is loopback, what is refused and why.
#include "app/runtime/operator_view_params.hpp"

#include <gtest/gtest.h>

namespace rovctl::app {
namespace {

TEST(ListenAddress, ParsesHostAndPort) {
  ListenAddress a;
  std::string error;
  ASSERT_TRUE(parse_listen_address("127.0.0.1:8080", a, error)) << error;
  EXPECT_EQ(a.host, "127.0.0.1");
  EXPECT_EQ(a.port, 8080);
  EXPECT_TRUE(a.loopback());
  ASSERT_TRUE(parse_listen_address("[::1]:9000", a, error)) << error;
  EXPECT_EQ(a.host, "::1");
  EXPECT_TRUE(a.loopback());
  ASSERT_TRUE(parse_listen_address("0.0.0.0:80", a, error)) << error;
  EXPECT_FALSE(a.loopback()) << "every interface is reachable from the network";
  ASSERT_TRUE(parse_listen_address("192.168.2.2:8080", a, error)) << error;
  EXPECT_FALSE(a.loopback());
}

TEST(ListenAddress, PortZeroMeansAnyFreePort) {
  ListenAddress a;
  std::string error;
  ASSERT_TRUE(parse_listen_address("127.0.0.1:0", a, error)) << error;
  EXPECT_EQ(a.port, 0);
}

TEST(ListenAddress, RefusesMalformedAddresses) {
  ListenAddress a;
  for (const char* bad : {"", "8080", ":8080", "127.0.0.1:", "127.0.0.1:http", "127.0.0.1:70000",
                          "[::1]8080", "localhost:-1"}) {
    std::string error;
    EXPECT_FALSE(parse_listen_address(bad, a, error)) << bad;
    EXPECT_FALSE(error.empty()) << bad;
  }
}

}  // namespace
}  // namespace rovctl::app
