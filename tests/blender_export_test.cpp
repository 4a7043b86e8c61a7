// insitu export-blender (interop/blender_export.h): the room box's walls, the catchers' albedo, the
// files and their safety, and — where Blender is installed — Cycles rendering the exported scene
// as insitu renders it.
#include <gtest/gtest.h>

#include <cstdlib>
#include <fmt/format.h>

#include "cli_util.h"
#include "gltf_fixture.h"
#include "obj_sphere.h"
#include "core/image.h"
#include "light/preview.h"
#include "interop/blender_export.h"
#include "scene/catcher_albedo.h"
#include "scene/pipeline.h"
#include "scene/scene_file.h"

namespace insitu {
namespace {

using json = nlohmann::json;

double quad_area(const Quad& q) { return 0.5 * ((q[2] - q[0]).cross(q[3] - q[1])).norm(); }

// Walls: the box's area less the openings', every quad facing into the box; the floor, which a
// local-scene plane replaces, left out.
TEST(BlenderExport, RoomWallsLeaveTheOpeningsOpenAndFaceInward) {
  EnvironmentSpec::RoomBox box;
  box.min = Vec3d(-2, 0, -3), box.max = Vec3d(3, 2.5, 1), box.capture = Vec3d(0, 1.2, 0);
  box.openings.push_back({Vec3d(-2, 0.8, -1), Vec3d(-2, 2.0, 0.5), 0});  // a window in the −x wall
  box.openings.push_back({Vec3d(0.5, 0.0, 1), Vec3d(1.4, 2.1, 1), 2});   // a door in the +z wall
  PlaneSpec floor;
  floor.point = Vec3d(5, 0, 7), floor.normal = Vec3d(0, -2, 0);
  const std::vector<Quad> quads = room_wall_quads(box, {floor});
  const Vec3d d = box.max - box.min;
  const double walls = 2 * (d.y() * d.z() + d.x() * d.y()) + d.x() * d.z();  // four walls and the ceiling
  const double openings = 1.2 * 1.5 + 0.9 * 2.1;
  double area = 0;
  for (const Quad& q : quads) {
    area += quad_area(q);
    const Vec3d n = (q[1] - q[0]).cross(q[2] - q[0]), centre = 0.25 * (q[0] + q[1] + q[2] + q[3]);
    EXPECT_GT(n.dot(0.5 * (box.min + box.max) - centre), 0) << "a wall faces out";
    EXPECT_GT(centre.y(), box.min.y() + 1e-9) << "the floor was kept";
  }
  EXPECT_NEAR(area, walls - openings, 1e-9);
  // Without the plane the floor is a wall too.
  double with_floor = 0;
  for (const Quad& q : room_wall_quads(box, {})) with_floor += quad_area(q);
  EXPECT_NEAR(with_floor, walls - openings + d.x() * d.z(), 1e-9);
}

Image constant_image(int w, int h, const Rgb& v) {
  Image img(w, h, 3);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) img.set_rgb(x, y, v);
  return img;
}

// A small scene: a constant linear photo, an environment brighter above than below with a bright
// patch on one side (a mirrored or turned world would light the ball differently), a floor plane
// and the demo's ball resting on it.
struct ExportFixture {
  test::TempDir dir;
  json scene;
  Rgb photo_value = Rgb(0.3f, 0.25f, 0.2f);

