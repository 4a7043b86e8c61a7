#include "light/sixshot.h"

#include <algorithm>
#include <cassert>
#include <fmt/format.h>
#include <optional>
#include <vector>

#include <tbb/parallel_for.h>

#include "core/error.h"

namespace insitu {

namespace {
Vec3d face_axis(int face) {
  static const Vec3d axes[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  return axes[face];
}
}  // namespace

ShotBasis shot_basis(int face, int faced_face) {
  assert(faced_face == kPosX || faced_face == kNegX || faced_face == kPosZ || faced_face == kNegZ);
  ShotBasis b;
  b.forward = face_axis(face);
  if (face == kPosY)
    b.up = -face_axis(faced_face);
  else if (face == kNegY)
    b.up = face_axis(faced_face);
  else
    b.up = Vec3d(0, 1, 0);
  b.right = b.forward.cross(b.up);
  return b;
}

int shot_face_size(const ShotSet& set, int f) {
  const double scale = 1.0 / std::tan(0.5 * deg_to_rad(set.hfov_deg[std::size_t(f)]));  // tan 45° / tan(hfov/2)
  return std::max(1, int(std::lround(set.shots[std::size_t(f)].width * scale)));
}

int natural_face_size(const ShotSet& set, int max_face_size) {
  int n = max_face_size;
  for (int f = 0; f < 6; ++f) n = std::min(n, shot_face_size(set, f));
  return n;
}

namespace {
// One pixel per texel at the face's centre: width ⌈n tan(hfov/2)⌉. The 1e-9 keeps
// tan 45° = 0.99999999999999989 from rounding n up.
int face_width_px(double hfov_deg, int n) {
  return std::max(1, int(std::ceil(n * std::tan(0.5 * deg_to_rad(hfov_deg)) - 1e-9)));
}
}  // namespace

// Shrunk by area averaging (which keeps its integral) to face_width_px.
Image shrunk_to_face(const Image& shot, double hfov_deg, int n) {
  const int needed_w = face_width_px(hfov_deg, n);
  if (shot.width <= needed_w) return shot;
  const int needed_h = std::max(1, int(std::lround(double(shot.height) * needed_w / shot.width)));
  return resize(shot, needed_w, needed_h, "box");
}

ShotBasis aimed_basis(const ShotSet& set, int s) {
  const ShotBasis b = shot_basis(s, set.faced_face);
  const Mat3d& R = set.aim[std::size_t(s)];
  return {R * b.forward, R * b.up, R * b.right};
}

namespace {

// A shot as the cube's face of n needs it: the shot itself when it is no larger
// (shrunk_to_face), else its own shrunk copy (never a copy of a shot already small enough: six
// shots at a 1024 face are 230 MB with their masks).
class FaceSized {
 public:
  FaceSized(const Image& shot, double hfov_deg, int n) : shot_(&shot) {
    if (shot.width > face_width_px(hfov_deg, n)) own_ = shrunk_to_face(shot, hfov_deg, n);
  }
  const Image& get() const { return own_ ? *own_ : *shot_; }

