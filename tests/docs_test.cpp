// The pages of docs/ and the README against the code: the reference tables are what the code
// prints, every file of the source they name exists, and the architecture map names every file.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>

#include "scene/mode_tables.h"
#include "test_util.h"

namespace insitu {
namespace {

namespace fs = std::filesystem;

std::string read_page(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// docs/cli.md holds, between its markers, exactly what `insitu modes` prints (scene/mode_tables.h):
// an integrator, irradiance mode or tone map added to the code, or a default changed, fails here
// until the page is regenerated.
TEST(Docs, TheCliPageHoldsWhatInsituModesPrints) {
  const std::string page = read_page(fs::path(test::source_dir()) / "docs/cli.md");
  const std::string begin = "<!-- insitu modes: begin -->\n", end = "<!-- insitu modes: end -->";
  const auto a = page.find(begin), b = page.find(end);
  ASSERT_NE(a, std::string::npos) << "docs/cli.md has no " << begin;
  ASSERT_NE(b, std::string::npos) << "docs/cli.md has no " << end;
  EXPECT_EQ(page.substr(a + begin.size(), b - a - begin.size()), mode_tables())
      << "regenerate it: build/insitu modes, pasted between the markers";
}

// A path of this repository that a page names (src/…, tests/…, tools/…, scripts/…, bench/…), in
// braces too (src/light/irradiance.{h,cpp}), exists: a file moved to its stage is followed by the
// pages. Left out: patterns (tools/cmd_*.cpp, tests/<name>_test.cpp), other projects' paths
// (pbrt-v4's src/pbrt/, fSpy's src/gui/), placeholders in capitals (tests/data/validation/SCENE)
// and what a command writes (…/out/…).
TEST(Docs, EveryPathOfTheSourceTheyNameExists) {
  const fs::path root = test::source_dir();
  std::vector<fs::path> pages = {root / "README.md"};
  for (const auto& e : fs::directory_iterator(root / "docs"))
    if (e.path().extension() == ".md") pages.push_back(e.path());
  const std::regex path_re(R"((?:^|[^\w./-])((?:src|tests|tools|scripts|bench)/[\w./{},*<>-]+))");
  const std::regex braces_re(R"((.*)\{([^}]*)\}(.*))");
  const std::regex placeholder_re(R"((^|/)[A-Z][A-Z_]+(/|\.|$))");
  int checked = 0;
  for (const fs::path& page : pages) {
    const std::string text = read_page(page);
    for (std::sregex_iterator it(text.begin(), text.end(), path_re), none; it != none; ++it) {
      std::string p = (*it)[1];
      while (!p.empty() && std::string(".,;:").find(p.back()) != std::string::npos) p.pop_back();
      if (p.find_first_of("*<>") != std::string::npos || p.rfind("src/pbrt/", 0) == 0 || p.rfind("src/gui/", 0) == 0 ||
          p.find("/out/") != std::string::npos || std::regex_search(p, placeholder_re))
        continue;
      std::vector<std::string> candidates = {p};
      std::smatch m;
      if (std::regex_match(p, m, braces_re)) {
        candidates.clear();
        std::stringstream alternatives(m[2].str());
        for (std::string alt; std::getline(alternatives, alt, ',');)
          candidates.push_back(m[1].str() + alt + m[3].str());
      }
      for (const std::string& c : candidates) {
        EXPECT_TRUE(fs::exists(root / c)) << page.filename() << " names " << c << ", which does not exist";
        ++checked;
      }
    }
  }
  EXPECT_GT(checked, 100);
}

// docs/architecture.md's map names every file of src/ (by its stem): a file added to a stage, or
// moved to another, is found there.
TEST(Docs, TheArchitectureMapNamesEverySourceFile) {
  const fs::path root = test::source_dir();
  const std::string map = read_page(root / "docs/architecture.md");
  int checked = 0;
  for (const auto& stage : fs::directory_iterator(root / "src")) {
    if (!stage.is_directory()) continue;
    for (const auto& e : fs::directory_iterator(stage.path())) {
      const std::string ext = e.path().extension().string();
      if (ext != ".h" && ext != ".cpp" && ext != ".py") continue;
      const std::string stem = e.path().stem().string();
      const std::regex word("(^|[^A-Za-z0-9_])" + stem + "($|[^A-Za-z0-9_])");
      EXPECT_TRUE(std::regex_search(map, word))
          << "docs/architecture.md does not name " << e.path().lexically_relative(root);
      ++checked;
    }
  }
  EXPECT_GT(checked, 100);
}

}  // namespace
}  // namespace insitu
