// insitu studio (issue 18): the server over a copy of the demo scene, asked as the page asks it,
// and the pieces it is made of: the file guard, the points store, corner snapping and the overlay.
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <filesystem>
#include <opencv2/imgcodecs.hpp>
#include <thread>

#include "calib/control_points.h"
#include "core/camera.h"
#include <fmt/format.h>
#include "cli_util.h"
#include "core/json_reader.h"
#include "studio/corner_snap.h"
#include "studio/file_under.h"
#include "studio/overlay_lines.h"
#include "studio/studio_server.h"
#include "test_util.h"
#include "studio_fixture.h"

namespace insitu {
namespace {

using test::get_json;
using test::StudioFixture;
using test::TempDir;
namespace fs = std::filesystem;

json five_points() {
  return json::parse(R"([
    {"name": "a", "uv": [227.0, 225.8], "xyz": [-2.5, 0.0, -3.0]},
    {"name": "b", "uv": [216.2, 12.4], "xyz": [-2.5, 2.6, -3.0]},
    {"name": "c", "uv": [180.4, 161.7], "xyz": [-2.5, 0.9, -2.2]},
    {"name": "d", "uv": [55.9, 176.3], "xyz": [-2.5, 0.9, -0.6]},
    {"name": "e", "uv": [400.0, 300.0], "xyz": [1.0, 0.0, -1.0]}])");
}

TEST(Studio, ServesThePageThePhotoAndTheState) {
  TempDir dir;
  StudioFixture studio(dir);
  auto c = studio.client();
  const auto page = c.Get("/");
  ASSERT_TRUE(page);
  EXPECT_EQ(page->status, 200);
  EXPECT_NE(page->body.find("<title>insitu studio</title>"), std::string::npos);
  for (const char* script : {"/studio.js", "/points.js", "/shots.js", "/studio.css"})
    EXPECT_EQ(c.Get(script)->status, 200) << script;
  EXPECT_NE(c.Get("/points.js")->body.find("/api/calibrate"), std::string::npos);
  const json state = get_json(c, "/api/state");
  EXPECT_EQ(state["photo"]["width"], 640);
  EXPECT_EQ(state["photo"]["height"], 480);
  EXPECT_EQ(state["points_file"], "points.json");
  EXPECT_EQ(state["points"].size(), read_control_points((studio.folder() / "points.json").string(), false, 480).size());
  EXPECT_EQ(state["version"].get<std::string>().size(), 16u);
  const auto png = c.Get("/api/photo.png");
  const cv::Mat photo = cv::imdecode(std::vector<uchar>(png->body.begin(), png->body.end()), cv::IMREAD_COLOR);
  EXPECT_EQ(photo.cols, 640);
  EXPECT_EQ(photo.rows, 480);
  // The photo as it is: its 8-bit values through sRGB decoding and encoding come back unchanged.
  EXPECT_EQ(cv::norm(photo, cv::imread((studio.folder() / "photo.jpg").string()), cv::NORM_INF), 0.0);
}

TEST(Studio, ServesOnlyFilesUnderTheScenesFolder) {
  TempDir dir;
  StudioFixture studio(dir);
  dir.write("secret.txt", "not for the page");
  fs::create_symlink(dir.path() / "secret.txt", studio.folder() / "link.txt");
  fs::create_directory_symlink(dir.path(), studio.folder() / "up");
  auto c = studio.client();
  const auto ok = c.Get("/files/scene.json");
  ASSERT_TRUE(ok);
  EXPECT_EQ(ok->status, 200);
  EXPECT_EQ(ok->body, test::slurp((studio.folder() / "scene.json").string()));
  for (const char* path : {"/files/../secret.txt", "/files/%2e%2e/secret.txt", "/files/%2E%2E%2Fsecret.txt",
                           "/files/shots/../../secret.txt", "/files/shots/%2e%2e/%2e%2e/secret.txt", "/files/link.txt",
                           "/files/up/secret.txt", "/files//etc/passwd", "/files/%2fetc%2fpasswd",
                           "/files/..%5csecret.txt", "/files/missing.png", "/files/shots", "/../secret.txt"}) {
    const auto r = c.Get(path);
    ASSERT_TRUE(r) << path;
    EXPECT_NE(r->status, 200) << path;
    EXPECT_EQ(r->body.find("not for the page"), std::string::npos) << path;
  }
}

TEST(Studio, FileUnderRefusesEveryWayOut) {
  TempDir dir;
  dir.write("root/a/b.txt", "b");
  dir.write("outside.txt", "o");
  fs::create_symlink(dir.path() / "outside.txt", dir.path() / "root/out.txt");
  fs::create_symlink("a/b.txt", dir.path() / "root/in.txt");
  const fs::path root = dir.path() / "root";
  EXPECT_TRUE(file_under(root, "a/b.txt"));
  EXPECT_TRUE(file_under(root, "in.txt"));  // a symlink that stays inside is fine
  EXPECT_TRUE(file_under(root, "./a/b.txt"));
  for (const char* bad :
       {"", "../outside.txt", "a/../../outside.txt", "out.txt", "a", "/etc/passwd", "a\\b.txt", "a/../a/b.txt"})
    EXPECT_FALSE(file_under(root, bad)) << bad;
  EXPECT_FALSE(file_under(root, std::string("a/b.txt\0x", 9)));
  dir.write("rootkit/x.txt", "x");  // "root" is a prefix of "rootkit" as text, not as a folder
  EXPECT_FALSE(file_under(root, "../rootkit/x.txt"));
}

TEST(Studio, SavesPointsAtomicallyAndTheCliReadsThem) {
  TempDir dir;
  StudioFixture studio(dir, "[]\n");
  auto c = studio.client();
  const json state = get_json(c, "/api/state");
  EXPECT_TRUE(state["points"].empty());
  const json points = five_points();
  const auto r =
      c.Put("/api/points", json{{"version", state["version"]}, {"points", points}}.dump(), "application/json");
  ASSERT_TRUE(r);
  ASSERT_EQ(r->status, 200) << r->body;
  const auto read = read_control_points((studio.folder() / "points.json").string(), false, 480);
  ASSERT_EQ(read.size(), 5u);
  for (std::size_t i = 0; i < 5; ++i) {
    EXPECT_EQ(read[i].name, points[i]["name"]);
    EXPECT_EQ(read[i].uv_px.x(), points[i]["uv"][0].get<double>());
    EXPECT_EQ(read[i].p_world.z(), points[i]["xyz"][2].get<double>());
  }
  EXPECT_EQ(json::parse(r->body)["version"], get_json(c, "/api/state")["version"]);
  for (const auto& e : fs::directory_iterator(studio.folder()))
    EXPECT_EQ(e.path().filename().string().find(".tmp"), std::string::npos) << e.path();
}

TEST(Studio, TwoTabsCannotOverwriteEachOther) {
  TempDir dir;
  StudioFixture studio(dir, "[]\n");
  const std::string version = get_json(studio.client(), "/api/state")["version"];
  // Eight tabs save different points, all edited from the same version, at once: one wins, every
  // other hears of the conflict, and the file holds the winner's points whole.
  std::atomic<int> saved{0}, conflicts{0}, winner{-1};
  std::vector<std::thread> tabs;
  for (int t = 0; t < 8; ++t)
    tabs.emplace_back([&, t] {
      json points = five_points();
      points[0]["name"] = "tab " + std::to_string(t);
      auto c = studio.client();
      const auto r = c.Put("/api/points", json{{"version", version}, {"points", points}}.dump(), "application/json");
      if (r && r->status == 200) ++saved, winner = t;
      if (r && r->status == 409) ++conflicts;
    });
  for (auto& t : tabs) t.join();
  EXPECT_EQ(saved, 1);
  EXPECT_EQ(conflicts, 7);
  const auto read = read_control_points((studio.folder() / "points.json").string(), false, 480);
  ASSERT_EQ(read.size(), 5u);
  EXPECT_EQ(read[0].name, "tab " + std::to_string(winner));
}

TEST(Studio, RefusesOversizedAndInvalidPointsWithoutWriting) {
  TempDir dir;
  StudioFixture studio(dir, "[]\n");
  auto c = studio.client();
  const std::string version = get_json(c, "/api/state")["version"];
  const std::string before = test::slurp((studio.folder() / "points.json").string());
  const auto big = c.Put("/api/points", std::string(2 << 20, ' ') + "[]", "application/json");
  ASSERT_TRUE(big);
  EXPECT_EQ(big->status, 413);
  json points = five_points();
  points[1].erase("xyz");
  const auto bad = c.Put("/api/points", json{{"version", version}, {"points", points}}.dump(), "application/json");
  ASSERT_EQ(bad->status, 400);
  const json error = json::parse(bad->body);
  EXPECT_NE(error["where"].get<std::string>().find("$[1]"), std::string::npos) << error;
  EXPECT_NE(error["error"].get<std::string>().find("points.json"), std::string::npos) << error;
  EXPECT_EQ(c.Put("/api/points", "{not json", "application/json")->status, 400);
  EXPECT_EQ(test::slurp((studio.folder() / "points.json").string()), before);
}

TEST(Studio, CalibrationShowsTheDemosModelAndCamera) {
  TempDir dir;
  StudioFixture studio(dir);
  auto c = studio.client();
  const json state = get_json(c, "/api/state");
  const auto r =
      c.Post("/api/calibrate", json{{"points", state["points"]}, {"model", "auto"}}.dump(), "application/json");
  ASSERT_EQ(r->status, 200) << r->body;
  const json view = json::parse(r->body);
  // The demo's photo was made by a camera with its principal point at the centre and square
  // pixels (tools/make_demo.cpp), hfov 62°: auto keeps the model "f" and finds that camera.
  EXPECT_EQ(view["model"], "f");
  const double hfov = view["camera"]["hfov_deg"], sigma = view["camera"]["calibration"]["stddev"]["hfov_deg"];
  EXPECT_NEAR(hfov, 62.0, 3 * sigma);
  EXPECT_EQ(view["points"].size(), state["points"].size());
  EXPECT_EQ(view["at_objects"]["objects"].size(), 3u);
  // The room box's back-left floor corner (−2.5, 0, −3) is a clicked point: the drawn box meets it
  // within the residual σ's few pixels.
  double nearest = HUGE_VAL;
  for (const json& line : view["lines"])
    if (line["kind"] == "box")
      for (const char* end : {"a", "b"})
        nearest = std::min(nearest, std::hypot(line[end][0].get<double>() - 227.0, line[end][1].get<double>() - 225.8));
  EXPECT_LT(nearest, 4 * view["sigma_px"].get<double>() + 1);
  // Four points: the library's own message, with the points file as its place.
  json four = five_points();
  four.erase(4);
  const auto few = c.Post("/api/calibrate", json{{"points", four}}.dump(), "application/json");
  ASSERT_EQ(few->status, 400);
  const json error = json::parse(few->body);
  EXPECT_NE(error["error"].get<std::string>().find("points.json: 4 control point(s): calibration needs at least 5"),
            std::string::npos)
      << error;
}

TEST(Studio, ListensOnTheLoopbackOnly) {
  TempDir dir;
  StudioFixture studio(dir);
  // /proc/net/tcp lists each socket as local address:port in hex; a listening socket is state 0A.
  std::ifstream tcp("/proc/net/tcp");
  if (!tcp) GTEST_SKIP() << "no /proc/net/tcp here";
  const std::string local = fmt::format("0100007F:{:04X}", studio.port());
  bool found = false;
  for (std::string line; std::getline(tcp, line);)
    if (line.find(fmt::format(":{:04X} ", studio.port())) != std::string::npos &&
        line.find(" 0A ") != std::string::npos) {
      found = true;
      EXPECT_NE(line.find(local), std::string::npos) << line;
    }
  EXPECT_TRUE(found);
}

// A scene whose camera is not a "points" camera in JSON (eye and look here; fSpy and camera files
// take the same path) opens: its points panel says why it edits nothing, every points route
// answers 409 naming the scene's camera once, and the shots and references panels work.
TEST(Studio, OpensASceneWhoseCameraIsNotFromPoints) {
  TempDir dir;
  fs::copy(fs::path(test::source_dir()) / "scenes/demo", dir.path() / "demo", fs::copy_options::recursive);
  json scene = read_json_file(dir.file("demo/scene.json"));
  scene["camera"] = {{"eye", {1, 1, 1}}, {"look", {0, 0, 0}}, {"hfov_deg", 60}};
  std::ofstream(dir.file("demo/scene.json")) << scene.dump();
  const std::string points_before = test::slurp(dir.file("demo/points.json"));
  StudioServer server(StudioOptions{dir.file("demo/scene.json"), 0});
  const int port = server.bind();
  std::thread serving([&] { server.run(); });
  httplib::Client c("127.0.0.1", port);
  c.set_default_headers(
      {{"Authorization", "token " + server.token()}, {"Origin", "http://127.0.0.1:" + std::to_string(port)}});
  c.set_read_timeout(300, 0);
  const json state = test::get_json(c, "/api/state");
  EXPECT_TRUE(state["points_file"].is_null()) << state.dump();
  ASSERT_TRUE(state["points_refusal"].is_string()) << state.dump();
  EXPECT_NE(state["points_refusal"].get<std::string>().find("eye and look"), std::string::npos) << state.dump();
  for (const auto& [method, path] : {std::pair{"PUT", "/api/points"}, std::pair{"POST", "/api/calibrate"}}) {
    const auto r = std::string(method) == "PUT" ? c.Put(path, R"({"version": "", "points": []})", "application/json")
                                                : c.Post(path, R"({"points": []})", "application/json");
    ASSERT_TRUE(r) << path;
    EXPECT_EQ(r->status, 409) << path << ": " << r->body;
    const std::string error = json::parse(r->body)["error"];
    EXPECT_EQ(error.rfind(dir.file("demo/scene.json") + ":$.camera: ", 0), 0u) << error;  // named once
    EXPECT_EQ(error.find("scene.json", error.find("scene.json") + 1), std::string::npos) << error;
  }
  EXPECT_EQ(test::get_json(c, "/api/shots")["shots"].size(), 6u);
  EXPECT_TRUE(test::get_json(c, "/api/references")["references"].is_array());
  server.stop();
  serving.join();
  EXPECT_EQ(test::slurp(dir.file("demo/points.json")), points_before);
  const auto run = test::run_insitu(dir, "studio " + dir.file("missing.json"));
  EXPECT_EQ(run.exit_code, 2) << run.err;
  EXPECT_NE(run.err.find("missing.json"), std::string::npos) << run.err;
}

// A checkerboard's cross at a known sub-pixel position, supersampled 8 × 8 per pixel.
cv::Mat checker_corner(const Vec2d& corner_px, int size) {
  cv::Mat img(size, size, CV_32F);
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      float sum = 0;
      for (int j = 0; j < 8; ++j)
        for (int i = 0; i < 8; ++i) {
          const double u = x + (i + 0.5) / 8 - corner_px.x(), v = y + (j + 0.5) / 8 - corner_px.y();
          sum += (u < 0) == (v < 0) ? 0.9f : 0.1f;
        }
      img.at<float>(y, x) = sum / 64;
    }
  return img;
}