  ExportFixture() {
    write_image(dir.file("photo.exr"), constant_image(96, 72, photo_value));
    Image env(64, 32, 3);
    for (int y = 0; y < 32; ++y)
      for (int x = 0; x < 64; ++x) {
        Rgb L = y < 16 ? Rgb(2.0f, 1.9f, 1.7f) : Rgb(0.5f, 0.5f, 0.5f);
        if (y >= 6 && y < 12 && x >= 40 && x < 48) L = Rgb(30.0f, 28.0f, 24.0f);
        env.set_rgb(x, y, L);
      }
    write_image(dir.file("env.exr"), env);
    for (const char* f : {"ball.obj", "ball.mtl"})
      std::filesystem::copy_file(test::source_dir() + "/scenes/demo/" + f, dir.path() / f);
    scene = {{"photo", "photo.exr"},
             {"camera", {{"eye", {0.0, 0.7, 1.5}}, {"look", {0.0, 0.2, 0.0}}, {"hfov_deg", 40}}},
             {"environment", "env.exr"},
             {"local_scene", {{{"plane", {{"point", {0, 0, 0}}, {"normal", {0, 1, 0}}}}}}},
             {"objects", {{{"mesh", "ball.obj"}}}},
             {"render", {{"integrator", "path"}, {"spp", 64}}}};
  }
  std::string write() const { return dir.write("scene.json", scene.dump(2)); }
};

// Under a constant environment L every surface's irradiance is πL, so a constant photo P gives
// ρ = πP / (πL) = P/L on the floor and on a wall alike; above 0.95 it is clamped; a surface with
// an albedo keeps it.
TEST(BlenderExport, CatcherAlbedoIsThePhotosOverTheIrradiance) {
  ExportFixture fx;
  const float L = 0.6f;
  fx.scene["photo"] = "photo.exr";
  write_image(fx.dir.file("env.exr"), constant_image(32, 16, Rgb::Constant(L)));
  fx.scene["local_scene"] = {{{"plane", {{"point", {0, 0, 0}}, {"normal", {0, 1, 0}}}}},
                             {{"plane", {{"point", {0, 0, -0.4}}, {"normal", {0, 0, 1}}}}},
                             {{"plane", {{"point", {0, 0, -9}}, {"normal", {0, 0, 1}}}}, {"albedo", {0.1, 0.2, 0.3}}}};
  const LoadedScene s = load_scene(parse_scene_file(fx.write()));
  const std::vector<CatcherAlbedo> a = catcher_albedos(s);
  ASSERT_EQ(a.size(), 3u);
  for (int k = 0; k < 2; ++k) {
    EXPECT_TRUE(a[std::size_t(k)].from_photo);
    EXPECT_GT(a[std::size_t(k)].pixels, 500u) << k;
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(a[std::size_t(k)].albedo[c], fx.photo_value[c] / L, 2e-3) << k << " channel " << c;
  }
  EXPECT_FALSE(a[2].from_photo);
  EXPECT_TRUE((a[2].albedo == Rgb(0.1f, 0.2f, 0.3f)).all());
  // A photo brighter than any albedo could make it: clamped.
  write_image(fx.dir.file("photo.exr"), constant_image(96, 72, Rgb::Constant(0.9f)));
  const LoadedScene bright = load_scene(parse_scene_file(fx.write()));
  EXPECT_FLOAT_EQ(catcher_albedos(bright)[0].albedo[0], 0.95f);
}

// The CLI writes the script, the meshes and the world; the meshes' size follows from their counts
// (load_mesh's layout) and the world is the environment cube unrolled.
TEST(BlenderExport, WritesTheThreeFiles) {
  ExportFixture fx;
  const std::string scene = fx.write();
  const test::CliRun r = test::run_insitu(fx.dir, "export-blender " + scene + " -o " + fx.dir.file("out/ball.py"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string script = test::slurp(fx.dir.file("out/ball.py"));
  EXPECT_NE(script.find("catcher(quads_object("), std::string::npos);
  EXPECT_EQ(script.find("room_box(scene, ["), std::string::npos);
  EXPECT_NE(script.find("render_settings(scene, 64, 5, 1)"), std::string::npos)
      << "the scene's spp and the path default depth";
  const LoadedScene s = load_scene(parse_scene_file(scene));
  const Mesh& ball = s.objects->meshes().at(0);
  const std::size_t nv = ball.positions.size(), nt = ball.triangles.size();
  // positions, triangles, material indices, corner normals and UVs: 4 bytes each.
  EXPECT_EQ(std::filesystem::file_size(fx.dir.file("out/ball.meshes.bin")),
            4 * (3 * nv + 3 * nt + nt + 9 * nt + 6 * nt));
  const Image world = read_image_file(fx.dir.file("out/ball.world.exr")).stored;
  EXPECT_EQ(world.width, 4 * s.environment.size());
  EXPECT_EQ(world.data, cube_to_equirect(s.environment).data);
}

// The world file must not replace an input: here the environment itself.
TEST(BlenderExport, RefusesToReplaceAnInput) {
  ExportFixture fx;
  std::filesystem::copy_file(fx.dir.file("env.exr"), fx.dir.file("in.world.exr"));
  fx.scene["environment"] = "in.world.exr";
  const std::string before = test::slurp(fx.dir.file("in.world.exr"));
  test::expect_one_line_error(test::run_insitu(fx.dir, "export-blender " + fx.write() + " -o " + fx.dir.file("in.py")),
                              "in.world.exr");
  EXPECT_EQ(test::slurp(fx.dir.file("in.world.exr")), before);
  EXPECT_FALSE(std::filesystem::exists(fx.dir.file("in.py")));
  test::expect_one_line_error(test::run_insitu(fx.dir, "export-blender " + fx.write() + " -o " + fx.dir.file("in.txt")),
                              ".py");
}

}  // namespace
}  // namespace insitu

namespace insitu {
namespace {

bool have_blender() { return std::system("command -v blender > /dev/null 2>&1") == 0; }

// Renders an exported script with Cycles; returns the composite (linear EXR).
Image render_with_cycles(const test::TempDir& dir, const std::string& script, int spp) {
  const std::string out = dir.file("cycles.exr"), log = dir.file("blender.log");
  const std::string cmd = fmt::format("blender -b --factory-startup --python {} -- --render {} --samples {} > {} 2>&1",
                                      script, out, spp, log);
  EXPECT_EQ(std::system(cmd.c_str()), 0) << test::slurp(log);
  return read_image_file(out).stored;
}

double lum(const float* p) { return 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2]; }

// Σ|a − b| / Σ b of the luminance over the objects' inner pixels (alpha 1 with its four
// neighbours: the edges' coverage differs between two renderers' sampling).
double object_error(const Image& a, const Image& b, const Image& alpha) {
  double num = 0, den = 0;
  for (int y = 1; y + 1 < alpha.height; ++y)
    for (int x = 1; x + 1 < alpha.width; ++x) {
      if (*alpha.at(x, y) < 1 || *alpha.at(x - 1, y) < 1 || *alpha.at(x + 1, y) < 1 || *alpha.at(x, y - 1) < 1 ||
          *alpha.at(x, y + 1) < 1)
        continue;
      num += std::abs(lum(a.at(x, y)) - lum(b.at(x, y))), den += lum(b.at(x, y));
    }
  return num / std::max(1e-30, den);
}

// The mean of composite / photo over the floor's pixels that the objects darken in insitu's render
// (the shadow), and the number of them.
double shadow_ratio(const Image& composite, const Image& insitu_composite, const Image& alpha, const Rgb& photo,
                    int* n) {
  double sum = 0;
  *n = 0;
  for (int y = 0; y < alpha.height; ++y)
    for (int x = 0; x < alpha.width; ++x)
      if (*alpha.at(x, y) == 0 && lum(insitu_composite.at(x, y)) < 0.9 * lum(photo.data())) {
        sum += lum(composite.at(x, y)) / lum(photo.data());
        ++*n;
      }
  return *n ? sum / *n : 0;
}

struct Comparison {
  double objects, objects_noise, cycles_noise, shadow_insitu, shadow_cycles;
  int shadow_pixels;
};

// insitu's path integrator at `spp` and Cycles on the exported scene at the same spp, each twice
// (seeds 1 and 2: each renderer's noise floor).
Comparison compare_with_cycles(ExportFixture& fx, int spp, bool mirror_world = false) {
  fx.scene["render"]["spp"] = spp;
  SceneSpec spec = parse_scene_file(fx.write());
  const LoadedScene s = load_scene(spec);
  const RenderResult r1 = render_scene(s);
  LoadedScene s2 = load_scene(spec);
  s2.spec.render.seed = 2;
  const RenderResult r2 = render_scene(s2);
  const BlenderExportPaths paths = blender_export_paths(fx.dir.file("export.py"));
  BlenderExport e = make_blender_export(s, paths);
  if (mirror_world) {  // the negative control: the world turned about the vertical
    Image m = e.world;
    for (int y = 0; y < m.height; ++y)
      for (int x = 0; x < m.width; ++x) m.set_rgb(x, y, e.world.rgb(m.width - 1 - x, y));
    e.world = m;
  }
  write_blender_export(e, paths);
  const Image cycles = render_with_cycles(fx.dir, paths.script, spp);
  const BlenderExportPaths paths2 = blender_export_paths(fx.dir.file("export2.py"));
  BlenderExport e2 = make_blender_export(s2, paths2);
  e2.world = e.world, e2.outside = e.outside;
  write_blender_export(e2, paths2);
  const Image cycles2 = render_with_cycles(fx.dir, paths2.script, spp);
  EXPECT_EQ(cycles.width, s.camera.width);
  const Image& alpha = r1.layers.alpha;
  Comparison c{};
  c.objects = object_error(cycles, r1.composite_linear, alpha);
  c.objects_noise = object_error(r2.composite_linear, r1.composite_linear, alpha);
  c.cycles_noise = object_error(cycles2, cycles, alpha);
  c.shadow_insitu = shadow_ratio(r1.composite_linear, r1.composite_linear, alpha, fx.photo_value, &c.shadow_pixels);
  c.shadow_cycles = shadow_ratio(cycles, r1.composite_linear, alpha, fx.photo_value, &c.shadow_pixels);
  return c;
}

// The exported scene's Cycles gets insitu's limits: every bounce at the path's depth, and the
// cut-outs crossed as insitu crosses them, without end (Cycles's default 8 would end a path behind
// the 8th sheer layer). A limit set by a name Cycles lacks would not reach it: this reads them back.
TEST(BlenderExport, CyclesGetsInsitusBounceLimits) {
  if (!have_blender()) GTEST_SKIP() << "blender is not installed (apt-get install blender)";
  ExportFixture fx;
  const std::string script = fx.dir.file("ball.py"), log = fx.dir.file("blender.log");
  ASSERT_EQ(test::run_insitu(fx.dir, "export-blender " + fx.write() + " -o " + script).exit_code, 0);
  const std::string read_back =
      "import bpy; c = bpy.data.scenes['insitu'].cycles; print('LIMITS', c.max_bounces, c.diffuse_bounces, "
      "c.glossy_bounces, c.transmission_bounces, c.transparent_max_bounces)";
  const std::string cmd =
      fmt::format("blender -b --factory-startup --python {} --python-expr \"{}\" > {} 2>&1", script, read_back, log);
  ASSERT_EQ(std::system(cmd.c_str()), 0) << test::slurp(log);
  EXPECT_NE(test::slurp(log).find("LIMITS 5 5 5 5 1024\n"), std::string::npos) << test::slurp(log);
}

// Cycles on the exported scene against insitu's path integrator, both at 256 spp, with a distant
// environment and with a room box (a window in one wall). The objects' L1 difference is bounded by
// 2 √((f_i² + f_c²) / 2) + 2 %, f_i and f_c the L1 differences of two renders of each renderer
// (seeds 1, 2): noise alone gives k·√(σ_c² + σ_i²) between them, and f = k·√2·σ for each, so the
// root is what noise alone gives and 2 its margin; the 2 % is for what the export approximates (the
// BSDF as Cycles's nodes, the catchers' mean albedo: 1.5 % beyond the noise with the distant world).
// (The bound was 2 f_i + 1 % while insitu's samples were independent: its noise floor stood in for
// Cycles's, and its slack hid that the export's own difference is nearer 2 % than 1 %.) The shadow (composite / photo
// on the floor's darkened pixels, a mean over some 500 pixels) agrees within 0.02. The negative control: the same world
// mirrored fails both.
//
// "glTF principled": the ball as a glTF sphere of a half-metallic, moderately rough material, which
// Blender's own glTF importer turns into its Principled BSDF: insitu's principled model
// (render/bsdf.h) against Cycles's, lobe by lobe, under the same bound. "MTL principled": the ball
// as an OBJ of the MTL PBR extension (a half-metal, its roughness from a grey data map, under a
// normal map), which the export builds as Cycles's Principled BSDF (render/obj_materials.h).
TEST(BlenderExport, CyclesRendersTheExportedSceneAsInsituDoes) {
  if (!have_blender()) GTEST_SKIP() << "blender is not installed (apt-get install blender)";
  for (const std::string variant : {"distant", "room box", "glTF principled", "MTL principled", "mirrored world"}) {
    ExportFixture fx;
    if (variant == "MTL principled") {
      Image grey(8, 8, 3), normals(8, 8, 3);
      const Vec3f tilted = Vec3f(0.3f, 0, 1).normalized();
      for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 8; ++x) {
          const bool odd = (x + y) % 2;
          grey.set_rgb(x, y, Rgb::Constant(odd ? 0.4f : 0.8f));
          const Vec3f n(odd ? tilted.x() : -tilted.x(), 0, tilted.z());
          normals.set_rgb(x, y, Rgb((n.x() + 1) / 2, (n.y() + 1) / 2, (n.z() + 1) / 2));
        }
      write_image(fx.dir.file("rough.png"), grey);
      write_image(fx.dir.file("normals.png"), normals);
      test::write_obj_sphere(fx.dir, "ball", Vec3f(0, 0.2f, 0), 0.2f,
                             "Kd 0.3 0.5 0.8\nKs 0.5 0.5 0.5\nPm 0.4\nPr 0.6\nmap_Pr rough.png\nnorm normals.png\n");
      fx.scene["objects"] = {{{"mesh", "ball.obj"}}};
    }
    if (variant == "glTF principled") {
      const json material = {
          {"pbrMetallicRoughness",
           {{"baseColorFactor", {0.8, 0.5, 0.3, 1.0}}, {"metallicFactor", 0.6}, {"roughnessFactor", 0.35}}}};
      test::write_gltf_sphere(fx.dir, "ball", Vec3f(0, 0.2f, 0), 0.2f, material);
      fx.scene["objects"] = {{{"mesh", "ball.gltf"}}};
    }
    if (variant == "room box")
      fx.scene["environment"] = {{"image", "env.exr"},
                                 {"room_box",
                                  {{"min", {-2, 0, -2}},
                                   {"max", {2.5, 2.5, 2}},
                                   {"capture", {0.3, 1.0, 0.2}},
                                   {"openings", {{{"min", {-2, 0.8, -1.0}}, {"max", {-2, 2.2, 1.2}}}}}}}};
    const Comparison c = compare_with_cycles(fx, test::kUnderAsan ? 4 : 256, variant == "mirrored world");
    std::printf(
        "%s: objects: error %.4f (noise floors: insitu %.4f, Cycles %.4f); shadow: insitu %.4f, Cycles %.4f over %d "
        "pixels\n",
        variant.c_str(), c.objects, c.objects_noise, c.cycles_noise, c.shadow_insitu, c.shadow_cycles, c.shadow_pixels);
    if (test::kUnderAsan) GTEST_SKIP() << "the agreement is checked in the release build, not under AddressSanitizer";
    const double bound =
        2 * std::sqrt((c.objects_noise * c.objects_noise + c.cycles_noise * c.cycles_noise) / 2) + 0.02;
    EXPECT_GT(c.shadow_pixels, 200) << variant;
    if (variant == "mirrored world") {
      EXPECT_GT(c.objects, bound) << "the comparison cannot tell a mirrored world";
      EXPECT_GT(std::abs(c.shadow_cycles - c.shadow_insitu), 0.02) << "the comparison cannot tell a mirrored world";
    } else {
      EXPECT_LT(c.objects, bound) << variant;
      EXPECT_NEAR(c.shadow_cycles, c.shadow_insitu, 0.02) << variant;
    }
  }
}

}  // namespace
}  // namespace insitu
