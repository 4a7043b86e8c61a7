// Generates the demo scene (scenes/demo): a procedural empty room seen by a camera (the "photo"),
// six 90° shots from where the furniture will stand (8-bit sRGB JPEGs, as a phone gives them),
// control points clicked in the photo (points.json, with ~1 px of click noise), simple procedural
// furniture as OBJ/MTL, and the scene file, whose camera is calibrated from the points.
// The true camera: eye (1.7, 1.45, 2.5), looking at (−0.2, 0.45, −1.2), up +Y, hfov 62°.
//
//   make_demo OUT_DIR
//
// The room is a box 5 m × 2.6 m × 6 m (x, y, z) with a bright window in the −X wall, a door in
// the back wall and a lamp
// under the ceiling. Being convex and empty, it needs no visibility: the radiance of a wall point
// is (albedo/π)·(E_window + E_lamp + E_ambient), with E_window integrated over the window's area,
// E_lamp = L·π(R/d)²·cosθ for the spherical lamp, and a constant E_ambient standing in for the
// interreflections. Photo and shots share one exposure (1/60 s, f/1.8, ISO 100, in their EXIF),
// so the cube comes out in the photo's unit.
#include <cstdio>
#include <filesystem>
#include <fmt/format.h>
#include <fstream>
#include <nlohmann/json.hpp>

#include "interop/blender_camera.h"
#include "core/camera.h"
#include "core/colour.h"
#include "core/image.h"
#include "core/sampler.h"
#include "demo_chair.h"
#include "light/sixshot.h"