 private:
  const Image* shot_;
  std::optional<Image> own_;
};

// One shot ready to be sampled: shrunk to at most one pixel per texel, with its aimed axes.
struct PreparedShot {
  FaceSized image;
  std::optional<FaceSized> clipped;  // the shot's clipped degree (0..1) at the same size
  ShotBasis basis;
  double f_px = 0;
};

PreparedShot prepare_shot(const ShotSet& set, const ShotSet* clipped, int s, int n) {
  const double hfov_deg = set.hfov_deg[std::size_t(s)];
  PreparedShot p{FaceSized(set.shots[std::size_t(s)], hfov_deg, n), std::nullopt, aimed_basis(set, s), 0};
  if (clipped) p.clipped.emplace(clipped->shots[std::size_t(s)], hfov_deg, n);
  const double tan_half = std::tan(0.5 * deg_to_rad(hfov_deg));
  p.f_px = 0.5 * p.image.get().width / tan_half;
  return p;
}

// What one shot says about a direction: its radiance, its clipped degree and its blending weight.
struct ShotSample {
  Rgb radiance, clipped;
  double weight = 0;
};

// The feathered weight of a pixel (u, v ∈ [0, 1] across the shot): the tent min(u, 1−u) ·
// min(v, 1−v), 0 on the shot's border and largest at its centre, so that the blend of
// overlapping shots has no seam (the distance-to-border feathering of OpenCV's FeatherBlender,
// separable). A clipped pixel's weight drops to 1/1000 of it, so that where a neighbour did not
// clip, the neighbour's radiance is taken.
std::optional<ShotSample> sample_shot(const PreparedShot& p, const Vec3d& d) {
  const double z = d.dot(p.basis.forward);
  const Image& image = p.image.get();
  const double w = image.width, h = image.height;
  // Pixel position (corner origin) of the direction in the shot.
  const double px = 0.5 * w + p.f_px * d.dot(p.basis.right) / z;
  const double py = 0.5 * h - p.f_px * d.dot(p.basis.up) / z;
  const double tol = 1e-3;
  if (!(z > 0) || px < -tol || px > w + tol || py < -tol || py > h + tol) return std::nullopt;
  const double x = std::clamp(px - 0.5, 0.0, w - 1.0), y = std::clamp(py - 0.5, 0.0, h - 1.0);
  ShotSample s;
  s.radiance = bilinear_rgb(image, x, y);
  s.clipped = p.clipped && p.clipped->get().width > 0 ? bilinear_rgb(p.clipped->get(), x, y) : Rgb::Zero();
  const double u = std::clamp(px / w, 0.0, 1.0), v = std::clamp(py / h, 0.0, 1.0);
  s.weight = std::max(1e-12, std::min(u, 1 - u) * std::min(v, 1 - v)) * (1 - 0.999 * double(s.clipped.maxCoeff()));
  return s;
}

}  // namespace

// Each texel: the shots that see its direction, blended by their weights (sample_shot). One shot
// alone gives its own sample unchanged.
CubeMap assemble_cube(const ShotSet& set, int n, AssemblyInfo* info, const ShotSet* clipped, CubeMap* clipped_cube) {
  std::vector<PreparedShot> shots;
  for (int s = 0; s < 6; ++s) shots.push_back(prepare_shot(set, clipped, s, n));
  CubeMap cube(n), weight(n), clip(n);
  // The face rows in parallel; each row counts the texels each shot reached ([0, 6)) and those
  // any shot covered ([6]), summed in order after.
  std::vector<std::array<long, 7>> row_counts(std::size_t(6) * std::size_t(n));
  tbb::parallel_for(0, 6 * n, [&](int row) {
    const int f = row / n, j = row % n;
    std::array<long, 7>& counts = row_counts[std::size_t(row)];
    counts.fill(0);
    for (int i = 0; i < n; ++i) {
      const Vec3d d = texel_direction(f, i, j, n).cast<double>();
      Rgb sum = Rgb::Zero(), clip_sum = Rgb::Zero(), only = Rgb::Zero(), only_clip = Rgb::Zero();
      double wsum = 0;
      int count = 0;
      for (int s = 0; s < 6; ++s)
        if (const auto smp = sample_shot(shots[std::size_t(s)], d)) {
          ++count, ++counts[std::size_t(s)];
          only = smp->radiance, only_clip = smp->clipped;
          sum += float(smp->weight) * smp->radiance, clip_sum += float(smp->weight) * smp->clipped;
          wsum += smp->weight;
        }
      if (count == 0) continue;
      ++counts[6];
      cube.set_texel(f, i, j, count == 1 ? only : Rgb(sum / float(wsum)));
      clip.set_texel(f, i, j, count == 1 ? only_clip : Rgb(clip_sum / float(wsum)));
      weight.set_texel(f, i, j, Rgb::Ones());
    }
  });
  std::array<long, 6> used{};
  AssemblyInfo local;
  bool holes = false;
  for (int f = 0; f < 6; ++f) {
    long covered = 0;
    for (int j = 0; j < n; ++j) {
      const std::array<long, 7>& counts = row_counts[std::size_t(f) * std::size_t(n) + std::size_t(j)];
      for (int s = 0; s < 6; ++s) used[std::size_t(s)] += counts[std::size_t(s)];
      covered += counts[6];
    }
    local.coverage[std::size_t(f)] = double(covered) / (double(n) * n);
    holes |= covered < long(n) * n;
  }
  for (int s = 0; s < 6; ++s)
    if (used[std::size_t(s)] == 0)
      throw InputError(set.names[std::size_t(s)], fmt::format("the shot covers none of the cube (field of view {}°)",
                                                              set.hfov_deg[std::size_t(s)]));
  cube.update_borders();
  clip.update_borders();
  if (holes) {
    local.covered.resize(std::size_t(6) * std::size_t(n) * std::size_t(n));
    for (int f = 0; f < 6; ++f)
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) local.covered[texel_index(f, i, j, n)] = weight.texel(f, i, j)[0] > 0;
    weight.update_borders();
    fill_uncovered(cube, weight);  // the clip mask is not filled: assemble_cube's comment
  }
  if (clipped_cube) *clipped_cube = std::move(clip);
  if (info) *info = local;
  return cube;
}

namespace {

// visit(face, j) for each row of a cube of n a face, the rows in parallel: each texel of the fill's
// passes depends only on the cube before the pass, so the order does not change a bit.
template <class Visit>
void for_each_row(int n, const Visit& visit) {
  tbb::parallel_for(0, 6 * n, [&](int row) { visit(row / n, row % n); });
}

// A cube half the size: each texel the weighted mean of its 2×2 children (odd sizes: the last
// child row/column counts once more); weights summed.
void pull(const CubeMap& v, const CubeMap& w, CubeMap& v2, CubeMap& w2) {
  const int n = v.size(), m = (n + 1) / 2;
  v2 = CubeMap(m);
  w2 = CubeMap(m);
  for_each_row(m, [&](int f, int j) {
    for (int i = 0; i < m; ++i) {
      Rgb sum = Rgb::Zero();
      float wsum = 0;
      for (int b = 0; b < 2; ++b)
        for (int a = 0; a < 2; ++a) {
          const int ci = std::min(2 * i + a, n - 1), cj = std::min(2 * j + b, n - 1);
          const float wt = w.texel(f, ci, cj)[0];
          sum += wt * v.texel(f, ci, cj);
          wsum += wt;
        }
      v2.set_texel(f, i, j, wsum > 0 ? Rgb(sum / wsum) : Rgb::Zero());
      w2.set_texel(f, i, j, Rgb::Constant(std::min(1.0f, wsum)));
    }
  });
  v2.update_borders();
  w2.update_borders();
}

// Jacobi relaxation of the unknown texels toward the mean of their four neighbours (across face
// edges through the borders), the known ones held fixed.
void relax(CubeMap& v, const CubeMap& w, int iterations) {
  const int n = v.size();
  for (int it = 0; it < iterations; ++it) {
    CubeMap next = v;
    for_each_row(n, [&](int f, int j) {
      for (int i = 0; i < n; ++i) {
        if (w.texel(f, i, j)[0] >= 1.0f) continue;
        const Rgb mean =
            0.25f * (v.texel(f, i - 1, j) + v.texel(f, i + 1, j) + v.texel(f, i, j - 1) + v.texel(f, i, j + 1));
        const float known = w.texel(f, i, j)[0];
        next.set_texel(f, i, j, known * v.texel(f, i, j) + (1 - known) * mean);
      }
    });
    next.update_borders();
    v = std::move(next);
  }
}

}  // namespace

void fill_uncovered(CubeMap& cube, const CubeMap& weight) {
  // Pull: coarser and coarser cubes of weighted means, until every texel is known.
  std::vector<CubeMap> values{cube}, weights{weight};
  while (values.back().size() > 1) {
    bool complete = true;
    const CubeMap& wl = weights.back();
    for (int f = 0; f < 6 && complete; ++f)
      for (int j = 0; j < wl.size() && complete; ++j)
        for (int i = 0; i < wl.size() && complete; ++i) complete = wl.texel(f, i, j)[0] > 0;
    if (complete) break;
    CubeMap v2, w2;
    pull(values.back(), weights.back(), v2, w2);
    values.push_back(std::move(v2));
    weights.push_back(std::move(w2));
  }
  relax(values.back(), weights.back(), 8);
  // Push: unknown texels start from the coarser level, looked up by direction (seamless), and are
  // relaxed; known texels keep their values, partly known ones blend.
  for (int l = int(values.size()) - 2; l >= 0; --l) {
    CubeMap& v = values[std::size_t(l)];
    const CubeMap& w = weights[std::size_t(l)];
    const CubeMap& coarse = values[std::size_t(l) + 1];
    const int n = v.size();
    for_each_row(n, [&](int f, int j) {
      for (int i = 0; i < n; ++i) {
        const float known = w.texel(f, i, j)[0];
        if (known >= 1.0f) continue;
        const Rgb up = coarse.lookup(texel_direction(f, i, j, n));
        v.set_texel(f, i, j, known * v.texel(f, i, j) + (1 - known) * up);
      }
    });
    v.update_borders();
    relax(v, w, 4);
  }
  cube = values.front();
}

}  // namespace insitu
