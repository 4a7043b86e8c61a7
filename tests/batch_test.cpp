// Catalogue batches (issue 17): `insitu batch` renders each entry as `insitu render` renders the
// entry's scene, bit for bit, whether the room is loaded for it or shared; a rerun skips entries
// whose outputs are there of the same inputs and renders those whose inputs changed; --index
// renders one entry; a killed batch leaves no output of the entry it was on; bad batches are
// refused with a one-line error naming the entry.
#include <gtest/gtest.h>

#include <signal.h>
#include <sys/wait.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fmt/format.h>
#include <functional>
#include <map>
#include <thread>

#include "cli_util.h"
#include "exr_pixels.h"
#include "scene_fixture.h"

namespace insitu {
namespace {

using test::exr_pixels;
using test::run_insitu;
using test::SceneFixture;
namespace fs = std::filesystem;

// The fixture's scene as the room, and entries that move the quad and name their outputs.
struct BatchFixture {
  SceneFixture fx;
  std::string scene;
  nlohmann::json entries = nlohmann::json::array();

  // room_box: the environment as an emitting box, whose room light and irradiance grids the
  // entries sharing the room share (light/room_cache.h).
  explicit BatchFixture(int spp = 8, bool room_box = false) {
    auto j = fx.scene;
    j["render"] = {{"integrator", "path"}, {"spp", spp}};
    j["local_scene"] = {{{"plane", {{"point", {0, 0, 0}}, {"normal", {0, 1, 0}}}}}};
    if (room_box)
      j["environment"] = {{"image", j["environment"]},
                          {"room_box", {{"min", {-3, 0, -4}}, {"max", {3, 3, 3}}, {"capture", {0.5, 1.0, -0.5}}}}};
    scene = fx.write(j);
    for (int i = 0; i < 3; ++i)
      entries.push_back({{"objects", {{{"mesh", "good_quad.obj"}, {"translate", {0.1 * i, 0.0, 0.0}}}}},
                         {"output", {{"image", fmt::format("out/e{}.exr", i)}}}});
  }
  std::string write_batch() const {
    return fx.dir.write("batch.json", nlohmann::json{{"scene", "scene.json"}, {"entries", entries}}.dump(2));
  }
  std::string out(int i) const { return fx.dir.file(fmt::format("out/e{}.exr", i)); }
  // Entry i rendered on its own by `insitu render` from its merged scene file, into `image`.
  test::CliRun render_alone(int i, const std::string& image) const {
    auto j = nlohmann::json::parse(test::slurp(scene));
    j.merge_patch(entries[std::size_t(i)]);
    j["output"]["image"] = image;
    return run_insitu(fx.dir, "render " + fx.dir.write(fmt::format("alone{}.json", i), j.dump()));
  }
};

// A room box: the shared room light and grids give the pixels of grids built for the entry alone.
TEST(Batch, EntriesSharingARoomBoxAreTheirScenesRenders) {
  BatchFixture b(4, true);
  const std::string batch = b.write_batch();
  auto r = run_insitu(b.fx.dir, "batch " + batch);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("(room shared)"), std::string::npos) << r.err;
  // Two entries against their own renders; under the sanitizers one (each render is 12 s there).
  for (int i : test::kUnderAsan ? std::vector<int>{1} : std::vector<int>{1, 2}) {
    r = b.render_alone(i, fmt::format("alone{}.exr", i));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    ASSERT_FALSE(exr_pixels(b.out(i)).empty());
    EXPECT_TRUE(exr_pixels(b.out(i)) == exr_pixels(b.fx.dir.file(fmt::format("alone{}.exr", i)))) << i;
  }
}

// The MTL file that an entry's OBJ names is an input too: editing it renders the entries again
// (all three read it), and the report lists it.
TEST(Batch, AnEditedMtlFileIsRenderedAgain) {
  BatchFixture b(2);
  const std::string batch = b.write_batch();
  auto r = run_insitu(b.fx.dir, "batch " + batch);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto report = nlohmann::json::parse(test::slurp(b.out(0) + ".report.json"));
  const auto files = report.at("batch").at("mesh_files").get<std::vector<std::string>>();
  EXPECT_TRUE(std::any_of(files.begin(), files.end(), [](const std::string& f) {
    return f.find("good_quad.mtl") != std::string::npos;
  })) << report["batch"].dump();
  r = run_insitu(b.fx.dir, "batch " + batch);
  EXPECT_NE(r.err.find("0 rendered, 3 done already"), std::string::npos) << r.err;
  // A different diffuse colour, same length of file or not: the bytes differ.
  std::string mtl = test::slurp(b.fx.dir.file("good_quad.mtl"));
  const auto kd = mtl.find("Kd");
  ASSERT_NE(kd, std::string::npos);
  mtl.replace(kd, mtl.find('\n', kd) - kd, "Kd 0.2 0.7 0.3");
  b.fx.dir.write("good_quad.mtl", mtl);
  r = run_insitu(b.fx.dir, "batch " + batch);
  EXPECT_NE(r.err.find("3 rendered, 0 done already"), std::string::npos) << r.err;
}

TEST(Batch, EachEntryIsTheRenderOfItsSceneAndReRunsSkipWhatIsDone) {
  BatchFixture b;
  const std::string batch = b.write_batch();
  auto r = run_insitu(b.fx.dir, "batch " + batch);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("(room shared)"), std::string::npos) << r.err;
  // Entry 2, rendered on its own from its merged scene file: the same pixels.
  ASSERT_EQ(b.render_alone(2, "alone.exr").exit_code, 0);
  ASSERT_FALSE(exr_pixels(b.out(2)).empty());
  EXPECT_TRUE(exr_pixels(b.out(2)) == exr_pixels(b.fx.dir.file("alone.exr")));
  EXPECT_FALSE(exr_pixels(b.out(1)) == exr_pixels(b.out(2)));
  // Again: nothing to do.
  const auto written = fs::last_write_time(b.out(0));
  r = run_insitu(b.fx.dir, "batch " + batch);
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_NE(r.err.find("0 rendered, 3 done already"), std::string::npos) << r.err;
  EXPECT_EQ(fs::last_write_time(b.out(0)), written);
  // Entry 1 changed: only it is rendered again.
  b.entries[1]["objects"][0]["translate"] = {0.3, 0.0, 0.0};
  b.write_batch();
  r = run_insitu(b.fx.dir, "batch " + batch);
  EXPECT_NE(r.err.find("1 rendered, 2 done already"), std::string::npos) << r.err;
  r = run_insitu(b.fx.dir, "batch " + batch + " --force --index 0");
  EXPECT_NE(r.err.find("1 rendered, 0 done already"), std::string::npos) << r.err;
  EXPECT_NE(fs::last_write_time(b.out(0)), written);
}

