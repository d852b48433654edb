// The summaries' JSON tree (io/json_writer.h): its text is the format the
// CLI has always printed (keys in insertion order, ", " and ": " between
// items, numbers with 17 significant digits, non-finite numbers as null,
// integers and integer arrays without a decimal point), and its values can
// be read back without parsing text.
#include "shellspace/io/json_writer.h"

#include <gtest/gtest.h>

#include <limits>
#include <string>
#include <vector>

namespace shellspace {
namespace {

TEST(JsonWriterTest, PrintsEveryKindAsBefore) {
  const JsonObject inner = JsonObject().Add("n", 2).Add("x", 0.5);
  const JsonObject json =
      JsonObject()
          .Add("int", 3)
          .Add("number", 0.1)
          .Add("true", true)
          .Add("text", std::string("a\"b\\c\nd"))
          .Add("chars", "e")
          .Add("numbers", std::vector<double>{1.0, 2.5})
          .Add("ints", std::vector<int>{4, -5})
          .Add("texts", std::vector<std::string>{"f", "g"})
          .Add("object", inner)
          .Add("objects", std::vector<JsonObject>{inner, JsonObject()})
          .Add("nan", std::numeric_limits<double>::quiet_NaN())
          .Add("inf", std::numeric_limits<double>::infinity())
          .Add("empty", std::vector<double>{})
          .Raw("raw", "[1,2]");
  EXPECT_EQ(json.str(),
            "{\"int\": 3, \"number\": 0.10000000000000001, \"true\": true, "
            "\"text\": \"a\\\"b\\\\c\\nd\", \"chars\": \"e\", "
            "\"numbers\": [1, 2.5], \"ints\": [4, -5], "
            "\"texts\": [\"f\", \"g\"], \"object\": {\"n\": 2, \"x\": 0.5}, "
            "\"objects\": [{\"n\": 2, \"x\": 0.5}, {}], \"nan\": null, "
            "\"inf\": null, \"empty\": [], \"raw\": [1,2]}");
  EXPECT_EQ(JsonObject().str(), "{}");
}

TEST(JsonWriterTest, TheTreeHoldsTheValuesAndFindsRawText) {
  JsonObject json;
  json.Add("a", 7).Add("b", 0.25).Add("c", JsonObject().Add("d", false));
  const JsonValue& value = json.value();
  ASSERT_EQ(value.kind(), JsonValue::Kind::kObject);
  ASSERT_EQ(value.members().size(), 3u);
  EXPECT_EQ(value.members()[0].first, "a");
  EXPECT_EQ(value.members()[0].second.kind(), JsonValue::Kind::kInt);
  EXPECT_EQ(value.members()[0].second.integer(), 7);
  EXPECT_EQ(value.members()[1].second.kind(), JsonValue::Kind::kNumber);
  EXPECT_EQ(value.members()[1].second.number(), 0.25);
  const JsonValue& c = value.members()[2].second;
  ASSERT_EQ(c.kind(), JsonValue::Kind::kObject);
  EXPECT_FALSE(c.members()[0].second.boolean());
  EXPECT_FALSE(value.ContainsRaw());
  // The twin: raw text deep in an array of objects is found.
  json.Add("e", std::vector<JsonObject>{JsonObject().Raw("f", "{}")});
  EXPECT_TRUE(json.value().ContainsRaw());
}

}  // namespace
}  // namespace shellspace
