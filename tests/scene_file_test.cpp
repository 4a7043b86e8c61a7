#include <gtest/gtest.h>

#include <filesystem>

#include <tbb/global_control.h>

#include "output/composite.h"
#include "scene/pipeline.h"
#include "cli_util.h"
#include "scene_fixture.h"

namespace insitu {
namespace {

using test::SceneFixture;
namespace fs = std::filesystem;

// Expects parse+load of `j` to fail with an InputError whose place ends with `where` (after the
// scene file's path) and whose message contains `what`.
void expect_error(const SceneFixture& fx, const nlohmann::json& j, const std::string& where, const std::string& what) {
  const std::string path = fx.write(j);
  try {
    load_scene(parse_scene_file(path));
    ADD_FAILURE() << "expected an InputError at " << where;
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().substr(0, path.size()), path) << e.what();
    EXPECT_EQ(e.where().substr(std::min(e.where().size(), path.size())), where) << e.what();
    EXPECT_NE(e.message().find(what), std::string::npos) << e.what();
  }
}

TEST(SceneFile, ValidSceneLoads) {
  SceneFixture fx;
  const LoadedScene s = load_scene(parse_scene_file(fx.write()));
  EXPECT_EQ(s.camera.width, fx.width);
  EXPECT_EQ(s.environment.size(), 4);  // 16 / 4
  EXPECT_EQ(s.objects->meshes().size(), 1u);
  EXPECT_EQ(s.spec.render.spp, 4);
  EXPECT_EQ(s.spec.render.integrator, "realtime");
}

// The layers' default (issue 46): out/layers.exr beside the default image; beside an image of
// the scene's own, IMAGE_STEM.layers.exr (variants in one folder wrote one out/layers.exr over
// each other's); as given, or none, when output.layers says so.
// The README's first scene is a scene file insitu reads: its JSON block under "A first scene of
// your own", parsed as the CLI parses it, beside empty files of the names it gives (nothing is loaded).
TEST(SceneFile, TheReadmesFirstSceneIsOneInsituReads) {
  const std::string readme = test::slurp(test::source_dir() + "/README.md");
  const std::size_t section = readme.find("## A first scene of your own"), begin = readme.find("```json\n", section),
                    end = readme.find("```\n", begin + 8);
  ASSERT_NE(section, std::string::npos);
  ASSERT_NE(end, std::string::npos);
  const json doc = json::parse(readme.substr(begin + 8, end - begin - 8));
  test::TempDir room;
  for (const char* f : {"room.jpg", "points.json", "east.jpg", "west.jpg", "south.jpg", "north.jpg", "ceiling.jpg",
                        "floor.jpg", "chair.glb"})
    room.write(f, "");
  const SceneSpec spec = parse_scene_json(doc, "README.md", room.path().string());
  EXPECT_EQ(spec.camera.kind, CameraSpec::Kind::Points);
  EXPECT_TRUE(spec.environment.from_shots());
  ASSERT_EQ(spec.objects.size(), 1u);
  EXPECT_EQ(spec.output.image, room.file("out/chair.png"));
  EXPECT_EQ(spec.render.integrator, "path");
}

TEST(SceneFile, TheLayersFollowTheImage) {
  using Paths = std::pair<std::string, std::string>;  // the image's and the layers', in the scene's folder
  SceneFixture fx;
  const auto outputs = [&](const nlohmann::json& output) {
    auto j = fx.scene;
    if (!output.is_null()) j["output"] = output;
    const OutputSpec o = parse_scene_file(fx.write(j)).output;
    return Paths{fs::path(o.image).lexically_relative(fx.dir.path()).string(),
                 o.layers.empty() ? "" : fs::path(o.layers).lexically_relative(fx.dir.path()).string()};
  };
  EXPECT_EQ(outputs(nullptr), Paths("out/composite.png", "out/layers.exr"));
  EXPECT_EQ(outputs({{"image", "out/sofa.png"}}), Paths("out/sofa.png", "out/sofa.layers.exr"));
  EXPECT_EQ(outputs({{"image", "out/sofa.png"}, {"layers", "l.exr"}}), Paths("out/sofa.png", "l.exr"));
  EXPECT_EQ(outputs({{"image", "out/sofa.png"}, {"layers", "none"}}), Paths("out/sofa.png", ""));
}

TEST(SceneFile, MalformedJsonNamesLineAndColumn) {
  SceneFixture fx;
  const std::string path = fx.dir.write("scene.json", "{\n  \"photo\": \"photo.png\",\n  \"camera\": {,\n}");
  try {
    parse_scene_file(path);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.where(), path + ":3:14") << e.what();
    EXPECT_NE(e.message().find("malformed JSON"), std::string::npos);
  }
}

