// The pipeline from a scene file to its layers and composite (scene/pipeline.h), on the demo and fixtures.
#include <gtest/gtest.h>

#include <tbb/global_control.h>

#include "output/composite.h"
#include "scene/pipeline.h"
#include "scene_fixture.h"

namespace insitu {
namespace {

using test::SceneFixture;

TEST(Demo, RendersWithObjectsWhereTheCameraSeesThem) {
  const std::string path = test::source_dir() + "/scenes/demo/scene.json";
  SceneSpec spec = parse_scene_file(path);
  spec.render.spp = test::kUnderAsan ? 2 : 4;  // the render was half of this test's 93 s under ASan
  // Without the change grid (path.cpp), which darkens every real pixel of the room a little, so
  // that the render leaves pixels alone for the composite to keep.
  spec.render.block.value["change_grid"] = 0;
  spec.output = {};
  const LoadedScene s = load_scene(spec);
  const RenderResult r = render_scene(s);
  EXPECT_EQ(r.layers.nonfinite_samples, 0u);
  // The ball's centre and the table top's centre, placed as in scene.json, are covered; a point
  // of the wall high above them is not.
  for (const Vec3d& p : {Vec3d(0.95, 0.2, -0.2), Vec3d(-0.2, 0.74, -1.2)}) {
    const Vec2d uv = s.camera.project(p);
    EXPECT_EQ(*r.layers.alpha.at(int(uv.x()), int(uv.y())), 1.0f) << p.transpose();
  }
  const Vec2d wall = s.camera.project(Vec3d(0.0, 2.3, -3.0));
  EXPECT_EQ(*r.layers.alpha.at(int(wall.x()), int(wall.y())), 0.0f);
  // Wherever the render left the pixel alone (no object, no change on the catcher) the encoded
  // composite is the photo as stored: the walls, and the floor far from the objects.
  const Image touched = touched_mask(r.layers);
  std::size_t untouched = 0;
  for (int y = 0; y < s.camera.height; ++y)
    for (int x = 0; x < s.camera.width; ++x)
      if (*touched.at(x, y) == 0.0f) {
        ++untouched;
        for (int k = 0; k < 3; ++k) ASSERT_EQ(r.composite_encoded.at(x, y)[k], s.photo.stored.at(x, y)[k]);
      }
  // Those are the pixels whose surface no sample connected to an object. Half the walls' reflection
  // samples go toward the objects (path.cpp, "Toward the objects"), so most real pixels carry their
  // small true change; 80 000 of 307 200 stay untouched at 4 spp (the window's, and those whose
  // few samples all missed).
  EXPECT_GT(untouched, std::size_t(s.camera.width) * s.camera.height / 5);
  // The floor right under the ball is in its shadow: darker with the objects than without.
  const Vec2d below = s.camera.project(Vec3d(0.95, 0.0, -0.2) + Vec3d(0.0, 0.0, 0.25));
  const int bx = int(below.x()), by = int(below.y());
  EXPECT_LT(luminance(r.layers.with_objects.rgb(bx, by)), luminance(r.layers.without_objects.rgb(bx, by)));
}

// The demo's generator used eye (1.7, 1.45, 2.5), look (−0.2, 0.45, −1.2), hfov 62°
// (tools/make_demo.cpp); its points.json carries ~0.7 px of click noise per axis. The calibrated
// camera must agree within 4 reported standard deviations.
TEST(Demo, CalibratedCameraAgreesWithTheGeneratorsCamera) {
  const SceneSpec spec = parse_scene_file(test::source_dir() + "/scenes/demo/scene.json");
  ASSERT_EQ(spec.camera.kind, CameraSpec::Kind::Points);
  const LoadedScene s = load_scene(spec);
  ASSERT_TRUE(s.calibration.has_value());
  const CalibrationResult& c = *s.calibration;
  ASSERT_TRUE(c.sigma.known);
  EXPECT_NEAR(s.camera.hfov_deg(), 62.0, 4 * c.sigma.hfov_deg);
  const Vec3d eye_true(1.7, 1.45, 2.5);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(s.camera.eye_world()[k], eye_true[k], 4 * c.sigma.eye_world[k]) << k;
  const Vec3d fwd_true = (Vec3d(-0.2, 0.45, -1.2) - eye_true).normalized();
  EXPECT_LT(rad_to_deg(std::acos(std::min(1.0, fwd_true.dot(s.camera.forward_world())))),
            4 * c.sigma.view_direction_deg);
  EXPECT_LT(c.rms_px, 1.5);
}

TEST(Render, BitIdenticalForAnyNumberOfThreads) {
  const std::string path = test::source_dir() + "/scenes/demo/scene.json";
  SceneSpec spec = parse_scene_file(path);
  spec.render.spp = test::kUnderAsan ? 1 : 3;  // the single-threaded render is a minute under ASan
  const LoadedScene s = load_scene(spec);
  RenderResult one;
  {
    tbb::global_control c(tbb::global_control::max_allowed_parallelism, 1);
    one = render_scene(s);
  }
  const RenderResult many = render_scene(s);
  EXPECT_EQ(one.layers.objects.data, many.layers.objects.data);
  EXPECT_EQ(one.layers.alpha.data, many.layers.alpha.data);
}

}  // namespace
}  // namespace insitu
