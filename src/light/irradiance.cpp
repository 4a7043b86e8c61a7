#include "light/irradiance.h"

#include <stdexcept>

#include <tbb/parallel_for.h>

#include <cmath>

#include "core/stop.h"
#include "light/gaussian_irradiance.h"
#include "light/texel_geometry.h"

namespace insitu {

// ---- Reference -------------------------------------------------------------------------------

Rgb irradiance_reference(const CubeMap& radiance, const Vec3d& n) {
  const int N = radiance.size();
  Eigen::Array3d sum = Eigen::Array3d::Zero();
  for (int f = 0; f < 6; ++f)
    for (int j = 0; j < N; ++j)
      for (int i = 0; i < N; ++i) {
        const double w = texel_clamped_cosine_integral(f, i, j, N, n);
        if (w > 0) sum += radiance.texel(f, i, j).cast<double>() * w;
      }
  return sum.cast<float>();
}

// ---- SH9 -----------------------------------------------------------------------------------

std::array<double, 9> sh9_basis(const Vec3d& d) {
  const double x = d.x(), y = d.y(), z = d.z();
  return {0.282095,
          0.488603 * y,
          0.488603 * z,
          0.488603 * x,
          1.092548 * x * y,
          1.092548 * y * z,
          0.315392 * (3 * z * z - 1),
          1.092548 * x * z,
          0.546274 * (x * x - y * y)};
}

Sh9 project_sh9(const CubeMap& radiance) {
  // L_lm = Σ_texels L_i Y_lm(ω_i) ΔΩ_i with the exact solid angle ΔΩ_i.
  const int N = radiance.size();
  std::array<Eigen::Array3d, 9> acc;
  for (auto& a : acc) a.setZero();
  const std::vector<double> d_omega = face_solid_angles(N);
  for (int f = 0; f < 6; ++f)
    for (int j = 0; j < N; ++j)
      for (int i = 0; i < N; ++i) {
        const auto Y = sh9_basis(texel_direction(f, i, j, N).cast<double>());
        const Eigen::Array3d L = radiance.texel(f, i, j).cast<double>() * d_omega[std::size_t(j) * N + i];
        for (int k = 0; k < 9; ++k) acc[std::size_t(k)] += L * Y[std::size_t(k)];
      }
  Sh9 sh;
  for (int k = 0; k < 9; ++k) sh.coeff[std::size_t(k)] = acc[std::size_t(k)].cast<float>();
  return sh;
}

Rgb sh9_irradiance(const Sh9& sh, const Vec3f& n) {
  static const double A[9] = {kPi, 2 * kPi / 3, 2 * kPi / 3, 2 * kPi / 3, kPi / 4, kPi / 4, kPi / 4, kPi / 4, kPi / 4};
  const auto Y = sh9_basis(n.cast<double>());
  Eigen::Array3d e = Eigen::Array3d::Zero();
  for (int k = 0; k < 9; ++k) e += A[k] * Y[std::size_t(k)] * sh.coeff[std::size_t(k)].cast<double>();
  return e.cast<float>();
}

// ---- Exact, accelerated ----------------------------------------------------------------------

namespace {

CubeMap box_reduce(const CubeMap& c, int size) {
  // Area average of factor × factor blocks (size divides c.size()) or OpenImageIO's box filter.
  CubeMap out(size);
  for (int f = 0; f < 6; ++f) out.set_face_image(f, resize(c.face_image(f), size, size, "box"));
  out.update_borders();
  return out;
}

// Per face: for each row j, prefix[j][i] = Σ_{i' < i} L_{i'} ⊗ Φ_{i'} as 9 doubles (rgb × xyz).
struct RowPrefix {
  int n = 0;
  std::vector<double> data;  // 6 faces × n rows × (n + 1) × 9
  const double* at(int f, int j, int i) const { return &data[((std::size_t(f) * n + j) * (n + 1) + i) * 9]; }
  double* at(int f, int j, int i) { return &data[((std::size_t(f) * n + j) * (n + 1) + i) * 9]; }
};

RowPrefix build_prefix(const CubeMap& L) {
  RowPrefix p;
  p.n = L.size();
  const int n = p.n;
  p.data.assign(std::size_t(6) * n * (n + 1) * 9, 0.0);
  tbb::parallel_for(0, 6 * n, [&](int fj) {
    const int f = fj / n, j = fj % n;
    for (int i = 0; i < n; ++i) {
      const Vec3d phi = texel_vector_irradiance(f, i, j, n);
      const Eigen::Array3d rad = L.texel(f, i, j).cast<double>();
      const double* prev = p.at(f, j, i);
      double* cur = p.at(f, j, i + 1);
      for (int c = 0; c < 3; ++c)
        for (int k = 0; k < 3; ++k) cur[c * 3 + k] = prev[c * 3 + k] + rad[c] * phi[k];
    }
  });
  return p;
}

// n · face_point(f, s, t) = g0 + gs·s + gt·t (face_point is affine in s, t).
struct FaceLinear {
  double g0, gs, gt;
};
FaceLinear face_linear(int f, const Vec3d& n) {
  const auto corners = texel_corners(f, 0, 0, 1);  // (0,0), (1,0), (1,1), (0,1)
  const double g00 = n.dot(corners[0]), g10 = n.dot(corners[1]), g01 = n.dot(corners[3]);
  return {g00, g10 - g00, g01 - g00};
}

Rgb exact_at(const CubeMap& L, const RowPrefix& P, const Vec3d& n) {
  const int N = L.size();
  Eigen::Array3d sum = Eigen::Array3d::Zero();
  auto add_run = [&](int f, int j, int i0, int i1) {  // fully visible texels [i0, i1)
    if (i1 <= i0) return;
    const double* a = P.at(f, j, i0);
    const double* b = P.at(f, j, i1);
    for (int c = 0; c < 3; ++c)
      sum[c] +=
          (b[c * 3] - a[c * 3]) * n.x() + (b[c * 3 + 1] - a[c * 3 + 1]) * n.y() + (b[c * 3 + 2] - a[c * 3 + 2]) * n.z();
  };
  for (int f = 0; f < 6; ++f) {
    const FaceLinear g = face_linear(f, n);
    for (int j = 0; j < N; ++j) {
      const double t0 = double(j) / N, t1 = double(j + 1) / N;
      // g(s, t) ≥ 0 at both row edges for every corner of texel i ⇔ fully visible. With
      // h(s) = min over t ∈ {t0, t1} of g(s, t), which is linear in s, the fully visible texels
      // are a run; any texel with a corner above but not all is clipped individually.
      const double c_lo = g.g0 + std::min(g.gt * t0, g.gt * t1);
      const double c_hi = g.g0 + std::max(g.gt * t0, g.gt * t1);
      // Visible-everywhere interval for s: c_lo + gs·s ≥ 0; visible-somewhere: c_hi + gs·s > 0.
      // Texel i covers s in [i/N, (i+1)/N]: fully visible where min_s(c_lo + gs·s) >= 0, visible
      // somewhere where max_s(c_hi + gs·s) > 0. Bounds are clamped to [0, N] before int conversion.
      auto index = [N](double x) { return std::clamp(x, -1.0, double(N) + 1.0); };
      int full0 = 0, full1 = N, any0 = 0, any1 = N;
      if (g.gs > 0) {
        full0 = int(std::ceil(index(-c_lo / g.gs * N)));
        any0 = int(std::floor(index(-c_hi / g.gs * N)));
      } else if (g.gs < 0) {
        full1 = int(std::floor(index(-c_lo / g.gs * N)));
        any1 = int(std::ceil(index(-c_hi / g.gs * N)));
      } else {
        if (c_lo < 0) full1 = 0;
        if (c_hi <= 0) any1 = 0;
      }
      full0 = std::clamp(full0, 0, N);
      full1 = std::clamp(full1, 0, N);
      any0 = std::clamp(any0, 0, N);
      any1 = std::clamp(any1, 0, N);
      if (full1 < full0) full1 = full0;
      add_run(f, j, full0, full1);
      // Partly visible texels: in [any0, any1) but outside [full0, full1).
      for (int i = any0; i < any1; ++i) {
        if (i >= full0 && i < full1) {
          i = full1 - 1;
          continue;
        }
        const double w = texel_clamped_cosine_integral(f, i, j, N, n);
        if (w > 0) sum += L.texel(f, i, j).cast<double>() * w;
      }
    }
  }
  return sum.cast<float>();
}

class GaussianField final : public IrradianceField {
 public:
  explicit GaussianField(const CubeMap& L) : blurred_(gaussian_blur_faces(L)) {}
  Rgb irradiance(const Vec3f& n) const override { return kPiF * blurred_.lookup(n); }

