// Control points files (calib/control_points.h).
#include <gtest/gtest.h>

#include <ceres/gradient_checker.h>

#include <random>

#include "calib/calibration.h"
#include "core/error.h"
#include "calib/f_test.h"
#include "calib/reprojection_cost.h"
#include "calib/view_correlation.h"
#include "test_util.h"

namespace insitu {
namespace {

TEST(ControlPoints, JsonCsvAndErrors) {
  test::TempDir dir;
  dir.write("p.json", R"([{"uv": [1, 2], "xyz": [3, 4, 5], "name": "corner"}, {"uv": [6, 7], "xyz": [8, 9, 10]}])");
  const auto pj = read_control_points(dir.file("p.json"), false, 100);
  ASSERT_EQ(pj.size(), 2u);
  EXPECT_EQ(pj[0].name, "corner");
  EXPECT_EQ(pj[1].name, "#2");
  EXPECT_EQ(pj[1].p_world, Vec3d(8, 9, 10));
  dir.write("p.csv", "u,v,x,y,z,name\n1, 2, 3, 4, 5, a\n# comment\n6,7,8,9,10\n");
  const auto pc = read_control_points(dir.file("p.csv"), true, 100);  // bottom-left origin
  ASSERT_EQ(pc.size(), 2u);
  EXPECT_EQ(pc[0].uv_px, Vec2d(1, 98));
  EXPECT_EQ(pc[0].name, "a");
  dir.write("bad.csv", "1,2,3,4,5\n1,2,x,4,5\n");
  try {
    read_control_points(dir.file("bad.csv"), false, 100);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.where(), dir.file("bad.csv") + ":2");
  }
  dir.write("bad.json", R"([{"uv": [1, 2], "xyz": [3, 4]}])");
  try {
    read_control_points(dir.file("bad.json"), false, 100);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.where(), dir.file("bad.json") + ":$[0].xyz");
  }
}

}  // namespace
}  // namespace insitu