TEST(SceneFile, MissingSceneFile) { EXPECT_THROW(parse_scene_file("/nonexistent/scene.json"), InputError); }

TEST(SceneFile, UnknownKeys) {
  SceneFixture fx;
  auto j = fx.scene;
  j["photos"] = "photo.png";
  expect_error(fx, j, ":$.photos", "unknown key");
  j = fx.scene;
  j["render"]["sp"] = 4;
  expect_error(fx, j, ":$.render.sp", "unknown key");
  j = fx.scene;
  j["objects"][0]["rotation"] = 30;
  expect_error(fx, j, ":$.objects[0].rotation", "unknown key");
}

TEST(SceneFile, WrongTypes) {
  SceneFixture fx;
  auto j = fx.scene;
  j["render"]["spp"] = "many";
  expect_error(fx, j, ":$.render.spp", "expected an integer");
  j = fx.scene;
  j["camera"]["eye"] = {1, 2};
  expect_error(fx, j, ":$.camera.eye", "expected an array of 3 numbers");
  j = fx.scene;
  j["objects"] = nlohmann::json::array({"good_quad.obj"});
  expect_error(fx, j, ":$.objects[0]", "expected an object, got string");
  j = fx.scene;
  j["photo"] = 3;
  expect_error(fx, j, ":$.photo", "expected a string");
}

TEST(SceneFile, OutOfRangeValues) {
  SceneFixture fx;
  auto j = fx.scene;
  j["render"]["spp"] = 0;
  expect_error(fx, j, ":$.render.spp", "0 is out of range");
  j = fx.scene;
  j["camera"]["hfov_deg"] = 180;
  expect_error(fx, j, ":$.camera.hfov_deg", "out of range");
  j = fx.scene;
  j["objects"][0]["scale"] = 0;
  expect_error(fx, j, ":$.objects[0].scale", "scale must not be zero");
  j = fx.scene;
  j["camera"]["look"] = j["camera"]["eye"];
  expect_error(fx, j, ":$.camera.look", "look point equals the eye");
  j = fx.scene;
  j["render"]["integrator"] = "raytrace";
  expect_error(fx, j, ":$.render.integrator", "unknown integrator 'raytrace' (known: realtime, irradiance, path)");
}

// Inverse lighting's keys (issue 13): a plane's reference mean albedo, and the switch.
TEST(SceneFile, MeanAlbedoAndInverseLighting) {
  SceneFixture fx;
  auto j = fx.scene;
  j["local_scene"] = {{{"plane", {{"point", {0, 0, 0}}, {"normal", {0, 1, 0}}}}, {"mean_albedo", 0.4}}};
  j["environment"] = {{"image", "env.exr"}, {"inverse_lighting", false}};
  const SceneSpec spec = parse_scene_file(fx.write(j));
  ASSERT_EQ(spec.local_scene.size(), 1u);
  EXPECT_EQ(spec.local_scene[0].mean_albedo, 0.4);
  EXPECT_TRUE(spec.local_scene[0].albedo_from_photo);  // still rendered with the photo's texture
  EXPECT_FALSE(spec.environment.inverse_lighting);
  EXPECT_TRUE(parse_scene_file(fx.write()).environment.inverse_lighting);  // on by default
  j["local_scene"][0]["mean_albedo"] = 1.5;
  expect_error(fx, j, ":$.local_scene[0].mean_albedo", "out of range");
  j["local_scene"][0]["mean_albedo"] = 0.4;
  j["local_scene"][0]["albedo"] = {0.5, 0.5, 0.5};
  expect_error(fx, j, ":$.local_scene[0].mean_albedo", "not both");
  j = fx.scene;
  j["environment"] = {{"image", "env.exr"}, {"inverse_lighting", "yes"}};
  expect_error(fx, j, ":$.environment.inverse_lighting", "expected true or false");
}