 private:
  CubeMap blurred_;
};

class Sh9Field final : public IrradianceField {
 public:
  explicit Sh9Field(const CubeMap& L) : sh_(project_sh9(L)) {}
  Rgb irradiance(const Vec3f& n) const override { return sh9_irradiance(sh_, n).max(0.0f); }

 private:
  Sh9 sh_;
};

class ExactField final : public IrradianceField {
 public:
  ExactField(const CubeMap& L, int size, const std::atomic<bool>* stop)
      : cube_(exact_irradiance_cube(L, size, 512, stop)) {}
  Rgb irradiance(const Vec3f& n) const override { return cube_.lookup(n); }

 private:
  CubeMap cube_;
};

}  // namespace

CubeMap exact_irradiance_cube(const CubeMap& radiance, int size, int max_face, const std::atomic<bool>* stop) {
  const CubeMap* L = &radiance;
  CubeMap reduced;
  if (radiance.size() > max_face) {
    reduced = box_reduce(radiance, max_face);
    L = &reduced;
  }
  const RowPrefix P = build_prefix(*L);
  CubeMap out(size);
  tbb::parallel_for(0, 6 * size, [&](int fj) {
    throw_if_stopped(stop);
    const int f = fj / size, j = fj % size;
    for (int i = 0; i < size; ++i)
      out.set_texel(f, i, j, exact_at(*L, P, texel_direction(f, i, j, size).cast<double>()));
  });
  out.update_borders();
  return out;
}

CubeMap irradiance_cube(const IrradianceField& field, int n, float scale) {
  CubeMap e(n);
  for (int f = 0; f < 6; ++f)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) e.set_texel(f, i, j, field.irradiance(texel_direction(f, i, j, n)) * scale);
  e.update_borders();
  return e;
}

std::unique_ptr<IrradianceField> make_irradiance(IrradianceMode mode, const CubeMap& radiance, int exact_size,
                                                 const std::atomic<bool>* stop) {
  switch (mode) {
    case IrradianceMode::kGaussian:
      return std::make_unique<GaussianField>(radiance);
    case IrradianceMode::kSh9:
      return std::make_unique<Sh9Field>(radiance);
    case IrradianceMode::kExact:
      return std::make_unique<ExactField>(radiance, exact_size, stop);
    case IrradianceMode::kVolume:
      break;
  }
  throw std::logic_error("make_irradiance takes the directional modes; every mode's factory is light/irradiance_at.h");
}

}  // namespace insitu