namespace {
using namespace insitu;
namespace fs = std::filesystem;

// ---- The room ------------------------------------------------------------------------------

const Vec3f kRoomLo(-2.5f, 0.0f, -3.0f), kRoomHi(2.5f, 2.6f, 3.0f);
// Window in the −X wall: y in [0.9, 2.1], z in [−2.2, −0.6].
const float kWinY0 = 0.9f, kWinY1 = 2.1f, kWinZ0 = -2.2f, kWinZ1 = -0.6f;
const Rgb kWindowRadiance(7.0f, 8.0f, 9.5f);
const Vec3f kLampCentre(1.2f, 2.3f, -1.0f);
const float kLampRadius = 0.12f;
const Rgb kLampRadiance(60.0f, 48.0f, 32.0f);
const Rgb kAmbientIrradiance(1.1f, 1.05f, 1.0f);
// A door in the back (−Z) wall: x in [0.3, 1.2], y in [0, 2.05].
const float kDoorX0 = 0.3f, kDoorX1 = 1.2f, kDoorY1 = 2.05f;
const float kExposure = 0.55f;  // photo value = exposure × radiance

float hash01(std::uint64_t a, std::uint64_t b) { return hash_to_unit(hash4(7, a, b, 0)); }

Rgb albedo_at(const Vec3f& p, int axis, int side) {
  if (axis == 1 && side == 0) {  // floor: wooden planks 0.16 m wide along x, staggered ends
    const int plank = int(std::floor((p.z() + 10.0f) / 0.16f));
    const float offset = hash01(std::uint64_t(plank), 1) * 1.5f;
    const int seg = int(std::floor((p.x() + 10.0f + offset) / 1.5f));
    const float tone = 0.75f + 0.5f * hash01(std::uint64_t(plank), std::uint64_t(seg));
    const float fz = (p.z() + 10.0f) / 0.16f - float(plank);
    const float fx = (p.x() + 10.0f + offset) / 1.5f - float(seg);
    const float grain = 0.93f + 0.07f * std::sin(60.0f * p.x() + 9.0f * std::sin(3.0f * p.z() + float(plank)));
    Rgb wood = Rgb(0.42f, 0.26f, 0.14f) * tone * grain;
    if (fz < 0.03f || fz > 0.97f || fx < 0.004f) wood *= 0.45f;  // gaps between planks
    return wood;
  }
  if (axis == 1 && side == 1) return Rgb(0.85f, 0.85f, 0.84f);  // ceiling
  if (axis == 2 && side == 0 && p.x() > kDoorX0 - 0.06f && p.x() < kDoorX1 + 0.06f && p.y() < kDoorY1 + 0.06f) {
    // A door in the back wall, with a white frame 6 cm wide.
    if (p.x() < kDoorX0 || p.x() > kDoorX1 || p.y() > kDoorY1) return Rgb(0.85f, 0.85f, 0.83f);
    return Rgb(0.30f, 0.19f, 0.11f);
  }
  if (p.y() < 0.1f) return Rgb(0.88f, 0.88f, 0.86f);  // skirting board
  return Rgb(0.72f, 0.68f, 0.60f);                    // warm off-white walls
}

Vec3f lamp_irradiance_dir(const Vec3f& p) { return kLampCentre - p; }

Rgb irradiance(const Vec3f& p, const Vec3f& n) {
  Rgb e = kAmbientIrradiance;
  // Window: E = Σ L cosθ_p cosθ_w / r² ΔA over an 8×8 grid of the window (normal +X).
  const int k = 8;
  const float dA = (kWinY1 - kWinY0) * (kWinZ1 - kWinZ0) / float(k * k);
  for (int a = 0; a < k; ++a)
    for (int b = 0; b < k; ++b) {
      const Vec3f q(kRoomLo.x(), kWinY0 + (float(a) + 0.5f) * (kWinY1 - kWinY0) / float(k),
                    kWinZ0 + (float(b) + 0.5f) * (kWinZ1 - kWinZ0) / float(k));
      const Vec3f d = q - p;
      const float r2 = d.squaredNorm();
      const float cos_p = n.dot(d) / std::sqrt(r2), cos_w = -d.x() / std::sqrt(r2);
      if (cos_p > 0 && cos_w > 0) e += kWindowRadiance * (cos_p * cos_w * dA / r2);
    }
  // Lamp sphere: E = L π (R/d)² cosθ.
  const Vec3f d = lamp_irradiance_dir(p);
  const float dist = d.norm(), cos_p = n.dot(d) / dist;
  if (cos_p > 0) e += kLampRadiance * (kPiF * (kLampRadius / dist) * (kLampRadius / dist) * cos_p);
  return e;
}

// Radiance seen along a ray from inside the room.
Rgb room_radiance(const Vec3f& o, const Vec3f& dir) {
  // The lamp first (it hangs inside the room).
  const Vec3f oc = o - kLampCentre;
  const float b = oc.dot(dir), c = oc.squaredNorm() - kLampRadius * kLampRadius;
  if (b * b - c > 0 && -b - std::sqrt(b * b - c) > 0) return kLampRadiance;
  // Exit point of the box: the nearest of the three slabs the ray leaves through.
  float t_exit = std::numeric_limits<float>::infinity();
  int axis = 0, side = 0;
  for (int k = 0; k < 3; ++k) {
    if (dir[k] == 0) continue;
    const float t = ((dir[k] > 0 ? kRoomHi[k] : kRoomLo[k]) - o[k]) / dir[k];
    if (t < t_exit) {
      t_exit = t;
      axis = k;
      side = dir[k] > 0 ? 1 : 0;
    }
  }
  const Vec3f p = o + t_exit * dir;
  if (axis == 0 && side == 0 && p.y() > kWinY0 && p.y() < kWinY1 && p.z() > kWinZ0 && p.z() < kWinZ1) {
    // The window: sky with mullions.
    const bool mullion = std::abs(p.z() - 0.5f * (kWinZ0 + kWinZ1)) < 0.025f || std::abs(p.y() - 1.5f) < 0.025f;
    return mullion ? Rgb(0.9f, 0.9f, 0.9f) * 0.3f : kWindowRadiance;
  }
  Vec3f n = Vec3f::Zero();
  n[axis] = side == 1 ? -1.0f : 1.0f;
  return albedo_at(p, axis, side) / kPiF * irradiance(p, n);
}

Image encode_srgb(const Image& linear) {
  Image out = linear;
  for (float& v : out.data) v = linear_to_srgb(v * kExposure);
  return out;
}

// ---- The furniture -------------------------------------------------------------------------

struct ObjWriter {
  std::string text;
  int nv = 0, nt = 0, nn = 0;
  void box(const Vec3f& lo, const Vec3f& hi, const char* material) {
    text += fmt::format("usemtl {}\n", material);
    // Six quads, counter-clockwise seen from outside, with per-face normals and UVs in metres.
    static const int faces[6][4][3] = {
        {{1, 0, 0}, {1, 1, 0}, {1, 1, 1}, {1, 0, 1}}, {{0, 0, 1}, {0, 1, 1}, {0, 1, 0}, {0, 0, 0}},
        {{0, 1, 0}, {0, 1, 1}, {1, 1, 1}, {1, 1, 0}}, {{0, 0, 0}, {1, 0, 0}, {1, 0, 1}, {0, 0, 1}},
        {{0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}}, {{1, 0, 0}, {0, 0, 0}, {0, 1, 0}, {1, 1, 0}}};
    static const float normals[6][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    for (int f = 0; f < 6; ++f) {
      text += fmt::format("vn {} {} {}\n", normals[f][0], normals[f][1], normals[f][2]);
      ++nn;
      for (int c = 0; c < 4; ++c) {
        const Vec3f p(faces[f][c][0] ? hi.x() : lo.x(), faces[f][c][1] ? hi.y() : lo.y(),
                      faces[f][c][2] ? hi.z() : lo.z());
        text += fmt::format("v {:.4f} {:.4f} {:.4f}\n", p.x(), p.y(), p.z());
        const int a = f / 2;  // UVs: the two coordinates other than the face's axis
        text += fmt::format("vt {:.4f} {:.4f}\n", p[(a + 1) % 3], p[(a + 2) % 3]);
      }
      text += fmt::format("f {}/{}/{} {}/{}/{} {}/{}/{} {}/{}/{}\n", nv + 1, nt + 1, nn, nv + 2, nt + 2, nn, nv + 3,
                          nt + 3, nn, nv + 4, nt + 4, nn);
      nv += 4;
      nt += 4;
    }
  }
  void sphere(const Vec3f& centre, float r, int nu, int nvv, const char* material) {
    text += fmt::format("usemtl {}\n", material);
    const int base = nv;
    for (int j = 0; j <= nvv; ++j)
      for (int i = 0; i <= nu; ++i) {
        const float th = kPiF * float(j) / float(nvv), ph = 2 * kPiF * float(i) / float(nu);
        const Vec3f n(std::sin(th) * std::cos(ph), std::cos(th), -std::sin(th) * std::sin(ph));
        const Vec3f p = centre + r * n;
        text += fmt::format("v {:.5f} {:.5f} {:.5f}\nvn {:.5f} {:.5f} {:.5f}\nvt {:.5f} {:.5f}\n", p.x(), p.y(), p.z(),
                            n.x(), n.y(), n.z(), float(i) / float(nu), 1 - float(j) / float(nvv));
        ++nv;
        ++nn;
        ++nt;
      }
    auto id = [&](int i, int j) { return base + j * (nu + 1) + i + 1; };
    for (int j = 0; j < nvv; ++j)
      for (int i = 0; i < nu; ++i) {
        const int a = id(i, j), b = id(i, j + 1), c = id(i + 1, j + 1), d = id(i + 1, j);
        if (j > 0) text += fmt::format("f {0}/{0}/{0} {1}/{1}/{1} {2}/{2}/{2}\n", a, b, d);
        if (j < nvv - 1) text += fmt::format("f {0}/{0}/{0} {1}/{1}/{1} {2}/{2}/{2}\n", d, b, c);
      }
  }
};

void write_text(const fs::path& p, const std::string& text) {
  std::ofstream out(p);
  out << text;
  if (!out) throw std::runtime_error("cannot write " + p.string());
}

void write_furniture(const fs::path& dir) {
  {  // Table: 1.2 × 0.7 top at 0.75 m with a wood texture, four legs; origin at the floor centre.
    ObjWriter w;
    w.text = "# insitu demo: table (generated by make_demo)\nmtllib table.mtl\no table\n";
    w.box({-0.6f, 0.71f, -0.35f}, {0.6f, 0.75f, 0.35f}, "oak");
    for (float sx : {-1.0f, 1.0f})
      for (float sz : {-1.0f, 1.0f})
        w.box({sx * 0.52f - 0.025f, 0.0f, sz * 0.28f - 0.025f}, {sx * 0.52f + 0.025f, 0.71f, sz * 0.28f + 0.025f},
              "steel");
    write_text(dir / "table.obj", w.text);
    write_text(dir / "table.mtl",
               "newmtl oak\nKd 1 1 1\nmap_Kd oak.png\n\nnewmtl steel\nKd 0.08 0.08 0.09\nKs 0.5 0.5 0.5\nNs 200\n");
    // Oak texture, 0.5 m per repeat along u: grain stripes with some variation.
    Image tex(128, 128, 3);
    for (int y = 0; y < 128; ++y)
      for (int x = 0; x < 128; ++x) {
        const float u = float(x) / 128.0f, v = float(y) / 128.0f;
        const float ring = 0.5f + 0.5f * std::sin(2 * kPiF * (6.0f * v + 0.4f * std::sin(2 * kPiF * u * 2)));
        const Rgb c = Rgb(0.62f, 0.42f, 0.22f) * (0.8f + 0.25f * ring);
        for (int k = 0; k < 3; ++k) tex.at(x, y)[k] = linear_to_srgb(c[k]);
      }
    write_image((dir / "oak.png").string(), tex);
  }
  {  // Sofa: seat, back and arms; 2.0 m wide, back toward −z.
    ObjWriter w;
    w.text = "# insitu demo: sofa (generated by make_demo)\nmtllib sofa.mtl\no sofa\n";
    w.box({-1.0f, 0.08f, -0.45f}, {1.0f, 0.42f, 0.45f}, "fabric");
    w.box({-1.0f, 0.42f, -0.45f}, {1.0f, 0.85f, -0.25f}, "fabric");
    w.box({-1.0f, 0.42f, -0.25f}, {-0.82f, 0.62f, 0.45f}, "fabric");
    w.box({0.82f, 0.42f, -0.25f}, {1.0f, 0.62f, 0.45f}, "fabric");
    w.box({-0.8f, 0.42f, -0.25f}, {-0.01f, 0.5f, 0.42f}, "cushion");
    w.box({0.01f, 0.42f, -0.25f}, {0.8f, 0.5f, 0.42f}, "cushion");
    for (float sx : {-0.95f, 0.95f})
      for (float sz : {-0.4f, 0.4f}) w.box({sx - 0.03f, 0.0f, sz - 0.03f}, {sx + 0.03f, 0.08f, sz + 0.03f}, "feet");
    write_text(dir / "sofa.obj", w.text);
    write_text(
        dir / "sofa.mtl",
        "newmtl fabric\nKd 0.16 0.24 0.38\n\nnewmtl cushion\nKd 0.20 0.29 0.44\n\nnewmtl feet\nKd 0.05 0.04 0.03\n");
  }
  {  // Ball: a smooth sphere of radius 0.2 m resting on the floor (origin at its bottom).
    ObjWriter w;
    w.text = "# insitu demo: ball (generated by make_demo)\nmtllib ball.mtl\no ball\n";
    w.sphere({0.0f, 0.2f, 0.0f}, 0.2f, 48, 24, "orange");
    write_text(dir / "ball.obj", w.text);
    write_text(dir / "ball.mtl", "newmtl orange\nKd 0.75 0.28 0.06\n");
  }
}

// The photo, 640 × 480 with 2 × 2 samples per pixel, written with the EXIF exposure of a phone.
void write_photo(const fs::path& out, const Camera& cam, const Exposure& exif) {
  Image photo(cam.width, cam.height, 3);
  for (int y = 0; y < cam.height; ++y)
    for (int x = 0; x < cam.width; ++x) {
      Rgb sum = Rgb::Zero();
      for (int s = 0; s < 4; ++s) {
        const Ray r = cam.ray({x + 0.25 + 0.5 * (s % 2), y + 0.25 + 0.5 * (s / 2)});
        sum += room_radiance(r.origin, r.dir);
      }
      photo.set_rgb(x, y, sum / 4.0f);
    }
  write_image((out / "photo.jpg").string(), encode_srgb(photo), &exif);
}

// Six 90° shots from where the furniture stands, 256 × 256 (rendered at 768² and shrunk), each
// as three exposure brackets four stops apart (EXIF 1/960 s, 1/60 s, 1/4 s), so that the window
// and the lamp are recorded without clipping in the shortest one.
void write_shots(const fs::path& out, const Vec3f& shot_origin, const Exposure& exif) {
  const int faced = kNegZ;
  const char* names[6] = {"east", "west", "ceiling", "floor", "south", "north"};
  const double bracket_factor[3] = {1.0 / 16, 1.0, 16.0};
  const char* bracket_suffix[3] = {"_short", "", "_long"};
  for (int f = 0; f < 6; ++f) {
    auto radiance = [&](const Vec3f& d) { return room_radiance(shot_origin, d); };
    const Image shot = resize(render_shot(radiance, f, faced, 90.0, 768, 768), 256, 256);
    for (int b = 0; b < 3; ++b) {
      Image exposed = shot;
      for (float& v : exposed.data) v *= float(bracket_factor[b]);
      Exposure e = exif;
      e.time_s = *exif.time_s * bracket_factor[b];
      write_image((out / "shots" / (std::string(names[f]) + bracket_suffix[b] + ".jpg")).string(), encode_srgb(exposed),
                  &e);
    }
  }
}

// The corner where the end of the plank under (x_m, z_m) meets its back edge (albedo_at's floor):
// the middle of the end gap, nearest x_m, on the gap line between two planks. A user finds it with
// a tape from the back and left walls; the floor points put the span of the clicked points under
// the furniture, so the camera is not extrapolated there (calibration's uncertainty at objects).
Vec3d plank_end_corner(double x_m, double z_m) {
  const int plank = int(std::floor((z_m + 10.0) / 0.16));
  const double offset = double(hash01(std::uint64_t(plank), 1)) * 1.5;
  const double seg = std::round((x_m + 10.0 + offset) / 1.5);
  const double x_end_m = seg * 1.5 - offset - 10.0 + 0.5 * 0.004 * 1.5;
  return {std::round(x_end_m * 1000) / 1000, 0.0, std::round((plank * 0.16 - 10.0) * 1000) / 1000};  // to the mm
}

// Control points: room corners and window corners a user would click, and five plank ends
// measured on the floor around the furniture, projected by the true camera, with about 1 px of
// click noise (σ = 0.7 px per axis), rounded to 0.1 px.
void write_points(const fs::path& out, const Camera& cam) {
  const std::vector<std::pair<std::string, Vec3d>> landmarks = {
      {"floor corner, back left", {-2.5, 0.0, -3.0}},
      {"floor corner, back right", {2.5, 0.0, -3.0}},
      {"ceiling corner, back left", {-2.5, 2.6, -3.0}},
      {"ceiling corner, back right", {2.5, 2.6, -3.0}},
      {"window, bottom back", {-2.5, 0.9, -2.2}},
      {"window, bottom front", {-2.5, 0.9, -0.6}},
      {"window, top back", {-2.5, 2.1, -2.2}},
      {"window, top front", {-2.5, 2.1, -0.6}},
      {"window, mullion cross", {-2.5, 1.5, -1.4}},
      {"skirting top, back left", {-2.5, 0.1, -3.0}},
      {"door, bottom left", {0.3, 0.0, -3.0}},
      {"door, bottom right", {1.2, 0.0, -3.0}},
      {"door, top left", {0.3, 2.05, -3.0}},
      {"door, top right", {1.2, 2.05, -3.0}},
      {"plank end, front left", plank_end_corner(-0.5, 0.6)},
      {"plank end, front", plank_end_corner(0.0, 0.9)},
      {"plank end, by the ball", plank_end_corner(1.0, 0.6)},
      {"plank end, right of the sofa", plank_end_corner(1.9, -1.6)},
      {"plank end, behind the sofa", plank_end_corner(2.0, -2.4)},
  };
  nlohmann::ordered_json points = nlohmann::ordered_json::array();
  std::uint64_t k = 0;
  for (const auto& [name, p] : landmarks) {
    double depth = 0;
    const Vec2d uv = cam.project(p, &depth);
    if (depth <= 0 || uv.x() < 0 || uv.y() < 0 || uv.x() > cam.width || uv.y() > cam.height) continue;
    // Box–Muller from the counter-based hash: two Gaussian numbers per point.
    const double u1 = std::max(1e-12, double(hash_to_unit(hash4(99, k, 0, 0)))), u2 = hash_to_unit(hash4(99, k, 0, 1));
    ++k;
    const double r = 0.7 * std::sqrt(-2 * std::log(u1));
    const Vec2d noisy = uv + Vec2d(r * std::cos(2 * kPi * u2), r * std::sin(2 * kPi * u2));
    points.push_back({{"name", name},
                      {"uv", {std::round(noisy.x() * 10) / 10, std::round(noisy.y() * 10) / 10}},
                      {"xyz", {p.x(), p.y(), p.z()}}});
  }
  write_text(out / "points.json", points.dump(2) + "\n");
}

void write_scene(const fs::path& out, const Vec3f& shot_origin) {
  auto r3 = [](float v) { return std::round(double(v) * 1000) / 1000; };  // float constants, printed cleanly
  auto brackets = [](const std::string& name) {
    return nlohmann::ordered_json::array(
        {"shots/" + name + "_short.jpg", "shots/" + name + ".jpg", "shots/" + name + "_long.jpg"});
  };
  nlohmann::ordered_json scene = {
      {"photo", "photo.jpg"},
      {"camera", {{"points", "points.json"}}},
      {"environment",
       {{"shots",
         {{"+x", brackets("east")},
          {"-x", brackets("west")},
          {"+z", brackets("south")},
          {"-z", brackets("north")},
          {"up", brackets("ceiling")},
          {"down", brackets("floor")},
          {"faced", "-z"}}},
        {"room_box",
         {{"min", {r3(kRoomLo.x()), r3(kRoomLo.y()), r3(kRoomLo.z())}},
          {"max", {r3(kRoomHi.x()), r3(kRoomHi.y()), r3(kRoomHi.z())}},
          {"capture", {r3(shot_origin.x()), r3(shot_origin.y()), r3(shot_origin.z())}}}}}},
      {"local_scene", {{{"plane", {{"point", {0, 0, 0}}, {"normal", {0, 1, 0}}}}}}},
      {"objects",
       {{{"mesh", "table.obj"}, {"translate", {-0.2, 0, -1.2}}, {"rotate", 12}},
        {{"mesh", "sofa.obj"}, {"translate", {0.6, 0, -2.35}}, {"rotate", -8}},
        {{"mesh", "ball.obj"}, {"translate", {0.95, 0, -0.2}}}}},
      {"render", {{"integrator", "path"}, {"spp", 144}}},
  };
  write_text(out / "scene.json", scene.dump(2) + "\n");
  // The same scene with the camera from fspy.json instead of the clicked points.
  scene["camera"] = {{"fspy", "fspy.json"}};
  scene["output"] = {{"image", "out/fspy.png"}, {"layers", "out/fspy.layers.exr"}};
  write_text(out / "scene_fspy.json", scene.dump(2) + "\n");
  // The catalogue scene: the glTF armchair and its glass-topped side table (tools/demo_chair.h) in
  // the ball's place, turned toward the camera.
  scene["camera"] = {{"points", "points.json"}};
  scene["objects"][2] = {{"mesh", "chair.glb"}, {"translate", {0.75, 0, -0.1}}, {"rotate", 30}};
  scene["output"] = {{"image", "out/chair.png"}, {"layers", "out/chair.layers.exr"}};
  write_text(out / "scene_chair.json", scene.dump(2) + "\n");
}

// The demo camera as fSpy exports it (calib/fspy.h, read there; this is its inverse): the longer
// side spans [−1, 1], f_rel = fx / (L/2), the camera-to-world matrix in fSpy's Z-up world,
// p_fspy = (x, −z, y) of insitu's (x, y, z), the camera looking down −z with +y up.
void write_fspy(const fs::path& out, const Camera& cam) {
  const double half_long = 0.5 * std::max(cam.width, cam.height), f_rel = cam.fx / half_long;
  const Mat4d M = blender_camera_to_world(cam);
  auto rows = [](const Mat4d& m) {
    nlohmann::ordered_json r = nlohmann::ordered_json::array();
    auto v = [](double x) { return x == 0 ? 0.0 : x; };  // no "-0.0" in the file
    for (int i = 0; i < 4; ++i) r.push_back({v(m(i, 0)), v(m(i, 1)), v(m(i, 2)), v(m(i, 3))});
    return r;
  };
  const nlohmann::ordered_json fspy = {
      {"principalPoint",
       {{"x", (cam.cx - 0.5 * cam.width) / half_long + 0.0}, {"y", (0.5 * cam.height - cam.cy) / half_long + 0.0}}},
      {"viewTransform", {{"rows", rows(M.inverse())}}},
      {"cameraTransform", {{"rows", rows(M)}}},
      {"horizontalFieldOfView", 2 * std::atan(1 / f_rel)},
      {"verticalFieldOfView", 2 * std::atan(0.5 * cam.height / cam.fy)},
      {"relativeFocalLength", f_rel},
      {"imageWidth", cam.width},
      {"imageHeight", cam.height}};
  write_text(out / "fspy.json", fspy.dump(2) + "\n");
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: make_demo OUT_DIR\n");
    return 2;
  }
  const fs::path out(argv[1]);
  fs::create_directories(out / "shots");
  const Vec3d eye(1.7, 1.45, 2.5), look(-0.2, 0.45, -1.2);
  const double hfov_deg = 62.0;
  const Camera cam = Camera::look_at(eye, look, Vec3d(0, 1, 0), hfov_deg, 640, 480);
  // One exposure for the photo and the shots, recorded in their EXIF as a phone would.
  Exposure exif;
  exif.time_s = 1.0 / 60;
  exif.f_number = 1.8;
  exif.iso = 100;
  const Vec3f shot_origin(-0.2f, 0.9f, -1.2f);
  write_photo(out, cam, exif);
  write_shots(out, shot_origin, exif);
  write_furniture(out);
  write_demo_chair((out / "chair.glb").string());
  write_points(out, cam);
  write_scene(out, shot_origin);
  write_fspy(out, cam);
  std::printf("demo scene written to %s\n", out.string().c_str());
  return 0;
}