// A reference in the photo: its polygon as given, its albedo; a polygon of fewer than three corners
// or of less than a pixel's area is refused where it is.
// "denoise": off unless the file says so (a final render is not denoised by default).
TEST(SceneFile, DenoiseIsOffUnlessAsked) {
  SceneFixture fx;
  EXPECT_FALSE(parse_scene_file(fx.write()).denoise);
  auto j = fx.scene;
  j["denoise"] = true;
  EXPECT_TRUE(parse_scene_file(fx.write(j)).denoise);
  j["denoise"] = 1;
  expect_error(fx, j, ":$.denoise", "expected");
}

TEST(SceneFile, ReferencesInThePhoto) {
  SceneFixture fx;
  auto j = fx.scene;
  j["references"] = {{{"polygon_px", {{1, 2}, {9.5, 2}, {9.5, 7}}}, {"albedo", 0.18}}};
  const SceneSpec spec = parse_scene_file(fx.write(j));
  ASSERT_EQ(spec.references.size(), 1u);
  EXPECT_EQ(spec.references[0].albedo, 0.18);
  ASSERT_EQ(spec.references[0].polygon_px.size(), 3u);
  EXPECT_EQ(spec.references[0].polygon_px[1], Vec2d(9.5, 2));
  EXPECT_NE(spec.references[0].where.find(":$.references[0]"), std::string::npos);
  j["references"][0]["polygon_px"] = {{1, 2}, {9.5, 2}};
  expect_error(fx, j, ":$.references[0].polygon_px", "3 or more");
  j["references"][0]["polygon_px"] = {{1, 1}, {2, 2}, {3, 3.5}};  // area ¼ pixel
  expect_error(fx, j, ":$.references[0].polygon_px", "less than one pixel");
  j["references"][0]["polygon_px"] = {{1, 2}, {9.5, 2}, {9.5}};
  expect_error(fx, j, ":$.references[0].polygon_px[2]", "[u, v]");
}

// A grey ball in the room: its centre and radius as given; a reference is a polygon or a ball, not
// both and not neither, a ball has a positive radius, and a reference plate must exist.
TEST(SceneFile, AGreyBallReference) {
  SceneFixture fx;
  auto j = fx.scene;
  j["references"] = {{{"sphere", {{"center", {0.5, 0.15, -1}}, {"radius", 0.15}}}, {"albedo", 0.18}}};
  const SceneSpec spec = parse_scene_file(fx.write(j));
  ASSERT_EQ(spec.references.size(), 1u);
  ASSERT_TRUE(spec.references[0].ball.has_value());
  EXPECT_EQ(spec.references[0].ball->center_world, Vec3d(0.5, 0.15, -1));
  EXPECT_EQ(spec.references[0].ball->radius_m, 0.15);
  EXPECT_TRUE(spec.references[0].polygon_px.empty());
  j["references"][0]["sphere"]["radius"] = 0;
  expect_error(fx, j, ":$.references[0].sphere.radius", "");
  j["references"][0]["sphere"]["radius"] = 0.15;
  j["references"][0]["polygon_px"] = {{1, 2}, {9.5, 2}, {9.5, 7}};
  expect_error(fx, j, ":$.references[0].sphere", "not both");
  j["references"][0].erase("sphere");
  j["references"][0].erase("polygon_px");
  expect_error(fx, j, ":$.references[0]", "'polygon_px' (a patch in the photo) or 'sphere'");
  j["references"][0]["sphere"] = {{"center", {0, 0, 0}}, {"radius", 1}, {"colour", 1}};
  expect_error(fx, j, ":$.references[0].sphere.colour", "unknown key (expected one of: center, radius)");
  j["references"][0]["sphere"] = {{"center", {0, 0, 0}}, {"radius", 1}};
  j["references"][0]["photo"] = "plate.jpg";
  expect_error(fx, j, ":$.references[0].photo", "file not found");
}

