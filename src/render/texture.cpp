#include "render/texture.h"

#include <cmath>

#include "core/colour.h"

namespace insitu {

namespace {

// The bilinear, repeating interpolation of img's texel(i, j) at image coordinates st.
template <class Texel>
auto bilinear(const Texels& img, const Vec2f& st, Texel texel) {
  const int w = img.width(), h = img.height();
  // Texel centres at (i + ½)/W: x = s·W − ½, repeating.
  const float x = (st.x() - std::floor(st.x())) * float(w) - 0.5f;
  const float y = (st.y() - std::floor(st.y())) * float(h) - 0.5f;
  const int x0 = int(std::floor(x)), y0 = int(std::floor(y));
  const float wx = x - float(x0), wy = y - float(y0);
  auto wrap_x = [&](int i) { return ((i % w) + w) % w; };
  auto wrap_y = [&](int j) { return ((j % h) + h) % h; };
  auto at = [&](int i, int j) { return texel(wrap_x(i), wrap_y(j)); };
  return decltype(at(0, 0))((1 - wy) * ((1 - wx) * at(x0, y0) + wx * at(x0 + 1, y0)) +
                            wy * ((1 - wx) * at(x0, y0 + 1) + wx * at(x0 + 1, y0 + 1)));
}

}  // namespace

Rgb Texture::sample(const UvSets& uv) const {
  if (!image) return Rgb::Ones();
  const Texels& img = *image;
  const Vec2f st = image_from_uv * uv[std::size_t(texcoord)].homogeneous();
  Rgb c = bilinear(img, st, [&](int i, int j) { return img.rgb(i, j); });
  if (alpha) {
    // With an alpha channel, the colour is filtered associated (weighted by alpha) and then
    // divided by the filtered alpha, as Cycles filters its images: a texel that is not there
    // lends no colour to its neighbours (a cut-out's edge keeps its own colour).
    const Texels& a = *alpha;
    const Rgb ac = bilinear(img, st, [&](int i, int j) { return Rgb(img.rgb(i, j) * a.value(i, j)); });
    const float mean_alpha = bilinear(a, st, [&](int i, int j) { return a.value(i, j); });
    if (mean_alpha > 0) c = ac / mean_alpha;
  }
  return srgb ? Rgb(srgb_to_linear(c[0]), srgb_to_linear(c[1]), srgb_to_linear(c[2])) : c;
}

float Texture::sample_alpha(const UvSets& uv) const {
  if (!alpha) return 1.0f;
  const Texels& img = *alpha;
  const Vec2f st = image_from_uv * uv[std::size_t(texcoord)].homogeneous();
  return bilinear(img, st, [&](int i, int j) { return img.value(i, j); });
}

std::shared_ptr<const Texels> texels_of(ImageFile& file) {
  if (!file.stored_bytes.empty()) return std::make_shared<const Texels>(std::move(file.stored_bytes));
  sanitize(file.stored);
  return std::make_shared<const Texels>(std::move(file.stored));
}

std::shared_ptr<const Texels> alpha_texels_of(ImageFile& file) {
  if (!file.alpha_bytes.empty()) return std::make_shared<const Texels>(std::move(file.alpha_bytes));
  if (file.alpha.empty()) return nullptr;
  sanitize(file.alpha);
  return std::make_shared<const Texels>(std::move(file.alpha));
}

void set_colour_image(Texture& t, ImageFile file) {
  t.image = texels_of(file);
  t.srgb = file.display_referred;
}

void set_data_image(Texture& t, ImageFile file) {
  set_colour_image(t, std::move(file));
  t.srgb = false;
}

}  // namespace insitu
