#include <gtest/gtest.h>

#include <cstdio>
#include <fmt/format.h>
#include <set>
#include <sstream>

#include "progress.h"

namespace insitu {
namespace {

// The line never wraps: at most columns − 1 characters, whatever the detail; the bar is dropped
// before the figures are.
TEST(Progress, LineFitsTheTerminal) {
  const std::string detail = "126/144 spp, noise 3.9%";
  for (int columns : {20, 40, 60, 80, 200}) {
    const std::string line = progress_line("render", 0.875, 5.3, detail, columns);
    EXPECT_LE(int(line.size()), columns - 1) << line;
  }
  const std::string at80 = progress_line("render", 0.875, 5.3, detail, 80);
  EXPECT_NE(at80.find('#'), std::string::npos) << at80;
  EXPECT_NE(at80.find(detail), std::string::npos) << at80;
  const std::string at50 = progress_line("render", 0.875, 5.3, detail, 50);
  EXPECT_NE(at50.find(" 87%"), std::string::npos) << at50;
}

// Not a terminal: one line per milestone that reaches a new tenth, each with its figures; none
// empty, none repeated, and the 100% line carries the last pass's figures.
TEST(Progress, PlainLinesCarryEachPassAndNeverRepeat) {
  std::FILE* f = std::tmpfile();
  ASSERT_NE(f, nullptr);
  {
    Progress p("render", Progress::Sink{f, false, 80, 0.0});
    p.update(0.0);
    const int passes = 8, spp = 144;
    std::string detail;
    for (int pass = 0; pass < passes; ++pass) {
      for (int tile = 1; tile <= 20; ++tile) p.update((pass + tile / 20.0) / passes, detail);  // mid-pass, old figures
      detail = fmt::format("{}/{} spp, noise {:.1f}%", spp * (pass + 1) / passes, spp, 10.0 / (pass + 1));
      p.update(double(pass + 1) / passes, detail, true);
    }
  }
  std::rewind(f);
  std::string text;
  for (int c; (c = std::fgetc(f)) != EOF;) text += char(c);
  std::fclose(f);
  std::istringstream in(text);
  std::vector<std::string> lines;
  std::set<std::string> figures;
  for (std::string line; std::getline(in, line);) {
    lines.push_back(line);
    ASSERT_NE(line.find(" spp, noise "), std::string::npos) << line;
    EXPECT_TRUE(figures.insert(line.substr(line.find(") ") + 2)).second) << "repeated: " << line;
  }
  ASSERT_EQ(lines.size(), 8u) << text;  // 8 passes, each ending in a new tenth
  EXPECT_EQ(lines.back().rfind("render: 100% ", 0), 0u) << lines.back();
  EXPECT_NE(lines.back().find("144/144 spp, noise 1.2%"), std::string::npos) << lines.back();
}

}  // namespace
}  // namespace insitu