TEST(SceneFile, MissingFilesAndKeys) {
  SceneFixture fx;
  auto j = fx.scene;
  j["photo"] = "nope.jpg";
  expect_error(fx, j, ":$.photo", "file not found");
  j = fx.scene;
  j["objects"][0]["mesh"] = "sofa.obj";
  expect_error(fx, j, ":$.objects[0].mesh", "file not found");
  j = fx.scene;
  j.erase("camera");
  expect_error(fx, j, ":$", "missing required key 'camera'");
  // A missing "faced" says what it is (issue 46).
  j = fx.scene;
  j["environment"] = {{"shots",
                       {{"+x", "photo.png"},
                        {"-x", "photo.png"},
                        {"+z", "photo.png"},
                        {"-z", "photo.png"},
                        {"up", "photo.png"},
                        {"down", "photo.png"}}}};
  expect_error(fx, j, ":$.environment.shots", "the wall you faced when you shot the ceiling and the floor");
}

// One tiny shot among six limits every cube face: said, naming it (issue 46: a 1×1 shot shrank
// the environment to six texels without a word); six shots of one size say nothing.
TEST(SceneFile, AShotThatShrinksTheEnvironmentIsNamed) {
  SceneFixture fx;
  nlohmann::json shots = {{"faced", "-z"}};
  for (const char* k : {"+x", "-x", "+z", "-z", "up", "down"}) {
    const std::string name = std::string("shot") +
                             (k[0] == '+'   ? "p"
                              : k[0] == '-' ? "n"
                                            : "") +
                             (k + (k[0] == '+' || k[0] == '-')) + ".png";
    write_image(fx.dir.file(name), Image(64, 64, 3, 0.4f));
    shots[k] = name;
  }
  auto j = fx.scene;
  j["environment"] = {{"shots", shots}};
  const auto warned = [&](const std::string& about) {
    const LoadedScene s = load_scene(parse_scene_file(fx.write(j)));
    for (const std::string& w : s.warnings.items)
      if (w.find("limits every cube face") != std::string::npos) return w.find(about) != std::string::npos;
    return false;
  };
  EXPECT_FALSE(warned(""));
  write_image(fx.dir.file("tiny.png"), Image(1, 1, 3, 0.4f));
  j["environment"]["shots"]["+z"] = "tiny.png";
  EXPECT_TRUE(warned("tiny.png: 1 × 1 pixels: it limits every cube face to"));
}

// Context is prepended once: an error named at the same place twice on its way out (issue 46:
// "sh.json:$.environment.shots.+x: sh.json:$.environment.shots.+x: ...").
TEST(SceneFile, ContextIsNamedOnce) {
  const InputError inner("sh.json:$.shots.+x: bad.jpg", "cannot read image");
  EXPECT_EQ(inner.with_context("sh.json:$.shots.+x").where(), "sh.json:$.shots.+x: bad.jpg");
  EXPECT_EQ(inner.with_context("sh.json").where(), "sh.json:$.shots.+x: bad.jpg");
  EXPECT_EQ(inner.with_context("batch.json:$.entries[0]").where(),
            "batch.json:$.entries[0]: sh.json:$.shots.+x: bad.jpg");
  EXPECT_EQ(InputError("bad.jpg", "x").with_context("sh.json:$.shots.+x").what(),
            std::string("sh.json:$.shots.+x: bad.jpg: x"));
}

