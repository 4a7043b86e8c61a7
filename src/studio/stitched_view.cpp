#include "studio/stitched_view.h"

#include <algorithm>
#include <cmath>

#include "core/colour.h"
#include "core/error.h"
#include "core/math.h"
#include "light/preview.h"
#include "light/texel_geometry.h"
#include "scene/pipeline.h"
#include "scene/scene_file.h"
#include "studio/preview_png.h"

namespace insitu {

namespace {

constexpr const char* kOutline[6] = {"#e6194b", "#3cb44b", "#4363d8", "#f58231", "#911eb4", "#42d4f4"};

Rgb colour_of(const char* hex) {
  const long v = std::strtol(hex + 1, nullptr, 16);
  return Rgb(float((v >> 16) & 255) / 255.0f, float((v >> 8) & 255) / 255.0f, float(v & 255) / 255.0f);
}

// The direction through pixel (x, y) of the cross at n pixels a face; false off the cross.
bool cross_direction(int x, int y, int n, Vec3d& d) {
  for (const CrossSquare& q : kCrossLayout) {
    if (x / n != q.col || y / n != q.row) continue;
    const ShotBasis b = shot_basis(q.face, kNegZ);
    // render_shot's pixel centres for a 90° view: f_px = n / 2.
    const double xc = (x % n + 0.5 - 0.5 * n) / (0.5 * n), yc = -(y % n + 0.5 - 0.5 * n) / (0.5 * n);
    d = b.forward + xc * b.right + yc * b.up;
    return true;
  }
  return false;
}

// The cross pixel direction d falls in (the square whose view holds it), or false.
bool cross_pixel(const Vec3d& d, int n, int& x, int& y) {
  for (const CrossSquare& q : kCrossLayout) {
    const ShotBasis b = shot_basis(q.face, kNegZ);
    const double z = d.dot(b.forward);
    if (z <= 0) continue;
    const double xc = d.dot(b.right) / z, yc = d.dot(b.up) / z;
    if (std::abs(xc) > 1 || std::abs(yc) > 1) continue;
    x = q.col * n + std::clamp(int(std::floor((xc + 1) * 0.5 * n)), 0, n - 1);
    y = q.row * n + std::clamp(int(std::floor((1 - yc) * 0.5 * n)), 0, n - 1);
    return true;
  }
  return false;
}

// Every direction no shot sees, hatched: a darker magenta on every fourth diagonal.
void hatch_gaps(Image& cross, int n, const std::array<ShotFrame, 6>& frames) {
  for (int y = 0; y < cross.height; ++y)
    for (int x = 0; x < cross.width; ++x) {
      Vec3d d;
      if (!cross_direction(x, y, n, d) || (x + y) % 8 >= 3) continue;
      if (std::none_of(frames.begin(), frames.end(), [&](const ShotFrame& f) { return frame_sees(f, d); }))
        cross.set_rgb(x, y, 0.5f * cross.rgb(x, y) + Rgb(0.45f, 0.0f, 0.45f));
    }
}

// The frame's edge, walked in small steps, each point a 2 × 2 dot of the shot's colour.
void draw_outline(Image& cross, int n, const ShotFrame& f, const Rgb& colour) {
  const int steps = 8 * n;
  for (int e = 0; e < 4; ++e)
    for (int k = 0; k <= steps; ++k) {
      const double t = 2.0 * k / steps - 1;
      const double u = e < 2 ? t : (e == 2 ? -1 : 1), v = e < 2 ? (e == 0 ? -1 : 1) : t;
      const Vec3d d = f.basis.forward + u * f.tan_half_w * f.basis.right + v * f.tan_half_h * f.basis.up;
      int x = 0, y = 0;
      if (!cross_pixel(d, n, x, y)) continue;
      for (int dy = 0; dy < 2; ++dy)
        for (int dx = 0; dx < 2; ++dx)
          if (x + dx < cross.width && y + dy < cross.height) cross.set_rgb(x + dx, y + dy, colour);
    }
}

}  // namespace

std::array<ShotFrame, 6> shot_frames(const EnvironmentSpec& env, const EnvironmentInfo& info) {
  std::array<ShotFrame, 6> frames;
  for (int s = 0; s < 6; ++s) {
    const ShotSpec& shot = env.shots[std::size_t(s)];
    ShotFrame& f = frames[std::size_t(s)];
    if (shot.files.empty()) continue;
    auto [w, h] = read_image_size(shot.files.front());
    if (shot.rotate_deg % 180 != 0) std::swap(w, h);
    const ShotBasis b = shot_basis(s, env.faced_face);
    const Mat3d aim = info.registration ? info.registration->aim[std::size_t(s)] : Mat3d::Identity();
    f.basis = {aim * b.forward, aim * b.up, aim * b.right};
    f.tan_half_w = std::tan(0.5 * deg_to_rad(info.hfov_deg[std::size_t(s)]));
    f.tan_half_h = f.tan_half_w * double(h) / double(std::max(1, w));
    f.present = true;
  }
  return frames;
}

bool frame_sees(const ShotFrame& f, const Vec3d& d) {
  const double z = d.dot(f.basis.forward);
  if (!f.present || z <= 0) return false;
  return std::abs(d.dot(f.basis.right)) <= f.tan_half_w * z && std::abs(d.dot(f.basis.up)) <= f.tan_half_h * z;
}

// Σ ΔΩ over the texels of a 256 face whose centre no frame sees, over 4π (a texel is 0.35°).
double gap_fraction(const std::array<ShotFrame, 6>& frames) {
  const int n = 256;
  const std::vector<double> omega = face_solid_angles(n);
  double gap = 0;
  for (int f = 0; f < 6; ++f)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const Vec3d d = texel_direction(f, i, j, n).cast<double>();
        if (std::none_of(frames.begin(), frames.end(), [&](const ShotFrame& s) { return frame_sees(s, d); }))
          gap += omega[std::size_t(j) * n + std::size_t(i)];
      }
  return gap / (4 * kPi);
}

const char* outline_colour(int s) { return kOutline[std::clamp(s, 0, 5)]; }

CubeMap load_shots_as_rendered(const SceneSpec& spec, Warnings& warnings, EnvironmentInfo& info,
                               std::string& photo_note) {
  photo_note.clear();
  if (spec.environment.room_box) return load_environment(spec.environment, warnings, &info);
  std::optional<PhotoAndCamera> pc;
  try {
    Warnings camera_warnings;  // the calibration panel's to show, not the shots'
    pc = load_photo_and_camera(spec, camera_warnings);
  } catch (const InputError& e) {
    photo_note = e.what();
  }
  return pc ? load_environment(spec.environment, warnings, &info, &pc->photo, &pc->camera)
            : load_environment(spec.environment, warnings, &info);
}

std::string stitched_png(const std::string& scene_path, int face_px) {
  const SceneSpec spec = parse_scene_file(scene_path);
  const EnvironmentSpec& env = spec.environment;
  if (!env.from_shots()) throw InputError(env.where, "this scene has no six shots");
  Warnings warnings;
  EnvironmentInfo info;
  std::string photo_note;
  const CubeMap cube = load_shots_as_rendered(spec, warnings, info, photo_note);
  Image cross = cube_cross_preview(cube, preview_exposure(cube), face_px);
  const std::array<ShotFrame, 6> frames = shot_frames(env, info);
  hatch_gaps(cross, face_px, frames);
  for (int s = 0; s < 6; ++s)
    if (frames[std::size_t(s)].present) draw_outline(cross, face_px, frames[std::size_t(s)], colour_of(kOutline[s]));
  return display_png(cross);
}

}  // namespace insitu
