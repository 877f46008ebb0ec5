#include "core/json.h"

#include <gtest/gtest.h>

#include "support/test_support.h"

namespace glarecam {
namespace {

using nlohmann::json;

std::string errorOf(const auto& result) {
  return result ? std::string("(no error)") : result.error().message;
}

TEST(JsonText, InvalidJsonGivesLineAndColumn) {
  auto document = parseJsonText("{\n  \"schema\": ,\n}", "x/stack.json");
  ASSERT_FALSE(document);
  EXPECT_EQ(document.error().code, ErrorCode::kBadInput);
  EXPECT_NE(document.error().message.find("x/stack.json: invalid JSON"), std::string::npos);
  EXPECT_NE(document.error().message.find("line 2"), std::string::npos) << document.error().message;
}

TEST(JsonText, NestingBeyondTheLimitIsRefusedWhileParsing) {
  const std::string deep =
      std::string(kMaxJsonDepth + 1, '[') + std::string(kMaxJsonDepth + 1, ']');
  const std::string fine = std::string(kMaxJsonDepth, '[') + std::string(kMaxJsonDepth, ']');
  EXPECT_NE(errorOf(parseJsonText(deep, "deep.json")).find("deep.json: invalid JSON: nesting"),
            std::string::npos);
  EXPECT_TRUE(parseJsonText(fine, "fine.json"));
}

TEST(JsonText, BinaryBytesInAParseErrorStayPrintable) {
  const std::string message = errorOf(parseJsonText(std::string("{\"a\": \x01\x7f}"), "b.json"));
  for (char c : message) EXPECT_GE(static_cast<unsigned char>(c), 0x20) << message;
}

TEST(JsonText, WrittenTextIsIndentedEndsInANewlineAndSurvivesBadUtf8) {
  const json document{{"name", std::string("caf\xe9")}};  // Latin-1, not UTF-8
  const std::string text = jsonText(document);
  EXPECT_EQ(text, "{\n  \"name\": \"caf\xef\xbf\xbd\"\n}\n");
}

TEST(JsonFile, WrittenAtomicallyAndReadBack) {
  testing::TempDir dir;
  const json document{{"alpha_deg", 42.5}, {"list", {1, 2, 3}}};
  ASSERT_TRUE(writeJsonFile(dir.path() / "d.json", document));
  auto read = readJsonFile(dir.path() / "d.json");
  ASSERT_TRUE(read) << read.error().message;
  EXPECT_EQ(*read, document);
}

TEST(JsonFile, MissingFileIsBadInputNamingIt) {
  testing::TempDir dir;
  auto read = readJsonFile(dir.path() / "none.json");
  ASSERT_FALSE(read);
  EXPECT_EQ(read.error().code, ErrorCode::kBadInput);
  EXPECT_EQ(read.error().message,
            (dir.path() / "none.json").string() + ": file is missing or not a regular file");
}

const json kScene = json::parse(R"({
  "schema": "demo/2",
  "site": {"latitude_deg": 47.4, "name": "Zürich", "flat": true, "empty": null},
  "arrays": [{"vertices_m": [[0, 0, 0], [1, "east", 0]]}],
  "count": 3.5
})");

TEST(JsonReader, ErrorsNameTheFileAndTheFullPath) {
  const JsonReader root(kScene, "scene.json");
  auto arrays = root.member("arrays");
  ASSERT_TRUE(arrays);
  ASSERT_TRUE(arrays->array());
  const JsonReader point = arrays->element(0).member("vertices_m")->element(1);
  EXPECT_EQ(point.path(), "arrays[0].vertices_m[1]");
  EXPECT_EQ(errorOf(point.element(1).number()),
            "scene.json: arrays[0].vertices_m[1][1] must be a number, not \"east\"");
  EXPECT_EQ(errorOf(root.member("site")->number("latitude")),
            "scene.json: site.latitude is missing");
  EXPECT_EQ(errorOf(root.member("site")->numberIn("latitude_deg", 0, 45, "°")),
            "scene.json: site.latitude_deg 47.4° is outside [0, 45]");
  EXPECT_EQ(root.number("count").value(), 3.5);
  EXPECT_EQ(errorOf(root.text("count")), "scene.json: count must be a string, not 3.5");
}

TEST(JsonReader, TheRootIsTheDocument) {
  const json list = json::array({1, 2});
  const JsonReader root(list, "a.json");
  EXPECT_EQ(errorOf(root.member("x")), "a.json: the document must be an object, not [1,2]");
  EXPECT_EQ(root.name(), "the document");
}

TEST(JsonReader, AbsentAndNullAreOneForOptionalFields) {
  const JsonReader site = *JsonReader(kScene, "scene.json").member("site");
  EXPECT_TRUE(site.has("name"));
  EXPECT_FALSE(site.has("empty"));
  EXPECT_FALSE(site.has("nowhere"));
  EXPECT_EQ(site.optionalNumber("empty").value(), std::nullopt);
  EXPECT_EQ(site.optionalText("nowhere").value(), std::nullopt);
  EXPECT_EQ(site.optionalText("name").value(), "Zürich");
  EXPECT_EQ(site.optionalBoolean("flat").value(), true);
  EXPECT_EQ(errorOf(site.text("empty")), "scene.json: site.empty is missing");
  EXPECT_EQ(errorOf(site.optionalBoolean("name")),
            "scene.json: site.name must be true or false, not \"Zürich\"");
}

TEST(JsonReader, NumbersAreFiniteAndWithinTheirKind) {
  const json values{{"zero", 0}, {"minus", -2}, {"half", 0.5}, {"big", 1e300}};
  const JsonReader r(values, "v.json", "block");
  EXPECT_EQ(errorOf(r.positive("zero")), "v.json: block.zero must be positive, not 0");
  EXPECT_EQ(errorOf(r.nonNegative("minus")), "v.json: block.minus must not be negative, not -2");
  EXPECT_EQ(r.nonNegative("zero").value(), 0);
  EXPECT_EQ(errorOf(r.integer("half", 0, 10)),
            "v.json: block.half must be a whole number in [0, 10], not 0.5");
  EXPECT_EQ(errorOf(r.integer("big", 0, 10)),
            "v.json: block.big must be a whole number in [0, 10], not 1e+300");
  EXPECT_EQ(r.integer("minus", -5, 5).value(), -2);
  // JSON has no infinity, but a document built in code may hold one.
  const json infinite{{"x", std::numeric_limits<double>::infinity()}};
  EXPECT_EQ(errorOf(JsonReader(infinite, "i.json").number("x")), "i.json: x must be finite");
}

TEST(JsonReader, ObjectAndArrayMembersAreCheckedForTheirKind) {
  const JsonReader root(kScene, "scene.json");
  EXPECT_EQ(root.objectMember("site")->path(), "site");
  EXPECT_EQ(root.arrayMember("arrays")->size(), 1u);
  EXPECT_EQ(
      errorOf(root.objectMember("arrays")),
      "scene.json: arrays must be an object, not [{\"vertices_m\":[[0,0,0],[1,\"east\",0]]}]");
  EXPECT_EQ(errorOf(root.arrayMember("site")).substr(0, 37),
            "scene.json: site must be an array, no");
  EXPECT_EQ(errorOf(root.arrayMember("nowhere")), "scene.json: nowhere is missing");
  const JsonReader site = *root.objectMember("site");
  EXPECT_FALSE(site.optionalObject("empty").value());
  EXPECT_FALSE(site.optionalArray("nowhere").value());
  EXPECT_EQ(errorOf(site.optionalObject("flat")),
            "scene.json: site.flat must be an object, not true");
  EXPECT_EQ(errorOf(site.optionalArray("name")),
            "scene.json: site.name must be an array, not \"Zürich\"");
  JsonReader assigned;  // what a member's reader is assigned to
  EXPECT_TRUE(assigned.isNull());
  assigned = *root.objectMember("site");
  EXPECT_EQ(assigned.number("latitude_deg").value(), 47.4);
}

TEST(JsonReader, AWordIsOneOfItsList) {
  const json values{{"mode", "constant"}, {"fit", "spline"}};
  const JsonReader r(values, "w.json");
  EXPECT_EQ(r.word("mode", {"alpha_curve", "constant", "none"}).value(), "constant");
  EXPECT_EQ(errorOf(r.word("fit", {"cos", "biquadratic"})),
            "w.json: fit \"spline\" is not cos or biquadratic");
  EXPECT_EQ(errorOf(r.word("fit", {"a", "b", "c"})), "w.json: fit \"spline\" is not a, b or c");
  EXPECT_EQ(errorOf(r.word("none", {"a", "b"})), "w.json: none is missing (a or b)");
  EXPECT_EQ(r.optionalWord("none", {"a", "b"}).value(), std::nullopt);
}

TEST(JsonReader, OnlyKnownKeysAndTheClosestOneSuggested) {
  const JsonReader root(kScene, "scene.json");
  const JsonReader site = *root.member("site");
  EXPECT_TRUE(site.onlyKeys({"latitude_deg", "name", "flat", "empty"}));
  // A null member is still a key written, and a misspelt one.
  EXPECT_EQ(errorOf(site.onlyKeys({"latitude_deg", "name", "flat", "empty_m"})),
            "scene.json: site has an unknown key \"empty\" (did you mean \"empty_m\"?)");
  EXPECT_EQ(errorOf(root.onlyKeys({"schema", "site", "arrays"})),
            "scene.json: the document has an unknown key \"count\" (known: schema, site, arrays)");
  EXPECT_EQ(errorOf(root.member("arrays")->element(0).onlyKeys({"vertex_m"})),
            "scene.json: arrays[0] has an unknown key \"vertices_m\" (did you mean \"vertex_m\"?)");
  EXPECT_EQ(errorOf(root.member("count")->onlyKeys({"a"})),
            "scene.json: count must be an object, not 3.5");
}

TEST(JsonReader, SchemaIsTheExpectedOneOrAnAcceptedOlderOne) {
  const JsonReader root(kScene, "scene.json");
  EXPECT_EQ(root.schema("demo/2", "a demo").value(), "demo/2");
  EXPECT_EQ(root.schema("demo/3", "a demo", {"demo/2"}).value(), "demo/2");
  EXPECT_EQ(errorOf(root.schema("demo/3", "a demo")),
            "scene.json: schema \"demo/2\" is not supported (a demo's is \"demo/3\")");
  EXPECT_EQ(
      errorOf(root.schema("demo/4", "a demo", {"demo/3"})),
      "scene.json: schema \"demo/2\" is not supported (a demo's is \"demo/4\" or \"demo/3\")");
  const json bare = json::object();
  EXPECT_EQ(errorOf(JsonReader(bare, "b.json").schema("demo/3", "a demo")),
            "b.json: schema is missing (a demo's is \"demo/3\")");
}

}  // namespace
}  // namespace glarecam