TEST(SceneFile, BadMeshErrorCarriesJsonPathAndObjLine) {
  SceneFixture fx;
  std::filesystem::copy_file(test::test_data("bad_zero_index.obj"), fx.dir.path() / "bad.obj");
  auto j = fx.scene;
  j["objects"][0]["mesh"] = "bad.obj";
  expect_error(fx, j, ":$.objects[0].mesh: " + fx.dir.file("bad.obj") + ":5", "face vertex index 0");
}

TEST(SceneFile, EnvironmentOfWrongShape) {
  SceneFixture fx;
  write_image(fx.dir.file("square.exr"), Image(8, 8, 3, 1.0f));
  auto j = fx.scene;
  j["environment"] = "square.exr";
  expect_error(fx, j, ":$.environment",
               "neither equirectangular (2:1, or partial with GPano metadata) nor a cube strip (1:6)");
}

TEST(SceneFile, CameraFileOfAnotherSizeIsAnError) {
  SceneFixture fx;
  nlohmann::json cam = camera_to_json(Camera::look_at({0, 1, 1}, {0, 0, 0}, {0, 1, 0}, 50, 640, 480));
  fx.dir.write("camera.json", cam.dump());
  auto j = fx.scene;
  j["camera"] = {{"file", "camera.json"}};
  const std::string path = fx.write(j);
  try {
    load_scene(parse_scene_file(path));
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.where(), fx.dir.file("camera.json") + ":$.width");
    EXPECT_NE(e.message().find("camera is for 640x480 images, the photo is 48x32"), std::string::npos);
  }
}

TEST(SceneFile, CameraFileRoundTrip) {
  SceneFixture fx;
  const Camera original = Camera::look_at({0.3, 1.7, 2.2}, {0, 0, 0}, {0, 1, 0}, 55, fx.width, fx.height);
  fx.dir.write("camera.json", camera_to_json(original).dump());
  auto j = fx.scene;
  j["camera"] = {{"file", "camera.json"}};
  const LoadedScene s = load_scene(parse_scene_file(fx.write(j)));
  EXPECT_NEAR((s.camera.R_cam_from_world - original.R_cam_from_world).norm(), 0.0, 1e-12);
  EXPECT_NEAR((s.camera.t_cam_from_world - original.t_cam_from_world).norm(), 0.0, 1e-12);
  EXPECT_DOUBLE_EQ(s.camera.fx, original.fx);
}

TEST(SceneFile, ExplicitIntrinsicsAndPose) {
  SceneFixture fx;
  auto j = fx.scene;
  j["camera"] = {{"intrinsics", {{"fx", 40.0}, {"cx", 20.0}}},
                 {"pose", {{"R", {{1, 0, 0}, {0, -1, 0}, {0, 0, -1}}}, {"t", {0, 0, 3}}}}};
  const LoadedScene s = load_scene(parse_scene_file(fx.write(j)));
  EXPECT_DOUBLE_EQ(s.camera.fy, 40.0);
  EXPECT_DOUBLE_EQ(s.camera.cx, 20.0);
  EXPECT_DOUBLE_EQ(s.camera.cy, 16.0);                            // the image centre by default
  j["camera"]["pose"]["R"] = {{1, 0, 0}, {0, 1, 0}, {0, 0, -1}};  // a reflection
  expect_error(fx, j, ":$.camera.pose.R", "not a rotation");
}

