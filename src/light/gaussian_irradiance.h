// The legacy fast irradiance of the 2011 real-time renderer, kept exactly so that users can A/B
// against it: each cube face is Gaussian-blurred on its own (no filtering across face edges, as
// the legacy code did) with a kernel as wide as the face — the largest odd size k <= the face's
// side, sigma = 0.3((k−1)/2 − 1) + 0.8 (OpenCV's default for sigma = 0), borders reflected
// (BORDER_REFLECT_101) — and a surface is lit by the blurred cube looked up along its normal.
// The blurred radiance is used as it is; it is not irradiance in physical units (a constant
// environment L gives L, not πL), and the realtime integrator uses it the legacy way:
// colour = base colour × blurred(n).
#pragma once
#include "light/cubemap.h"

namespace insitu {

constexpr int kLegacyMaxFace = 256;  // larger faces are box-averaged to this first
int legacy_kernel_size(int face_size);
double legacy_sigma(int kernel_size);  // 0.3((k−1)/2 − 1) + 0.8
CubeMap gaussian_blur_faces(const CubeMap& radiance);

}  // namespace insitu
