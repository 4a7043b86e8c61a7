// insitu studio's references of known albedo (issue 13 in the points panel): a polygon clicked on
// the photo saved to the scene file's "references", read back by the library's own parser; a bad
// corner refused where it is, nothing written; a stale page refused.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/error.h"
#include "scene/scene_file.h"
#include "studio/scene_edit.h"
#include "studio_fixture.h"

namespace insitu {
namespace {

using test::get_json;
using test::post;
using test::StudioFixture;
using test::TempDir;
using test::text_of;
namespace fs = std::filesystem;

const json kSheet = {{100, 400}, {180, 400}, {180, 440}, {100, 440}};

TEST(StudioReferences, ADrawnSheetIsSavedToTheSceneFileAndRemoved) {
  TempDir dir;
  StudioFixture studio(dir);
  const fs::path scene = studio.folder() / "scene.json";
  const json before = get_json(studio.client(), "/api/references");
  EXPECT_TRUE(before["references"].empty());
  const auto [code, reply] =
      post(studio.client(), "/api/references",
           {{"version", before["version"]}, {"op", "add"}, {"polygon_px", kSheet}, {"albedo", 0.8}});
  ASSERT_EQ(code, 200) << reply.dump();
  const SceneSpec spec = parse_scene_file(scene.string());
  ASSERT_EQ(spec.references.size(), 1u);
  EXPECT_EQ(spec.references[0].albedo, 0.8);
  ASSERT_EQ(spec.references[0].polygon_px.size(), 4u);
  EXPECT_EQ(spec.references[0].polygon_px[2], Vec2d(180, 440));
  const json after = get_json(studio.client(), "/api/references");
  ASSERT_EQ(after["references"].size(), 1u);
  EXPECT_EQ(after["version"], reply["version"]);
  // A second tab still at the first version: refused, the file as the first left it.
  const std::string text = text_of(scene);
  const auto [stale, stale_reply] =
      post(studio.client(), "/api/references", {{"version", before["version"]}, {"op", "remove"}, {"index", 0}});
  EXPECT_EQ(stale, 409) << stale_reply.dump();
  EXPECT_EQ(text_of(scene), text);
  const auto [removed, removed_reply] =
      post(studio.client(), "/api/references", {{"version", after["version"]}, {"op", "remove"}, {"index", 0}});
  ASSERT_EQ(removed, 200) << removed_reply.dump();
  EXPECT_FALSE(json::parse(text_of(scene)).contains("references"));
}

// The CLI's refusals, at the same places: a corner outside the photo (640 x 480), too few corners,
// an albedo out of (0, 1]; the file untouched each time.
TEST(StudioReferences, ABadReferenceIsRefusedWhereItIsAndNothingIsWritten) {
  TempDir dir;
  StudioFixture studio(dir);
  const fs::path scene = studio.folder() / "scene.json";
  const std::string text = text_of(scene);
  const std::string version = get_json(studio.client(), "/api/references")["version"];
  const json outside = {{100, 400}, {700, 400}, {180, 440}};
  const json two = {{100, 400}, {180, 400}};
  const std::vector<std::pair<json, std::string>> cases = {
      {{{"polygon_px", outside}, {"albedo", 0.8}}, "scene.json:$.references[0].polygon_px[1]"},
      {{{"polygon_px", two}, {"albedo", 0.8}}, "scene.json:$.references[0].polygon_px"},
      {{{"polygon_px", kSheet}, {"albedo", 1.5}}, "scene.json:$.references[0].albedo"},
      {{{"polygon_px", kSheet}}, "scene.json:$.references[0]"},
  };
  for (const auto& [ref, where] : cases) {
    json body = ref;
    body["version"] = version;
    body["op"] = "add";
    const auto [code, reply] = post(studio.client(), "/api/references", body);
    EXPECT_EQ(code, 400) << reply.dump();
    EXPECT_NE(reply["where"].get<std::string>().find(where), std::string::npos) << where << ": " << reply.dump();
    EXPECT_EQ(text_of(scene), text);
  }
  const auto [code, reply] =
      post(studio.client(), "/api/references", {{"version", version}, {"op", "remove"}, {"index", 0}});
  EXPECT_EQ(code, 400) << reply.dump();
  EXPECT_EQ(reply["where"], "scene.json:$.references");
}

// The edits on their own, on text: order and other keys kept; the array goes with its last item.
TEST(StudioReferences, SceneEditsKeepEverythingElse) {
  const std::string text = R"({"photo": "p.jpg", "render": {"spp": 4}})";
  const std::string added = add_reference(text, "s.json", {{"polygon_px", kSheet}, {"albedo", 0.18}});
  EXPECT_LT(added.find("\"photo\""), added.find("\"render\""));
  EXPECT_LT(added.find("\"render\""), added.find("\"references\""));
  EXPECT_EQ(json::parse(added)["references"][0]["albedo"], 0.18);
  EXPECT_EQ(json::parse(remove_reference(added, "s.json", 0)), json::parse(text));
  EXPECT_THROW(remove_reference(text, "s.json", 0), InputError);
  EXPECT_THROW(add_reference(R"({"references": 3})", "s.json", {{"polygon_px", kSheet}, {"albedo", 0.5}}), InputError);
}

}  // namespace
}  // namespace insitu
