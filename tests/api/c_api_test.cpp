// The C API (include/insitu/insitu.h), called as a host program calls it, against libinsitu.so:
// the same layers as the CLI's EXR bit for bit, scenes from files and from JSON text, meshes and
// control points from memory, errors as codes with the CLI's `where: what`, cancellation from the
// callback and from another thread, and two scenes rendering at once.
#include <gtest/gtest.h>

#include <OpenImageIO/imageio.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <string>
#include <thread>
#include <vector>

#include "cli_util.h"
#include "core/camera.h"
#include "gltf_fixture.h"
#include "insitu/insitu.h"
#include "scene_fixture.h"

namespace {

using insitu::test::SceneFixture;

// The fixture's scene rendered by the path tracer with a floor that catches the shadow.
nlohmann::json path_scene(const SceneFixture& fx, int spp) {
  auto j = fx.scene;
  j["render"] = {{"integrator", "path"}, {"spp", spp}};
  j["local_scene"] = {{{"plane", {{"point", {0, 0, 0}}, {"normal", {0, 1, 0}}}}}};
  return j;
}

insitu_scene* scene_from(const std::string& path) {
  insitu_scene* s = nullptr;
  EXPECT_EQ(insitu_scene_from_file(path.c_str(), &s), INSITU_OK) << insitu_last_error();
  return s;
}

struct Result {
  insitu_status status = INSITU_OK;
  insitu_result* r = nullptr;
  ~Result() { insitu_result_free(r); }
};

std::vector<float> layer(const insitu_result* r, const char* name, int* channels = nullptr) {
  const float* data = nullptr;
  int c = 0;
  EXPECT_EQ(insitu_result_layer(r, name, &data, &c), INSITU_OK) << insitu_last_error();
  if (channels) *channels = c;
  return data ? std::vector<float>(data, data + std::size_t(insitu_result_width(r)) * insitu_result_height(r) * c)
              : std::vector<float>{};
}

// One channel of an EXR, by name.
std::vector<float> exr_channel(const std::string& path, const std::string& channel) {
  auto in = OIIO::ImageInput::open(path);
  if (!in) return {};
  const OIIO::ImageSpec& spec = in->spec();
  const int c = spec.channelindex(channel);
  if (c < 0) return {};
  std::vector<float> v(std::size_t(spec.width) * spec.height);
  in->read_image(0, 0, c, c + 1, OIIO::TypeDesc::FLOAT, v.data());
  return v;
}

std::vector<float> channel_of(const std::vector<float>& interleaved, int channels, int c) {
  std::vector<float> v;
  for (std::size_t i = std::size_t(c); i < interleaved.size(); i += std::size_t(channels)) v.push_back(interleaved[i]);
  return v;
}

// The fixture's camera, and six points as it sees them: in memory, and in the file points.json.
insitu::Camera fixture_camera(const SceneFixture& fx) {
  return insitu::Camera::look_at({0.5, 2.0, 1.5}, {0.5, 0.0, -0.5}, {0, 1, 0}, 60, fx.width, fx.height);
}

std::vector<insitu_control_point> known_points(const SceneFixture& fx, const insitu::Camera& truth) {
  std::vector<insitu_control_point> points;
  nlohmann::json file = nlohmann::json::array();
  for (const insitu::Vec3d& p :
       {insitu::Vec3d(0, 0, 0), {1, 0, 0}, {1, 0, -1}, {0, 0, -1}, {0.5, 0.5, -0.5}, {0.2, 0.8, -0.9}}) {
    const insitu::Vec2d uv = truth.project(p);
    points.push_back({uv.x(), uv.y(), p.x(), p.y(), p.z()});
    file.push_back({{"uv", {uv.x(), uv.y()}}, {"xyz", {p.x(), p.y(), p.z()}}});
  }
  fx.dir.write("points.json", file.dump());
  return points;
}

TEST(CApi, Version) {
  EXPECT_EQ(insitu_api_version(), INSITU_API_VERSION);
  EXPECT_STREQ(insitu_version(), INSITU_VERSION);
}

// Every layer the C API returns is the CLI's EXR channel, float for float.
TEST(CApi, LayersAreTheCLIsExrBitForBit) {
  SceneFixture fx;
  const std::string scene = fx.write(path_scene(fx, 4));
  const auto cli = insitu::test::run_insitu(fx.dir, "render " + scene + " -o " + fx.dir.file("cli.png"));
  ASSERT_EQ(cli.exit_code, 0) << cli.err;
  insitu_scene* s = scene_from(scene);
  Result r;
  ASSERT_EQ(insitu_render(s, nullptr, nullptr, &r.r), INSITU_OK) << insitu_last_error();
  ASSERT_EQ(insitu_result_width(r.r), fx.width);
  EXPECT_EQ(insitu_result_spp(r.r), 4);
  int compared = 0;
  for (int i = 0; i < insitu_result_layer_count(r.r); ++i) {
    const std::string name = insitu_result_layer_name(r.r, i);
    if (name == "display") continue;  // the PNG's: not in the EXR
    int channels = 0;
    const std::vector<float> data = layer(r.r, name.c_str(), &channels);
    const char* names[] = {"R", "G", "B", "A"};
    for (int c = 0; c < channels; ++c) {
      std::string ch = channels == 1      ? (name == "depth" ? "Z" : "Y")
                       : name == "normal" ? std::string(1, "XYZ"[c])
                                          : names[c];
      if (name != "composite") ch = name + "." + ch;
      EXPECT_EQ(channel_of(data, channels, c), exr_channel(fx.dir.file("cli.layers.exr"), ch)) << ch;
      ++compared;
    }
  }
  EXPECT_EQ(compared, 28);
  EXPECT_EQ(insitu_result_layer_name(r.r, insitu_result_layer_count(r.r)), nullptr);
  insitu_scene_free(s);
}

// A scene from JSON text renders as the same scene from its file; relative paths start at base_dir.
TEST(CApi, SceneFromJsonTextAndSettings) {
  SceneFixture fx;
  const std::string file = fx.write(path_scene(fx, 2));
  insitu_scene* a = scene_from(file);
  ASSERT_EQ(insitu_scene_set(a, "render.spp", "3"), INSITU_OK) << insitu_last_error();
  insitu_scene* b = nullptr;
  ASSERT_EQ(insitu_scene_from_json(path_scene(fx, 3).dump().c_str(), fx.dir.path().c_str(), "mine", &b), INSITU_OK)
      << insitu_last_error();
  Result ra, rb;
  ASSERT_EQ(insitu_render(a, nullptr, nullptr, &ra.r), INSITU_OK);
  ASSERT_EQ(insitu_render(b, nullptr, nullptr, &rb.r), INSITU_OK);
  EXPECT_EQ(insitu_result_spp(ra.r), 3);
  EXPECT_EQ(layer(ra.r, "composite"), layer(rb.r, "composite"));
  // A bad value is refused with the JSON path, and the scene is as it was.
  EXPECT_EQ(insitu_scene_set(a, "render.spp", "-3"), INSITU_ERROR_INPUT);
  EXPECT_NE(std::string(insitu_last_error()).find("$.render.spp"), std::string::npos) << insitu_last_error();
  EXPECT_EQ(insitu_scene_set(a, "render.spp", "{"), INSITU_ERROR_INPUT);
  EXPECT_NE(std::string(insitu_last_error()).find("render.spp:1:2: malformed JSON"), std::string::npos)
      << insitu_last_error();
  EXPECT_EQ(insitu_scene_set(a, "render.colour", "1"), INSITU_ERROR_INPUT);  // no integrator reads it
  EXPECT_NE(std::string(insitu_last_error()).find("colour"), std::string::npos) << insitu_last_error();
  Result again;
  ASSERT_EQ(insitu_render(a, nullptr, nullptr, &again.r), INSITU_OK);
  EXPECT_EQ(layer(again.r, "composite"), layer(ra.r, "composite"));
  insitu_scene_free(a);
  insitu_scene_free(b);
}

TEST(CApi, ErrorsAreCodesWithTheCLIsMessage) {
  SceneFixture fx;
  insitu_scene* s = nullptr;
  const std::string missing = fx.dir.file("missing.json");
  EXPECT_EQ(insitu_scene_from_file(missing.c_str(), &s), INSITU_ERROR_INPUT);
  EXPECT_EQ(s, nullptr);
  EXPECT_EQ(std::string(insitu_last_error()), missing + ": file not found");
  EXPECT_EQ(insitu_scene_from_json("{\"photo\": 1}", nullptr, nullptr, &s), INSITU_ERROR_INPUT);
  EXPECT_NE(std::string(insitu_last_error()).find("<json>:$.photo"), std::string::npos) << insitu_last_error();
  EXPECT_EQ(insitu_scene_from_file(nullptr, &s), INSITU_ERROR_ARGUMENT);
  EXPECT_EQ(insitu_render(nullptr, nullptr, nullptr, nullptr), INSITU_ERROR_ARGUMENT);
  // A mesh named in the scene that is broken: the CLI's message, whole.
  auto j = path_scene(fx, 1);
  fx.dir.write("bad.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n");
  j["objects"] = {{{"mesh", "bad.obj"}}};
  s = scene_from(fx.write(j));
  Result r;
  EXPECT_EQ(insitu_render(s, nullptr, nullptr, &r.r), INSITU_ERROR_INPUT);
  EXPECT_EQ(r.r, nullptr);
  const auto cli = insitu::test::run_insitu(fx.dir, "render " + fx.dir.file("scene.json"));
  EXPECT_EQ(cli.err, "insitu: error: " + std::string(insitu_last_error()) + "\n");
  insitu_scene_free(s);
}

// A glTF file added through the API renders as the scene file's "mesh" renders it, principled
// material (a coated, half-metallic ball) and all.
TEST(CApi, GltfFileRendersAsTheSceneFileSaysIt) {
  SceneFixture fx;
  const nlohmann::json material = {
      {"pbrMetallicRoughness", {{"baseColorFactor", {0.8, 0.4, 0.2, 1}}, {"metallicFactor", 0.5}}},
      {"extensions", {{"KHR_materials_clearcoat", {{"clearcoatFactor", 1.0}, {"clearcoatRoughnessFactor", 0.1}}}}}};
  const std::string ball =
      insitu::test::write_gltf_sphere(fx.dir, "ball", insitu::Vec3f(0.5f, 0.2f, -0.5f), 0.2f, material, 8);
  auto j = path_scene(fx, 2);
  j["objects"] = {{{"mesh", "ball.gltf"}}};
  insitu_scene* a = scene_from(fx.write(j));
  j.erase("objects");
  insitu_scene* b = scene_from(fx.write(j));
  ASSERT_EQ(insitu_scene_add_obj(b, ball.c_str(), nullptr), INSITU_OK) << insitu_last_error();
  Result ra, rb;
  ASSERT_EQ(insitu_render(a, nullptr, nullptr, &ra.r), INSITU_OK) << insitu_last_error();
  ASSERT_EQ(insitu_render(b, nullptr, nullptr, &rb.r), INSITU_OK) << insitu_last_error();
  const std::vector<float> objects = layer(ra.r, "objects");
  float coverage = 0;
  for (std::size_t i = 3; i < objects.size(); i += 4) coverage += objects[i];
  EXPECT_GT(coverage, 1.0f);  // the ball is in view
  for (const char* name : {"composite", "objects", "with", "without"})
    EXPECT_EQ(layer(ra.r, name), layer(rb.r, name)) << name;
  insitu_scene_free(a);
  insitu_scene_free(b);
}

// The quad of tests/data/good_quad.obj given from memory renders as the file does.
TEST(CApi, MeshFromMemoryRendersAsTheObj) {
  SceneFixture fx;
  auto j = path_scene(fx, 2);
  j.erase("objects");
  const std::string file = fx.write(j);
  insitu_scene* a = scene_from(file);
  insitu_scene* b = scene_from(file);
  const double M[16] = {1, 0, 0, 0.1, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
  ASSERT_EQ(insitu_scene_add_obj(a, fx.dir.file("good_quad.obj").c_str(), M), INSITU_OK) << insitu_last_error();
  const float positions[] = {0, 0, 0, 1, 0, 0, 1, 0, -1, 0, 0, -1};
  const float normals[] = {0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0};
  const float uvs[] = {0, 0, 1, 0, 1, 1, 0, 1};
  const std::uint32_t indices[] = {0, 1, 2, 0, 2, 3};  // the OBJ's quad fanned as the reader fans it
  insitu_mesh mesh;
  insitu_mesh_init(&mesh);
  mesh.positions = positions, mesh.normals = normals, mesh.uvs = uvs, mesh.vertex_count = 4;
  mesh.indices = indices, mesh.triangle_count = 2;
  mesh.kd[0] = 0.8f, mesh.kd[1] = 0.1f, mesh.kd[2] = 0.05f;  // good_quad.mtl
  mesh.ks[0] = mesh.ks[1] = mesh.ks[2] = 0.04f, mesh.ns = 50;
  ASSERT_EQ(insitu_scene_add_mesh(b, &mesh, M, "quad"), INSITU_OK) << insitu_last_error();
  Result ra, rb;
  ASSERT_EQ(insitu_render(a, nullptr, nullptr, &ra.r), INSITU_OK) << insitu_last_error();
  ASSERT_EQ(insitu_render(b, nullptr, nullptr, &rb.r), INSITU_OK) << insitu_last_error();
  EXPECT_GT(layer(ra.r, "objects")[4 * (16 * fx.width + 24) + 3] + 1, 1.0f);  // the quad is in view
  for (const char* name : {"composite", "objects", "with", "without", "normal", "depth"})
    EXPECT_EQ(layer(ra.r, name), layer(rb.r, name)) << name;
  // Bad arrays: named by array and index; the scene keeps its meshes.
  const std::uint32_t bad_indices[] = {0, 1, 2, 0, 2, 4};
  mesh.indices = bad_indices;
  EXPECT_EQ(insitu_scene_add_mesh(b, &mesh, nullptr, "quad"), INSITU_ERROR_INPUT);
  EXPECT_EQ(std::string(insitu_last_error()), "quad: indices[5]: vertex 4 out of range (the mesh has 4 vertices)");
  const float nan_positions[] = {0, 0, 0, 1, 0, 0, 1, NAN, -1, 0, 0, -1};
  mesh.indices = indices, mesh.positions = nan_positions;
  EXPECT_EQ(insitu_scene_add_mesh(b, &mesh, nullptr, "quad"), INSITU_ERROR_INPUT);
  EXPECT_EQ(std::string(insitu_last_error()), "quad: positions[7]: not a finite number");
  Result again;
  ASSERT_EQ(insitu_render(b, nullptr, nullptr, &again.r), INSITU_OK);
  EXPECT_EQ(layer(again.r, "composite"), layer(rb.r, "composite"));
  insitu_scene_free(a);
  insitu_scene_free(b);
}

// Points in memory calibrate as the CLI calibrates them from a file; the scene takes them too.
TEST(CApi, CalibrationFromMemoryIsTheCLIs) {
  SceneFixture fx;
  const insitu::Camera truth = fixture_camera(fx);
  const std::vector<insitu_control_point> points = known_points(fx, truth);
  const auto cli =
      insitu::test::run_insitu(fx.dir, "calibrate --points " + fx.dir.file("points.json") + " --size 48 32 " +
                                           "--box sofa 0 0 -1 1 0.5 0 -o " + fx.dir.file("camera.json"));
  ASSERT_EQ(cli.exit_code, 0) << cli.err;
  insitu_calibration* c = nullptr;
  ASSERT_EQ(insitu_calibrate(points.data(), points.size(), 48, 32, nullptr, nullptr, &c), INSITU_OK)
      << insitu_last_error();
  const double lo[3] = {0, 0, -1}, hi[3] = {1, 0.5, 0};
  ASSERT_EQ(insitu_calibration_add_box(c, "sofa", lo, hi), INSITU_OK);
  EXPECT_EQ(std::string(insitu_calibration_json(c)), insitu::test::slurp(fx.dir.file("camera.json")));
  EXPECT_EQ(cli.out.rfind(insitu_calibration_report(c), 0), 0u) << cli.out;
  EXPECT_LT(insitu_calibration_rms_px(c), 1e-6);
  insitu_camera cam;
  ASSERT_EQ(insitu_calibration_camera(c, &cam), INSITU_OK);
  EXPECT_NEAR(cam.fx, truth.fx, 1e-6 * truth.fx);
  // The scene calibrated from the same points has the same camera, and its report.
  insitu_scene* s = scene_from(fx.write(path_scene(fx, 1)));
  ASSERT_EQ(insitu_scene_set_control_points(s, points.data(), points.size(), "auto"), INSITU_OK) << insitu_last_error();
  insitu_camera scam;
  ASSERT_EQ(insitu_scene_camera(s, &scam), INSITU_OK) << insitu_last_error();
  EXPECT_EQ(scam.fx, cam.fx);
  const char* report = nullptr;
  ASSERT_EQ(insitu_scene_calibration_report(s, &report), INSITU_OK);
  EXPECT_NE(std::string(report).find("RMS"), std::string::npos) << report;
  // Set explicitly, the camera is taken as given; one for another image size is refused.
  scam.fx *= 1.1;
  ASSERT_EQ(insitu_scene_set_camera(s, &scam), INSITU_OK) << insitu_last_error();
  insitu_camera back;
  ASSERT_EQ(insitu_scene_camera(s, &back), INSITU_OK) << insitu_last_error();
  EXPECT_EQ(back.fx, scam.fx);
  scam.width = 64;
  ASSERT_EQ(insitu_scene_set_camera(s, &scam), INSITU_OK);
  EXPECT_EQ(insitu_scene_camera(s, &back), INSITU_ERROR_INPUT);
  EXPECT_NE(std::string(insitu_last_error()).find("64x32 images, the photo is 48x32"), std::string::npos)
      << insitu_last_error();
  // Four points cannot calibrate: the calibration's own message.
  insitu_calibration* none = nullptr;
  EXPECT_EQ(insitu_calibrate(points.data(), 4, 48, 32, nullptr, nullptr, &none), INSITU_ERROR_INPUT);
  EXPECT_EQ(none, nullptr);
  insitu_calibration_free(c);
  insitu_scene_free(s);
}

// Cancelled from the callback as a pass is under way: INSITU_CANCELLED, and the result holds the
// samples taken, whole tiles of the cancelled pass included.
TEST(CApi, CancelFromTheCallbackMidPass) {
  SceneFixture fx(160, 96);
  insitu_scene* s = scene_from(fx.write(path_scene(fx, 64)));
  struct Count {
    int tiles = 0;
  } count;
  auto fn = [](const insitu_progress* p, void* user) -> int {
    auto& c = *static_cast<Count*>(user);
    EXPECT_EQ(p->spp_planned, 64);
    return p->noise < 0 && p->fraction > 0.3 && ++c.tiles >= 3;
  };
  Result r;
  ASSERT_EQ(insitu_render(s, fn, &count, &r.r), INSITU_CANCELLED) << insitu_last_error();
  ASSERT_NE(r.r, nullptr);
  EXPECT_EQ(insitu_result_cancelled(r.r), 1);
  EXPECT_LT(insitu_result_spp(r.r), 64);
  const std::vector<float> samples = layer(r.r, "samples");
  const float lo = float(insitu_result_spp(r.r)), hi = lo + 8;  // passes of 8 samples
  for (float n : samples) ASSERT_TRUE(n == lo || n == hi) << n;
  EXPECT_NE(std::string(insitu_result_report(r.r)).find("\"interrupted\": true"), std::string::npos);
  insitu_scene_free(s);
}

// insitu_scene_cancel from another thread stops the render under way.
TEST(CApi, CancelFromAnotherThread) {
  SceneFixture fx(160, 96);
  insitu_scene* s = scene_from(fx.write(path_scene(fx, 1 << 14)));
  std::atomic<bool> started{false};
  auto fn = [](const insitu_progress* p, void* user) -> int {
    if (p->fraction > 0) static_cast<std::atomic<bool>*>(user)->store(true);
    return 0;
  };
  std::thread canceller([&] {
    while (!started) std::this_thread::sleep_for(std::chrono::milliseconds(1));
    insitu_scene_cancel(s);
  });
  Result r;
  EXPECT_EQ(insitu_render(s, fn, &started, &r.r), INSITU_CANCELLED);
  canceller.join();
  EXPECT_LT(insitu_result_spp(r.r), 1 << 14);
  insitu_scene_free(s);
}

// Two scenes render at once, on two threads, to what each renders alone.
TEST(CApi, TwoScenesRenderConcurrently) {
  SceneFixture fx1, fx2(40, 30);
  auto j2 = path_scene(fx2, 3);
  j2["render"]["seed"] = 9;
  insitu_scene* scenes[2] = {scene_from(fx1.write(path_scene(fx1, 3))), scene_from(fx2.write(j2))};
  std::vector<float> alone[2];
  for (int i = 0; i < 2; ++i) {
    Result r;
    ASSERT_EQ(insitu_render(scenes[i], nullptr, nullptr, &r.r), INSITU_OK);
    alone[i] = layer(r.r, "composite");
  }
  for (int round = 0; round < 3; ++round) {
    Result together[2];
    std::thread t([&] { together[1].status = insitu_render(scenes[1], nullptr, nullptr, &together[1].r); });
    together[0].status = insitu_render(scenes[0], nullptr, nullptr, &together[0].r);
    t.join();
    for (int i = 0; i < 2; ++i) {
      ASSERT_EQ(together[i].status, INSITU_OK);
      EXPECT_EQ(layer(together[i].r, "composite"), alone[i]) << "scene " << i;
    }
  }
  insitu_scene_free(scenes[0]);
  insitu_scene_free(scenes[1]);
}

// The result's buffers and files: a copy into the caller's buffer, a short buffer refused, an
// unknown layer named with the known ones, and the files the CLI writes; never over an input.
TEST(CApi, ResultBuffersAndFiles) {
  SceneFixture fx;
  insitu_scene* s = scene_from(fx.write(path_scene(fx, 2)));
  Result r;
  ASSERT_EQ(insitu_render(s, nullptr, nullptr, &r.r), INSITU_OK);
  std::vector<float> buffer(std::size_t(fx.width) * fx.height * 4);
  ASSERT_EQ(insitu_result_copy_layer(r.r, "objects", buffer.data(), buffer.size()), INSITU_OK);
  EXPECT_EQ(buffer, layer(r.r, "objects"));
  EXPECT_EQ(insitu_result_copy_layer(r.r, "objects", buffer.data(), buffer.size() - 1), INSITU_ERROR_ARGUMENT);
  const float* data = nullptr;
  EXPECT_EQ(insitu_result_layer(r.r, "colour", &data, nullptr), INSITU_ERROR_ARGUMENT);
  EXPECT_NE(std::string(insitu_last_error()).find("no layer 'colour' (the layers: composite, objects"),
            std::string::npos);
  ASSERT_EQ(insitu_result_write(r.r, fx.dir.file("a.png").c_str(), fx.dir.file("a.exr").c_str()), INSITU_OK)
      << insitu_last_error();
  EXPECT_TRUE(std::filesystem::exists(fx.dir.file("a.png.report.json")));
  EXPECT_EQ(exr_channel(fx.dir.file("a.exr"), "objects.A"), channel_of(layer(r.r, "objects"), 4, 3));
  const std::string photo_before = insitu::test::slurp(fx.dir.file("photo.png"));
  EXPECT_EQ(insitu_result_write(r.r, fx.dir.file("photo.png").c_str(), nullptr), INSITU_ERROR_INPUT);
  EXPECT_EQ(insitu::test::slurp(fx.dir.file("photo.png")), photo_before);
  insitu_scene_free(s);
}

}  // namespace

namespace {

// docs/library.md's two listings are the example files the install test builds and runs.
TEST(CApi, LibraryPageShowsTheTestedExamples) {
  const std::string readme = insitu::test::slurp(std::string(INSITU_SOURCE_DIR) + "/docs/library.md");
  for (const auto& [file, fence] : {std::pair{"minimal.c", "```c\n"}, std::pair{"minimal.py", "```python\n"}}) {
    const std::string text = insitu::test::slurp(std::string(INSITU_SOURCE_DIR) + "/examples/" + file);
    ASSERT_FALSE(text.empty()) << file;
    EXPECT_NE(readme.find(fence + text + "```\n"), std::string::npos)
        << "docs/library.md does not show examples/" << file;
    EXPECT_LE(std::count(text.begin(), text.end(), '\n'), std::string(file) == "minimal.c" ? 24 : 10) << file;
  }
}

}  // namespace

namespace {

// A resumable render cancelled midway writes its checkpoint; the next call continues from it to
// the uninterrupted render's layers, bit for bit, and removes it; a checkpoint of other settings
// is refused, and the photo cannot be the checkpoint.
TEST(CApi, ResumableRenderContinuesBitForBit) {
  SceneFixture fx(160, 96);
  insitu_scene* s = scene_from(fx.write(path_scene(fx, 16)));
  Result whole;
  ASSERT_EQ(insitu_render(s, nullptr, nullptr, &whole.r), INSITU_OK);
  const std::string checkpoint = fx.dir.file("api.checkpoint");
  auto cancel_early = [](const insitu_progress* p, void*) -> int { return p->fraction > 0.4; };
  Result part;
  ASSERT_EQ(insitu_render_resumable(s, checkpoint.c_str(), cancel_early, nullptr, &part.r), INSITU_CANCELLED)
      << insitu_last_error();
  ASSERT_TRUE(std::filesystem::exists(checkpoint));
  Result rest;
  ASSERT_EQ(insitu_render_resumable(s, checkpoint.c_str(), nullptr, nullptr, &rest.r), INSITU_OK)
      << insitu_last_error();
  for (const char* name : {"composite", "objects", "with", "without", "variance", "samples"})
    EXPECT_EQ(layer(rest.r, name), layer(whole.r, name)) << name;
  EXPECT_FALSE(std::filesystem::exists(checkpoint));
  Result again;
  ASSERT_EQ(insitu_render_resumable(s, checkpoint.c_str(), cancel_early, nullptr, &again.r), INSITU_CANCELLED);
  ASSERT_EQ(insitu_scene_set(s, "render.seed", "2"), INSITU_OK);
  Result refused;
  EXPECT_EQ(insitu_render_resumable(s, checkpoint.c_str(), nullptr, nullptr, &refused.r), INSITU_ERROR_INPUT);
  EXPECT_NE(std::string(insitu_last_error()).find("a checkpoint of another scene"), std::string::npos)
      << insitu_last_error();
  EXPECT_EQ(insitu_render_resumable(s, fx.dir.file("photo.png").c_str(), nullptr, nullptr, &refused.r),
            INSITU_ERROR_INPUT);
  insitu_scene_free(s);
}

// The calibrate verb's other outputs: the Blender script and the View Correlation file, as the CLI
// writes them.
TEST(CApi, CalibrationBlenderScriptAndViewCorrelation) {
  SceneFixture fx;
  const insitu::Camera truth = fixture_camera(fx);
  const std::vector<insitu_control_point> points = known_points(fx, truth);
  const auto cli = insitu::test::run_insitu(fx.dir, "calibrate --points " + fx.dir.file("points.json") + " --image " +
                                                        fx.dir.file("photo.png") + " --vc " + fx.dir.file("cli.vc") +
                                                        " --blender " + fx.dir.file("cli.py"));
  ASSERT_EQ(cli.exit_code, 0) << cli.err;
  insitu_calibration* c = nullptr;
  ASSERT_EQ(insitu_calibrate(points.data(), points.size(), 48, 32, nullptr, nullptr, &c), INSITU_OK);
  EXPECT_EQ(std::string(insitu_calibration_blender_script(c, fx.dir.file("photo.png").c_str())),
            insitu::test::slurp(fx.dir.file("cli.py")));
  ASSERT_EQ(insitu_calibration_write_vc(c, fx.dir.file("api.vc").c_str()), INSITU_OK) << insitu_last_error();
  EXPECT_EQ(insitu::test::slurp(fx.dir.file("api.vc")), insitu::test::slurp(fx.dir.file("cli.vc")));
  EXPECT_EQ(insitu_calibration_write_vc(c, fx.dir.file("points.json").c_str()), INSITU_ERROR_INPUT);
  insitu_calibration_free(c);
}

}  // namespace
