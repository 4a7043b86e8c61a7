#include "render/texture.h"

#include <cmath>

#include "core/colour.h"

namespace insitu {

namespace {

// The bilinear, repeating interpolation of img's texel(i, j) at image coordinates st.
template <class Texel>
auto bilinear(const Image& img, const Vec2f& st, Texel texel) {
  // Texel centres at (i + ½)/W: x = s·W − ½, repeating.
  const float x = (st.x() - std::floor(st.x())) * float(img.width) - 0.5f;
  const float y = (st.y() - std::floor(st.y())) * float(img.height) - 0.5f;
  const int x0 = int(std::floor(x)), y0 = int(std::floor(y));
  const float wx = x - float(x0), wy = y - float(y0);
  auto wrap_x = [&](int i) { return ((i % img.width) + img.width) % img.width; };
  auto wrap_y = [&](int j) { return ((j % img.height) + img.height) % img.height; };
  auto at = [&](int i, int j) { return texel(wrap_x(i), wrap_y(j)); };
  return decltype(at(0, 0))((1 - wy) * ((1 - wx) * at(x0, y0) + wx * at(x0 + 1, y0)) +
                            wy * ((1 - wx) * at(x0, y0 + 1) + wx * at(x0 + 1, y0 + 1)));
}

}  // namespace

Rgb Texture::sample(const UvSets& uv) const {
  if (!image) return Rgb::Ones();
  const Image& img = *image;
  const Vec2f st = image_from_uv * uv[std::size_t(texcoord)].homogeneous();
  Rgb c = bilinear(img, st, [&](int i, int j) { return img.rgb(i, j); });
  if (alpha) {
    // With an alpha channel, the colour is filtered associated (weighted by alpha) and then
    // divided by the filtered alpha, as Cycles filters its images: a texel that is not there
    // lends no colour to its neighbours (a cut-out's edge keeps its own colour).
    const Image& a = *alpha;
    const Rgb ac = bilinear(img, st, [&](int i, int j) { return Rgb(img.rgb(i, j) * *a.at(i, j)); });
    const float mean_alpha = bilinear(a, st, [&](int i, int j) { return *a.at(i, j); });
    if (mean_alpha > 0) c = ac / mean_alpha;
  }
  return srgb ? Rgb(srgb_to_linear(c[0]), srgb_to_linear(c[1]), srgb_to_linear(c[2])) : c;
}

float Texture::sample_alpha(const UvSets& uv) const {
  if (!alpha) return 1.0f;
  const Image& img = *alpha;
  const Vec2f st = image_from_uv * uv[std::size_t(texcoord)].homogeneous();
  return bilinear(img, st, [&](int i, int j) { return *img.at(i, j); });
}

void set_colour_image(Texture& t, const ImageFile& file) {
  Image img = file.stored;
  sanitize(img);
  t.image = std::make_shared<Image>(std::move(img));
  t.srgb = file.display_referred;
}

void set_data_image(Texture& t, const ImageFile& file) {
  set_colour_image(t, file);
  t.srgb = false;
}

}  // namespace insitu