// Exporters (Blender, most JSON writers) round R to 6 decimals: such an R is accepted with a
// warning and replaced by the nearest rotation; beyond the documented tolerance, or mirrored, it is
// refused.
TEST(SceneFile, RotationRoundedByAnExporterIsAccepted) {
  SceneFixture fx;
  const Mat3d exact = Eigen::AngleAxisd(0.7, Vec3d(1, 2, 3).normalized()).toRotationMatrix();
  for (const double decimals : {6.0, 5.0}) {
    const double scale = std::pow(10.0, decimals);
    nlohmann::json rows = nlohmann::json::array();
    Mat3d rounded;
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) rounded(r, c) = std::round(exact(r, c) * scale) / scale;
    for (int r = 0; r < 3; ++r) rows.push_back({rounded(r, 0), rounded(r, 1), rounded(r, 2)});
    auto j = fx.scene;
    j["camera"] = {{"intrinsics", {{"fx", 40.0}}}, {"pose", {{"R", rows}, {"t", {0, 0, 3}}}}};
    const LoadedScene s = load_scene(parse_scene_file(fx.write(j)));
    const Mat3d& R = s.camera.R_cam_from_world;
    EXPECT_LT((R * R.transpose() - Mat3d::Identity()).norm(), 1e-12);
    EXPECT_LT((R - exact).norm(), 3 * 0.5 / scale);  // rounding moved each entry by at most ½·10⁻ᵈ
    // A warning exactly when R was further than 1e-6 from orthonormal.
    const double orth = (rounded * rounded.transpose() - Mat3d::Identity()).norm();
    bool warned = false;
    for (const auto& w : s.warnings.items) warned |= w.find("nearest rotation") != std::string::npos;
    EXPECT_EQ(warned, orth > 1e-6) << decimals << " decimals, |R Rᵀ − I| = " << orth;
    if (decimals == 5.0) {
      EXPECT_TRUE(warned);
      // Beyond the tolerance: refused, and the message states the tolerance.
      j["camera"]["pose"]["R"][0][0] = rounded(0, 0) + 2 * kRotationTolerance;
      expect_error(fx, j, ":$.camera.pose.R", "not a rotation");
    }
  }
}

TEST(SceneFile, ExactRotationGivesNoWarning) {
  SceneFixture fx;
  auto j = fx.scene;
  j["camera"] = {{"intrinsics", {{"fx", 40.0}}},
                 {"pose", {{"R", {{1, 0, 0}, {0, -1, 0}, {0, 0, -1}}}, {"t", {0, 0, 3}}}}};
  const LoadedScene s = load_scene(parse_scene_file(fx.write(j)));
  for (const auto& w : s.warnings.items) EXPECT_EQ(w.find("rotation"), std::string::npos) << w;
}

// Messages that name the real mistake: an unknown key before a missing one, the allowed forms of
// rotate and scale, and a mesh that is not OBJ.
TEST(SceneFile, MessagesNameTheRealMistake) {
  SceneFixture fx;
  auto j = fx.scene;
  j["camera"] = {{"eye", {0.5, 2.0, 1.5}}, {"look", {0.5, 0.0, -0.5}}, {"fov", 70}};
  expect_error(fx, j, ":$.camera.fov", "unknown key");
  j = fx.scene;
  j["objects"][0]["rotate"] = {0, 20, 0};
  expect_error(fx, j, ":$.objects[0].rotate", "expected degrees about +Y (\"rotate\": 30) or {\"angle_deg\"");
  j = fx.scene;
  j["objects"][0]["scale"] = "0.3";
  expect_error(fx, j, ":$.objects[0].scale", "expected a number (uniform: \"scale\": 0.3) or [sx, sy, sz]");
  j = fx.scene;
  fx.dir.write("chair.ply", "ply\nformat ascii 1.0\nend_header\n");
  j["objects"][0]["mesh"] = "chair.ply";
  expect_error(fx, j, ":$.objects[0].mesh: " + fx.dir.file("chair.ply"),
               "only OBJ and glTF meshes are supported ('.ply')");
}

