// Comma lists (core/text.h): what --passes, --config, --format and the dataset spec's lists go
// through between the command line, the spec and the sequence pipeline.
#include <gtest/gtest.h>

#include "core/text.h"

namespace inet {
namespace {

TEST(Text, CommaListsSplitWithoutEmptyItemsAndJoinBack) {
  EXPECT_EQ(splitCommaList("rgb,depth,,label,"),
            (std::vector<std::string>{"rgb", "depth", "label"}));
  EXPECT_TRUE(splitCommaList("").empty());
  EXPECT_TRUE(splitCommaList(",,").empty());
  EXPECT_EQ(splitCommaList("original"), (std::vector<std::string>{"original"}));
  const std::vector<std::string> items = {"original", "lighting:1", "rearranged:2"};
  EXPECT_EQ(joinCommaList(items), "original,lighting:1,rearranged:2");
  EXPECT_EQ(splitCommaList(joinCommaList(items)), items);
  EXPECT_EQ(joinCommaList({}), "");
}

}  // namespace
}  // namespace inet
