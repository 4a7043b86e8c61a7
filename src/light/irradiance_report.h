// Speed and accuracy of the irradiance modes on one environment (`insitu irradiance-report`).
//
// Each mode's precomputation time; its time per lookup (mean over 10⁶ lookups at random normals);
// and its error against irradiance_reference() over a Fibonacci sphere of normals: the relative
// error of luminance, |Y(E) − Y(E_ref)| / max(Y(E_ref), 10⁻³·Ē) (Ē the mean irradiance over all
// normals, so that normals in near-total darkness do not divide by zero), its mean and maximum,
// and its value at the normal that faces the brightest texel.
#pragma once
#include <string>
#include <vector>

#include "light/cubemap.h"
#include "light/irradiance.h"

namespace insitu {

struct ModeReport {
  IrradianceMode mode;
  double precompute_ms = 0;
  double lookup_ns = 0;
  double mean_rel_error = 0;
  double max_rel_error = 0;
  double brightest_rel_error = 0;
};

struct IrradianceReport {
  int face_size = 0;
  int normals = 0;
  double reference_ms_per_normal = 0;
  Vec3d brightest_direction = Vec3d::Zero();
  std::vector<ModeReport> modes;
};

IrradianceReport irradiance_report(const CubeMap& radiance, int normals = 256, int exact_size = 32);

std::vector<Vec3d> fibonacci_sphere(int count);

}  // namespace insitu