TEST(Studio, SnapsAClickToTheCornerItIsNearAndOnlyThere) {
  const Vec2d corner(40.3, 30.7);
  const cv::Mat img = checker_corner(corner, 80);
  for (const Vec2d& click : {Vec2d(42.0, 29.0), Vec2d(38.6, 33.1), Vec2d(40.3, 30.7)}) {
    const CornerSnap s = snap_to_corner(img, click);
    EXPECT_TRUE(s.snapped) << click.transpose();
    // Within a quarter pixel, of clicks up to 2.5 px off. cornerSubPix is biased by the corner's
    // sub-pixel phase on a box-filtered saddle: 0.00, 0.18 and 0.03 px at phases 0, 0.3 and 0.5
    // (measured with cv::cornerSubPix alone, window 5, ε = 1e-5), so a tighter bound would test
    // OpenCV's pixel locking rather than this code.
    EXPECT_LT((s.uv_px - corner).norm(), 0.25) << click.transpose() << " -> " << s.uv_px.transpose();
    EXPECT_LT((s.uv_px - click - s.offset_px).norm(), 1e-12);
  }
  // On an edge (the corner 20 px away along it), in a flat region, at the border: kept as clicked.
  for (const Vec2d& click : {Vec2d(60.0, 30.5), Vec2d(15.0, 15.0), Vec2d(2.0, 2.0), Vec2d(NAN, 3.0)}) {
    const CornerSnap s = snap_to_corner(img, click);
    EXPECT_FALSE(s.snapped) << click.transpose();
    if (click.allFinite()) {
      EXPECT_EQ(s.uv_px, click);
    }
  }
}