TEST(Batch, IndexRendersOneEntryAndCountCountsThem) {
  BatchFixture b;
  const std::string batch = b.write_batch();
  auto r = run_insitu(b.fx.dir, "batch " + batch + " --count");
  EXPECT_EQ(r.out, "3\n");
  r = run_insitu(b.fx.dir, "batch " + batch + " --index 1");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out, b.out(1) + "\n");
  EXPECT_FALSE(fs::exists(b.out(0)));
  EXPECT_FALSE(fs::exists(b.out(2)));
  EXPECT_TRUE(fs::exists(b.out(1) + ".report.json"));
  test::expect_one_line_error(run_insitu(b.fx.dir, "batch " + batch + " --index 3"), "has entries 0 to 2");
}

// --per-task K: task I renders entries I·K … I·K + K − 1 (the last task fewer), sharing the room.
TEST(Batch, PerTaskGroupsEntries) {
  BatchFixture b;
  const std::string batch = b.write_batch();
  auto r = run_insitu(b.fx.dir, "batch " + batch + " --count --per-task 2");
  EXPECT_EQ(r.out, "2\n");
  r = run_insitu(b.fx.dir, "batch " + batch + " --index 0 --per-task 2");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out, b.out(0) + "\n" + b.out(1) + "\n");
  EXPECT_NE(r.err.find("(room shared)"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(b.out(2)));
  r = run_insitu(b.fx.dir, "batch " + batch + " --index 1 --per-task 2");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out, b.out(2) + "\n");
  test::expect_one_line_error(run_insitu(b.fx.dir, "batch " + batch + " --index 2 --per-task 2"),
                              "tasks 0 to 1 of 2 entries");
}

