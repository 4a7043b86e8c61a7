#include <gtest/gtest.h>

#include <cstdlib>
#include <fmt/format.h>

#include "interop/blender_camera.h"
#include "core/image.h"
#include "cli_util.h"
#include "test_util.h"

namespace insitu {
namespace {

// insitu's Y-up world to Blender's Z-up world.
Vec3d to_blender(const Vec3d& p) { return Vec3d(p.x(), -p.z(), p.y()); }

// Three small emitting spheres (red, green, blue) on black, rendered by Cycles through the camera
// that blender_camera_script creates.
std::string render_script(const std::vector<Vec3d>& centres_world, double radius, const std::string& out) {
  std::string s = "import bpy\nscene = bpy.context.scene\n";
  s += "for o in list(scene.objects):\n    if o.name != 'insitu camera': bpy.data.objects.remove(o, do_unlink=True)\n";
  s += "scene.world = bpy.data.worlds.new('black')\nscene.world.color = (0, 0, 0)\n";
  s += "scene.render.engine = 'CYCLES'\nscene.cycles.samples = 16\nscene.cycles.device = "
       "'CPU'\nscene.cycles.use_denoising = False\n";
  s += "scene.view_settings.view_transform = 'Standard'\n";
  s += "scene.render.image_settings.file_format = 'OPEN_EXR'\n";
  const char* colours[] = {"(1, 0, 0, 1)", "(0, 1, 0, 1)", "(0, 0, 1, 1)"};
  for (std::size_t i = 0; i < centres_world.size(); ++i) {
    const Vec3d b = to_blender(centres_world[i]);
    s += fmt::format(
        "bpy.ops.mesh.primitive_uv_sphere_add(radius={}, location=({}, {}, {}), segments=48, ring_count=24)\n", radius,
        b.x(), b.y(), b.z());
    s += fmt::format(
        "m = bpy.data.materials.new('e{0}')\nm.use_nodes = True\nn = m.node_tree.nodes\n"
        "n.remove(n['Principled BSDF'])\ne = n.new('ShaderNodeEmission')\ne.inputs['Color'].default_value = {1}\n"
        "m.node_tree.links.new(e.outputs[0], n['Material Output'].inputs[0])\n"
        "bpy.context.active_object.data.materials.append(m)\n",
        i, colours[i]);
  }
  s += fmt::format("scene.render.filepath = '{}'\nbpy.ops.render.render(write_still=True)\n", out);
  return s;
}

// The centroid of channel c's bright pixels.
Vec2d centroid(const Image& im, int c) {
  Vec2d sum = Vec2d::Zero();
  double w = 0;
  for (int y = 0; y < im.height; ++y)
    for (int x = 0; x < im.width; ++x) {
      const double v = im.data[(std::size_t(y) * im.width + x) * im.channels + c];
      if (v > 0.05) {
        sum += v * Vec2d(x + 0.5, y + 0.5);
        w += v;
      }
    }
  return w > 0 ? Vec2d(sum / w) : Vec2d(-1, -1);
}

// A wide camera with its principal point off centre, and a tall one with non-square pixels:
// Blender renders each sphere where insitu projects its centre.
TEST(BlenderCamera, CyclesRendersPointsWhereInsituProjectsThem) {
  if (std::system("command -v blender > /dev/null 2>&1") != 0)
    GTEST_SKIP() << "blender is not installed (apt-get install blender)";
  struct Case {
    int w, h;
    double fx, fy, cx, cy;
  };
  for (const Case k : {Case{320, 240, 300, 300, 180, 105}, Case{240, 320, 280, 308, 112, 170}}) {
    test::TempDir dir;
    Camera cam = Camera::look_at(Vec3d(1.0, 1.4, 3.0), Vec3d(0.2, 0.6, -0.5), Vec3d(0, 1, 0), 60, k.w, k.h);
    cam.fx = k.fx;
    cam.fy = k.fy;
    cam.cx = k.cx;
    cam.cy = k.cy;
    const std::vector<Vec3d> centres = {Vec3d(0.2, 0.6, -0.5), Vec3d(-0.4, 0.2, -0.9), Vec3d(0.7, 1.0, -0.2)};
    const std::string cam_py = dir.write("cam.py", blender_camera_script(cam));
    const std::string render_py = dir.write("render.py", render_script(centres, 0.03, dir.file("render.exr")));
    const std::string cmd = "blender -b --factory-startup --python " + cam_py + " --python " + render_py + " > " +
                            dir.file("blender.log") + " 2>&1";
    ASSERT_EQ(std::system(cmd.c_str()), 0) << test::slurp(dir.file("blender.log"));
    const Image im = read_image_file(dir.file("render.exr")).stored;
    ASSERT_EQ(im.width, k.w);
    ASSERT_EQ(im.height, k.h);
    for (int i = 0; i < 3; ++i) {
      const Vec2d expected = cam.project(centres[std::size_t(i)]), got = centroid(im, i);
      EXPECT_LT((got - expected).norm(), 0.25) << k.w << "x" << k.h << " sphere " << i << ": Blender ("
                                               << got.transpose() << "), insitu (" << expected.transpose() << ")";
    }
  }
}

}  // namespace
}  // namespace insitu
