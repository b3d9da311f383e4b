// vsi serve's token rules: which addresses need one, and which headers carry it.
#include <gtest/gtest.h>

#include "http/bearer_token.hpp"

namespace railvsi::scheduler {
namespace {

TEST(BearerToken, OnlyTheExactTokenAfterTheBearerSchemeMatches) {
  EXPECT_TRUE(bearer_matches("Bearer abc123", "abc123"));
  EXPECT_FALSE(bearer_matches("Bearer abc124", "abc123"));   // same length, last byte differs
  EXPECT_FALSE(bearer_matches("Bearer abc12", "abc123"));    // a prefix of it
  EXPECT_FALSE(bearer_matches("Bearer abc1234", "abc123"));  // it as a prefix
  EXPECT_FALSE(bearer_matches("abc123", "abc123"));          // no scheme
  EXPECT_FALSE(bearer_matches("Basic abc123", "abc123"));
  EXPECT_FALSE(bearer_matches("", "abc123"));
  EXPECT_FALSE(bearer_matches("Bearer ", ""));  // an empty token never matches
}

TEST(BearerToken, LoopbackAddressesNeedNoToken) {
  for (const char* a : {"127.0.0.1", "127.1.2.3", "::1", "localhost"}) EXPECT_TRUE(is_loopback_address(a)) << a;
  for (const char* a : {"0.0.0.0", "::", "10.0.0.5", "192.168.1.2", "1270.0.0.1", ""})
    EXPECT_FALSE(is_loopback_address(a)) << a;
}

}  // namespace
}  // namespace railvsi::scheduler