// A focal length in millimetres where pixels are meant stays finite but opens the view to ~180°:
// warned, with the field of view it gives.
TEST(SceneFile, TinyFocalLengthIsWarned) {
  SceneFixture fx;
  auto j = fx.scene;
  j["camera"] = {{"intrinsics", {{"fx", 1e-9}}},
                 {"pose", {{"R", {{1, 0, 0}, {0, -1, 0}, {0, 0, -1}}}, {"t", {0, 0, 3}}}}};
  const LoadedScene s = load_scene(parse_scene_file(fx.write(j)));
  bool warned = false;
  for (const auto& w : s.warnings.items) warned |= w.find("field of view of 180.0°") != std::string::npos;
  EXPECT_TRUE(warned);
  j["camera"]["intrinsics"]["fx"] = 40.0;
  for (const auto& w : load_scene(parse_scene_file(fx.write(j))).warnings.items)
    EXPECT_EQ(w.find("field of view"), std::string::npos);
}

// An object that covers no pixel is worth a warning; one in view is not.
TEST(SceneFile, ObjectOutOfViewIsWarned) {
  SceneFixture fx;
  auto has_warning = [](const LoadedScene& s) {
    for (const auto& w : s.warnings.items)
      if (w.find("outside the camera's view") != std::string::npos) return true;
    return false;
  };
  EXPECT_FALSE(has_warning(load_scene(parse_scene_file(fx.write()))));
  for (const nlohmann::json& t : {nlohmann::json{0, 0, 50}, nlohmann::json{40, 0, 0}, nlohmann::json{0, -30, 0}}) {
    auto j = fx.scene;
    j["objects"][0]["translate"] = t;
    EXPECT_TRUE(has_warning(load_scene(parse_scene_file(fx.write(j))))) << t.dump();
  }
  // The frustum test itself: a box around the look point is inside, one behind the eye outside.
  const Camera cam = Camera::look_at({0, 1, 3}, {0, 1, 0}, {0, 1, 0}, 60, 64, 48);
  Bounds in, behind;
  in.extend({-0.1f, 0.9f, -0.1f}), in.extend({0.1f, 1.1f, 0.1f});
  behind.extend({-0.1f, 0.9f, 3.5f}), behind.extend({0.1f, 1.1f, 3.7f});
  EXPECT_FALSE(outside_view(cam, in));
  EXPECT_TRUE(outside_view(cam, behind));
}

// Untouched pixels must come out exactly as they went in: with no objects, and with objects
// entirely out of view.
TEST(SceneFile, NoObjectsReproducesThePhotoBitForBit) {
  SceneFixture fx;
  for (int variant = 0; variant < 2; ++variant) {
    auto j = fx.scene;
    if (variant == 0)
      j["objects"] = nlohmann::json::array();
    else
      j["objects"][0]["translate"] = {0, 0, 50};  // behind the camera
    j["output"] = {{"image", "out/composite.png"}};
    const LoadedScene s = load_scene(parse_scene_file(fx.write(j)));
    const RenderResult r = render_scene(s);
    write_outputs(s, r);
    const ImageFile in = read_image_file(fx.dir.file("photo.png"));
    const ImageFile out = read_image_file(fx.dir.file("out/composite.png"));
    ASSERT_EQ(in.stored.data.size(), out.stored.data.size());
    EXPECT_EQ(in.stored.data, out.stored.data) << "variant " << variant;
  }
}

TEST(SceneFile, CameraFromPointsErrorsCarryTheJsonPath) {
  SceneFixture fx;
  fx.dir.write("points.json", R"([{"uv": [1, 2], "xyz": [0, 0, 0]}, {"uv": [5, 2], "xyz": [1, 0, 0]}])");
  auto j = fx.scene;
  j["camera"] = {{"points", "points.json"}};
  expect_error(fx, j, ":$.camera.points", "2 control point(s): calibration needs at least 5");
  j["camera"] = {{"points", "points.json"}, {"model", "f+x"}};
  expect_error(fx, j, ":$.camera.model", "expected \"auto\"");
}

}  // namespace
}  // namespace insitu
