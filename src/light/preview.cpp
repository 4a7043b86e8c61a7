#include "light/preview.h"

#include <algorithm>

#include "core/colour.h"
#include "light/equirect.h"
#include "light/sixshot.h"

namespace insitu {

double preview_exposure(const CubeMap& cube) {
  std::vector<float> y;
  for (int f = 0; f < 6; ++f)
    for (int j = 0; j < cube.size(); ++j)
      for (int i = 0; i < cube.size(); ++i) y.push_back(luminance(cube.texel(f, i, j)));
  std::nth_element(y.begin(), y.begin() + long(y.size() / 2), y.end());
  const double median = y[y.size() / 2];
  return median > 0 ? 0.18 / median : 1.0;
}

Image cube_cross_preview(const CubeMap& cube, double exposure, int face_px) {
  const int n = face_px > 0 ? face_px : cube.size();
  Image out(4 * n, 3 * n, 3, 0.0f);
  for (const CrossSquare& l : kCrossLayout) {
    const Image view = render_shot([&](const Vec3f& d) { return cube.lookup(d); }, l.face, kNegZ, 90.0, n, n);
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x)
        for (int c = 0; c < 3; ++c)
          out.at(l.col * n + x, l.row * n + y)[c] = linear_to_srgb(float(exposure) * view.at(x, y)[c]);
  }
  return out;
}

Image cube_to_equirect(const CubeMap& cube) {
  const int w = 4 * cube.size(), h = 2 * cube.size();
  Image out(w, h, 3);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      out.set_rgb(x, y, cube.lookup(equirect_to_direction((float(x) + 0.5f) / float(w), (float(y) + 0.5f) / float(h))));
  return out;
}

}  // namespace insitu
