#include <gtest/gtest.h>

#include "pipeline.h"
#include "scene_fixture.h"

namespace insitu {
namespace {

// The camera-space z at which the ray through pixel position uv meets the floor y = 0 inside
// [box_min, box_max] (x and z), or nothing.
std::optional<double> floor_z(const Camera& cam, const Vec2d& uv, double x_lo, double x_hi, double z_lo, double z_hi) {
  const Ray r = cam.ray(uv);
  if (!(r.dir.y() < 0)) return std::nullopt;
  const Vec3d o = r.origin.cast<double>(), d = r.dir.cast<double>();
  const Vec3d p = o + (-o.y() / d.y()) * d;
  if (p.x() < x_lo || p.x() > x_hi || p.z() < z_lo || p.z() > z_hi) return std::nullopt;
  return (cam.R_cam_from_world * p + cam.t_cam_from_world).z();
}

// depth.Z is camera-space z, as Cycles and Nuke read it: in every pixel whose four corners all
// see the floor, it lies between the corners' z (z is monotonic across a pixel of a plane);
// where no corner sees anything it is the documented no-hit value. With a room box the floor ends
// at the walls: beyond them is no hit, never a distance of 10⁷.
TEST(Render, DepthIsCameraSpaceZAndNoHitIsDocumented) {
  test::SceneFixture fx;
  for (const bool box : {false, true}) {
    auto j = fx.scene;
    j["camera"] = {{"eye", {0.5, 1.0, 1.5}}, {"look", {0.5, 0.8, -0.5}}, {"hfov_deg", 60}};
    j["render"] = {{"integrator", "path"}, {"spp", 4}};
    j["objects"] = nlohmann::json::array();
    j["local_scene"] = {{{"plane", {{"point", {0, 0, 0}}, {"normal", {0, 1, 0}}}}}};
    const double big = 1e30;
    double x_lo = -big, x_hi = big, z_lo = -big, z_hi = big;
    if (box) {
      j["environment"] = {{"image", "env.exr"}, {"room_box", {{"min", {-1, 0, -4}}, {"max", {2, 2.5, 2}}, {"capture", {0.5, 1, 0}}}}};
      x_lo = -1, x_hi = 2, z_lo = -4, z_hi = 2;
    }
    const LoadedScene s = load_scene(parse_scene_file(fx.write(j)));
    const RenderResult r = render_scene(s);
    int floor_pixels = 0, empty_pixels = 0;
    for (int y = 0; y < s.camera.height; ++y)
      for (int x = 0; x < s.camera.width; ++x) {
        std::vector<double> zs;
        for (int c = 0; c < 4; ++c)
          if (auto z = floor_z(s.camera, {x + c % 2, y + c / 2}, x_lo, x_hi, z_lo, z_hi)) zs.push_back(*z);
        const float depth = *r.layers.depth.at(x, y);
        ASSERT_TRUE(std::isfinite(depth));
        if (zs.size() == 4) {
          ++floor_pixels;
          const auto [lo, hi] = std::minmax_element(zs.begin(), zs.end());
          EXPECT_GE(depth, *lo * (1 - 1e-5)) << x << "," << y << " box " << box;
          EXPECT_LE(depth, *hi * (1 + 1e-5)) << x << "," << y << " box " << box;
        } else if (zs.empty()) {
          ++empty_pixels;
          EXPECT_EQ(depth, kNoHitDepth) << x << "," << y << " box " << box;
        }
      }
    EXPECT_GT(floor_pixels, 100);
    EXPECT_GT(empty_pixels, 20) << "the view should show some sky (no box) or beyond the walls (box)";
  }
}

}  // namespace
}  // namespace insitu