// SIGKILL in the middle of an entry's render (once its progress shows it under way): none of its
// outputs has a final name.
TEST(Batch, AKilledTaskLeavesNoOutput) {
  // Progress shows at the end of the first of 8 passes: the kill lands in the other 7/8 of a
  // render of about 30 s (release) or a few tens of seconds (sanitizers, 16 times fewer samples).
  BatchFixture b(test::kUnderAsan ? 1 << 12 : 1 << 16);
  b.entries.erase(b.entries.begin() + 1, b.entries.end());
  const std::string batch = b.write_batch(), err = b.fx.dir.file("batch.err");
  const std::string cmd = std::string(INSITU_BINARY) + " batch " + batch + " > /dev/null 2> " + err + " & echo $!";
  FILE* p = popen(cmd.c_str(), "r");
  int pid = 0;
  ASSERT_EQ(fscanf(p, "%d", &pid), 1);
  pclose(p);
  for (int i = 0; i < 3000 && test::slurp(err).find("entry 0: ") == std::string::npos; ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  EXPECT_NE(test::slurp(err).find("entry 0: "), std::string::npos) << "no progress within 300 s";
  kill(pid, SIGKILL);
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  EXPECT_FALSE(fs::exists(b.out(0)));
  EXPECT_FALSE(fs::exists(b.out(0) + ".report.json"));
  EXPECT_FALSE(fs::exists(b.fx.dir.file("out/e0.layers.exr")));
}

TEST(Batch, BadBatchesAreRefusedNamingTheEntry) {
  BatchFixture b;
  auto refused = [&](const nlohmann::json& doc, const std::string& says) {
    const std::string path = b.fx.dir.write("bad.json", doc.dump());
    test::expect_one_line_error(run_insitu(b.fx.dir, "batch " + path), says);
  };
  refused({{"scene", "scene.json"}, {"entries", nlohmann::json::array()}}, "non-empty array");
  refused({{"scene", "scene.json"}, {"entries", b.entries}, {"extra", 1}}, "$.extra");
  refused({{"entries", b.entries}}, "$.scene");
  refused({{"scene", "none.json"}, {"entries", b.entries}}, "none.json");
  auto twice = b.entries;
  twice[2]["output"]["image"] = "out/e0.exr";
  refused({{"scene", "scene.json"}, {"entries", twice}}, "entry 2");
  auto unnamed = b.entries;
  unnamed[1].erase("output");
  refused({{"scene", "scene.json"}, {"entries", unnamed}}, "entries[1]: every entry names its own output.image");
  auto missing = b.entries;
  missing[2]["objects"][0]["mesh"] = "no_such.obj";
  refused({{"scene", "scene.json"}, {"entries", missing}}, "entries[2]");
  EXPECT_FALSE(fs::exists(b.out(0)));
}

// The whole batch is checked before its first render (issue 46): an entry's output on the batch
// file, on the room's scene file or on another entry's photo, and two entries writing one file
// under two spellings (a layers path that is another entry's image, a symlink), each exit 0 and
// an overwritten input before. Refused with one line; nothing rendered, nothing changed.
TEST(Batch, NoEntryWritesOverAnInputOrAnotherEntrysOutput) {
  BatchFixture b;
  const fs::path dir = b.fx.dir.path();
  fs::copy_file(dir / "photo.png", dir / "photo1.png");
  fs::copy_file(dir / "scene.json", dir / "room.png.report.json");
  fs::create_directories(dir / "out");
  b.fx.dir.write("out/e0.exr", "a previous run's image");
  fs::create_symlink(dir / "out/e0.exr", dir / "out/link.exr");
  // A textured mesh: its MTL and texture are known only by reading the OBJ (issue 46: an entry's
  // output over another entry's texture was caught only when that entry loaded).
  b.fx.dir.write("tex.obj",
                 "mtllib tex.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nusemtl t\nf 1/1 2/2 3/3\n");
  b.fx.dir.write("tex.mtl", "newmtl t\nKd 1 1 1\nmap_Kd tex.png\n");
  fs::copy_file(dir / "photo.png", dir / "tex.png");
  struct Case {
    std::string batch_name, room, says;
    std::function<void(nlohmann::json&)> edit;
  };
  const std::vector<Case> cases = {
      {"e.png.report.json", "scene.json", "the batch file", [](auto& e) { e[0]["output"]["image"] = "e.png"; }},
      {"batch.json", "room.png.report.json", "the room's scene file",
       [](auto& e) { e[1]["output"]["image"] = "room.png"; }},
      {"batch.json", "scene.json", "the photo of entry 1",
       [](auto& e) {
         e[1]["photo"] = "photo1.png";
         e[0]["output"]["image"] = "photo1.png";
       }},
      {"batch.json", "scene.json", "the output image of entry 1",
       [](auto& e) { e[0]["output"]["layers"] = "out/e1.exr"; }},
      {"batch.json", "scene.json", "the output image of entry 0",
       [](auto& e) { e[2]["output"]["image"] = "out/link.exr"; }},
      {"batch.json", "scene.json", "tex.obj of entry 2",
       [](auto& e) {
         e[2]["objects"][0]["mesh"] = "tex.obj";
         e[0]["output"]["image"] = "tex.png";
       }},
  };
  for (const Case& c : cases) {
    nlohmann::json entries = b.entries;
    c.edit(entries);
    const std::string batch =
        b.fx.dir.write(c.batch_name, nlohmann::json{{"scene", c.room}, {"entries", entries}}.dump(2));
    std::map<std::string, std::string> before;
    for (const auto& e : fs::directory_iterator(dir))
      if (e.is_regular_file() && e.path().extension() != ".txt")  // not run_insitu's stdout.txt, stderr.txt
        before[e.path().string()] = test::slurp(e.path().string());
    test::expect_one_line_error(run_insitu(b.fx.dir, "batch " + batch), c.says);
    for (const auto& [file, text] : before) EXPECT_EQ(test::slurp(file), text) << c.says << ": " << file << " changed";
    EXPECT_EQ(test::slurp(b.fx.dir.file("out/e0.exr")), "a previous run's image") << c.says;
    EXPECT_FALSE(fs::exists(b.out(1))) << c.says << ": an entry was rendered";
    fs::remove(batch);
  }
}

// docs/farm.md's batch example is a batch insitu reads (issue 46: it used "rotate_deg", which the
// parser refuses): its JSON block, with the fixture's room and quad as its meshes.
TEST(Batch, TheFarmPagesExampleIsABatchInsituReads) {
  BatchFixture b;
  const std::string doc = test::slurp(test::source_dir() + "/docs/farm.md");
  const std::size_t section = doc.find("## Batches"), begin = doc.find("```json\n", section),
                    end = doc.find("```\n", begin + 8);
  ASSERT_NE(section, std::string::npos);
  ASSERT_NE(end, std::string::npos);
  auto batch = nlohmann::json::parse(doc.substr(begin + 8, end - begin - 8));
  batch["scene"] = "scene.json";
  for (const char* mesh : {"sofa.obj", "table.obj"})
    fs::copy_file(b.fx.dir.path() / "good_quad.obj", b.fx.dir.path() / mesh);
  const test::CliRun r = run_insitu(b.fx.dir, "batch " + b.fx.dir.write("farm.json", batch.dump()) + " --count");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out, fmt::format("{}\n", batch["entries"].size()));
}

}  // namespace
}  // namespace insitu
