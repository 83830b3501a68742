// trip.json as the report reads it back: every value kind, paths into nested objects, and errors
// that name the line and the member where the text stops being JSON.
#include <gtest/gtest.h>

#include <cmath>

#include "roadload/results/json.hpp"

namespace roadload::results {
namespace {

TEST(ResultsJson, ReadsEveryKindAndNestedPaths) {
  const auto doc = parse_json(R"({
  "crr": 0.0061, "identified": true, "none": null,
  "fuel": {"rolling_l": 1.25e-1, "uses": [1, -2.5, 3]},
  "name": "conc\"rete\u00b5\n"
})",
                              "trip.json");
  ASSERT_TRUE(doc.ok()) << doc.error().to_string();
  const JsonValue& v = doc.value();
  EXPECT_DOUBLE_EQ(*v.number_at("crr"), 0.0061);
  EXPECT_DOUBLE_EQ(*v.number_at("fuel.rolling_l"), 0.125);
  EXPECT_FALSE(v.number_at("fuel.missing").has_value());
  EXPECT_FALSE(v.number_at("identified").has_value());
  EXPECT_TRUE(v.find("identified")->boolean());
  EXPECT_EQ(v.find("none")->kind(), JsonValue::Kind::null);
  ASSERT_EQ(v.find("fuel")->find("uses")->items().size(), 3u);
  EXPECT_DOUBLE_EQ(v.find("fuel")->find("uses")->items()[1].number(), -2.5);
  EXPECT_EQ(v.find("name")->string(), "conc\"rete\xc2\xb5\n");
  EXPECT_EQ(v.find("fuel")->line(), 3);
  ASSERT_EQ(v.members().size(), 5u);
  EXPECT_EQ(v.members()[3].first, "fuel");
}

TEST(ResultsJson, AnErrorNamesTheLineAndTheMember) {
  const auto doc = parse_json("{\n  \"crr\": 0.006,\n  \"fuel\": {\"rolling_l\": tru}\n}", "trip.json");
  ASSERT_FALSE(doc.ok());
  EXPECT_EQ(doc.error().file, "trip.json");
  EXPECT_EQ(doc.error().line, 3);
  EXPECT_EQ(doc.error().field, "rolling_l");
  EXPECT_NE(doc.error().message.find("tru"), std::string::npos) << doc.error().message;
}

TEST(ResultsJson, RejectsWhatIsNotOneDocument) {
  for (const char* bad : {"", "{", "[1,]", "{\"a\" 1}", "{\"a\": 1} x", "\"open", "{\"a\": \"\\q\"}", "[\"\\u12\"]"}) {
    EXPECT_FALSE(parse_json(bad, "t").ok()) << bad;
  }
}

TEST(ResultsJson, BoundsNesting) {
  EXPECT_TRUE(parse_json(std::string(30, '[') + std::string(30, ']'), "t").ok());
  const auto deep = parse_json(std::string(100000, '['), "t");
  ASSERT_FALSE(deep.ok());
  EXPECT_NE(deep.error().message.find("nested deeper"), std::string::npos);
}

TEST(ResultsJson, AMissingFileIsAnErrorNotACrash) {
  const auto doc = read_json_file("/nonexistent/trip.json");
  ASSERT_FALSE(doc.ok());
  EXPECT_EQ(doc.error().file, "/nonexistent/trip.json");
}

}  // namespace
}  // namespace roadload::results