TEST(Studio, GridLiesOnThePlaneAtARoundSpacingAtAnyScale) {
  for (const double scale : {1e-3, 1.0, 1e3}) {
    const Vec3d n = Vec3d(0.2, 1.0, -0.3).normalized(), point = Vec3d(1, 2, 3) * scale;
    const auto lines = plane_grid(point, n, Vec3d(4, 0, -2) * scale, 5 * scale);
    ASSERT_GT(lines.size(), 8u);
    for (const Segment3& s : lines) {
      EXPECT_NEAR(n.dot(s.a_world - point), 0, 1e-9 * scale);
      EXPECT_NEAR(n.dot(s.b_world - point), 0, 1e-9 * scale);
    }
    // Parallel neighbours are 1, 2 or 5 × 10^k apart: here 5/4 = 1.25 rounds down to 1 (× scale).
    EXPECT_NEAR((lines[2].a_world - lines[0].a_world).norm(), scale, 1e-9 * scale);
  }
}

TEST(Studio, SegmentsBehindTheCameraAreClippedNotMirrored) {
  const Camera cam = Camera::look_at(Vec3d(0, 0, 0), Vec3d(0, 0, 1), Vec3d(0, 1, 0), 90, 200, 200);
  EXPECT_FALSE(project_segment(cam, {Vec3d(0, 0, -1), Vec3d(1, 0, -2)}));
  // From behind (t = 0) to in front (t = 1) of the camera, crossing its plane at t = 1/3. The image
  // of the front part runs from the front end through the image of t = 0.5 and on: the mirrored
  // projection of the back end would lie on the front end's other side instead.
  const Vec3d back(-1, 0, -1), front(1, 0, 2);
  const auto s = project_segment(cam, {back, front});
  ASSERT_TRUE(s);
  const Vec2d b = cam.project(front), mid = cam.project(0.5 * (back + front));
  EXPECT_LT((s->b_px - b).norm(), 1e-9);
  EXPECT_NEAR((s->a_px - b).normalized().dot((mid - b).normalized()), 1.0, 1e-9);  // the same direction
  EXPECT_GT((s->a_px - b).norm(), (mid - b).norm());                               // and past t = 0.5
  EXPECT_EQ(box_edges(Vec3d::Zero(), Vec3d::Ones()).size(), 12u);
}

}  // namespace
}  // namespace insitu
