#include "render/texture.h"

#include <cmath>

#include "core/colour.h"

namespace insitu {

Rgb Texture::sample(const UvSets& uv) const {
  if (!image) return Rgb::Ones();
  const Image& img = *image;
  const Vec2f st = image_from_uv * uv[std::size_t(texcoord)].homogeneous();
  // Texel centres at (i + ½)/W: x = s·W − ½, repeating.
  const float x = (st.x() - std::floor(st.x())) * float(img.width) - 0.5f;
  const float y = (st.y() - std::floor(st.y())) * float(img.height) - 0.5f;
  const int x0 = int(std::floor(x)), y0 = int(std::floor(y));
  const float wx = x - float(x0), wy = y - float(y0);
  auto wrap_x = [&](int i) { return ((i % img.width) + img.width) % img.width; };
  auto wrap_y = [&](int j) { return ((j % img.height) + img.height) % img.height; };
  auto texel = [&](int i, int j) { return img.rgb(wrap_x(i), wrap_y(j)); };
  const Rgb c = (1 - wy) * ((1 - wx) * texel(x0, y0) + wx * texel(x0 + 1, y0)) +
                wy * ((1 - wx) * texel(x0, y0 + 1) + wx * texel(x0 + 1, y0 + 1));
  return srgb ? Rgb(srgb_to_linear(c[0]), srgb_to_linear(c[1]), srgb_to_linear(c[2])) : c;
}

void set_colour_image(Texture& t, const ImageFile& file) {
  Image img = file.stored;
  sanitize(img);
  t.image = std::make_shared<Image>(std::move(img));
  t.srgb = file.display_referred;
}

}  // namespace insitu
