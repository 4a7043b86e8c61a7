// The house's layers (docs/architecture.md): every #include of src/ points down
// the stage order, and the scene file's spec types reach nothing of the render side, even
// transitively. The link targets enforce the same for symbols (CMakeLists.txt); this test catches
// a header-only dependency, which linking cannot see.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <string>
#include <vector>

namespace insitu {
namespace {

namespace fs = std::filesystem;
const fs::path kRoot = INSITU_SOURCE_DIR;

// Each stage and the stages it may include (itself included).
const std::map<std::string, std::set<std::string>> kAllowed = {
    {"core", {"core"}},
    {"calib", {"core", "calib"}},
    {"light", {"core", "light"}},
    {"render", {"core", "light", "render"}},
    {"integrators", {"core", "light", "render", "integrators"}},
    {"relight", {"core", "light", "render", "relight"}},
    {"output", {"core", "light", "render", "output"}},
    {"scene", {"core", "calib", "light", "render", "integrators", "relight", "output", "scene"}},
    {"interop", {"core", "calib", "light", "render", "integrators", "relight", "output", "scene", "interop"}},
    {"api", {"core", "calib", "light", "render", "integrators", "relight", "output", "scene", "interop", "api"}},
    {"studio", {"core", "calib", "light", "render", "integrators", "relight", "output", "scene", "interop", "studio"}},
};

// The quoted includes of a file, as written ("core/math.h").
std::vector<std::string> includes_of(const fs::path& file) {
  std::ifstream in(file);
  const std::regex include_re(R"re(^\s*#\s*include\s+"([^"]+)")re");
  std::vector<std::string> out;
  std::smatch m;
  for (std::string line; std::getline(in, line);)
    if (std::regex_search(line, m, include_re)) out.push_back(m[1]);
  return out;
}

std::string stage_of_include(const std::string& include) { return include.substr(0, include.find('/')); }

fs::path header_path(const std::string& include) { return kRoot / "src" / include; }

std::vector<std::pair<std::string, fs::path>> stage_files() {
  std::vector<std::pair<std::string, fs::path>> files;
  for (const auto& [stage, allowed] : kAllowed) {
    const fs::path dir = kRoot / "src" / stage;
    for (const auto& e : fs::directory_iterator(dir))
      if (e.path().extension() == ".h" || e.path().extension() == ".cpp") files.emplace_back(stage, e.path());
  }
  return files;
}

TEST(Architecture, EveryStageDirectoryExists) {
  for (const auto& [stage, allowed] : kAllowed) EXPECT_TRUE(fs::is_directory(kRoot / "src" / stage)) << stage;
}

TEST(Architecture, IncludesPointDownTheStages) {
  const auto files = stage_files();
  ASSERT_GT(files.size(), 40u);
  for (const auto& [stage, file] : files)
    for (const std::string& inc : includes_of(file)) {
      const std::string to = stage_of_include(inc);
      ASSERT_TRUE(kAllowed.count(to)) << file << ": #include \"" << inc << "\" names no stage (write \"stage/file.h\")";
      EXPECT_TRUE(kAllowed.at(stage).count(to)) << file << " (" << stage << ") includes " << inc << " (" << to << ")";
      EXPECT_TRUE(fs::is_regular_file(header_path(inc))) << file << ": " << inc;
    }
}

// spec.h, closed over its includes: core, the light's environment spec and the output settings.
TEST(Architecture, SpecTypesIncludeNothingOfTheRenderSide) {
  std::set<std::string> seen;
  std::vector<std::string> todo = {"scene/spec.h"};
  while (!todo.empty()) {
    const std::string inc = todo.back();
    todo.pop_back();
    if (!seen.insert(inc).second) continue;
    for (const std::string& next : includes_of(header_path(inc))) todo.push_back(next);
  }
  EXPECT_GT(seen.size(), 3u);
  for (const std::string& inc : seen) {
    const std::string stage = stage_of_include(inc);
    EXPECT_TRUE(stage != "render" && stage != "integrators" && stage != "relight" && stage != "calib")
        << "scene/spec.h reaches " << inc;
    EXPECT_TRUE(inc != "scene/scene_file.h" && inc != "scene/pipeline.h") << "scene/spec.h reaches " << inc;
  }
}

// Every quoted include anywhere (the tests, the fuzz targets, the benchmarks, the CLI) names a
// file that exists beside it, or under src/ or tools/: a header moved to its stage
// is followed everywhere, including the targets that only the sanitizer leg builds.
TEST(Architecture, EveryQuotedIncludeExists) {
  int checked = 0;
  for (const char* dir : {"tests", "tests/fuzz", "bench", "tools"})
    for (const auto& e : fs::directory_iterator(kRoot / dir)) {
      if (e.path().extension() != ".h" && e.path().extension() != ".cpp") continue;
      for (const std::string& inc : includes_of(e.path())) {
        const bool found = fs::is_regular_file(e.path().parent_path() / inc) ||
                           fs::is_regular_file(kRoot / "src" / inc) || fs::is_regular_file(kRoot / "tools" / inc);
        EXPECT_TRUE(found) << e.path() << ": #include \"" << inc << "\" is nowhere";
        ++checked;
      }
    }
  EXPECT_GT(checked, 100);
}

// The checker itself: a file that includes upward is caught.
TEST(Architecture, TheCheckCanFail) {
  EXPECT_FALSE(kAllowed.at("calib").count(stage_of_include("render/embree_scene.h")));
  EXPECT_FALSE(kAllowed.at("light").count(stage_of_include("scene/spec.h")));
  const fs::path tmp = fs::temp_directory_path() / "insitu_architecture_probe.h";
  std::ofstream(tmp) << "#pragma once\n  #include \"render/render.h\"\n#include <vector>\n";
  EXPECT_EQ(includes_of(tmp), std::vector<std::string>{"render/render.h"});
  fs::remove(tmp);
}

}  // namespace
}  // namespace insitu
