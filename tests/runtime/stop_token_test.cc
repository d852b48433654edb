// StopToken: the default token never says stop and asks nothing; a token
// says what its poll says, each time it is asked; copies share the poll.
#include "shellspace/runtime/stop_token.h"

#include <gtest/gtest.h>

#include <functional>

namespace shellspace {
namespace {

TEST(StopTokenTest, DefaultAndEmptyPollNeverStop) {
  const StopToken none;
  EXPECT_FALSE(none.stop_possible());
  EXPECT_FALSE(none.stop_requested());
  const StopToken empty{std::function<bool()>()};
  EXPECT_FALSE(empty.stop_possible());
  EXPECT_FALSE(empty.stop_requested());
}

TEST(StopTokenTest, SaysWhatItsPollSaysAndCopiesShareIt) {
  int asked = 0;
  const StopToken token([&asked] { return ++asked >= 3; });
  EXPECT_TRUE(token.stop_possible());
  const StopToken copy = token;
  EXPECT_FALSE(token.stop_requested());
  EXPECT_FALSE(copy.stop_requested());
  EXPECT_TRUE(token.stop_requested());
  EXPECT_TRUE(copy.stop_requested());
  EXPECT_EQ(asked, 4);
}

}  // namespace
}  // namespace shellspace
