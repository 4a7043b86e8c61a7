#include "composite.h"

#include <cassert>

#include "colour.h"

namespace insitu {

Image composite_over(const Image& photo, const RenderLayers& layers) {
  assert(photo.width == layers.objects.width && photo.height == layers.objects.height);
  Image out(photo.width, photo.height, 3);
  for (int y = 0; y < photo.height; ++y)
    for (int x = 0; x < photo.width; ++x) {
      const float a = *layers.alpha.at(x, y);
      out.set_rgb(x, y, layers.objects.rgb(x, y) + (1.0f - a) * photo.rgb(x, y));
    }
  return out;
}

Image encode_composite(const Image& c, const Image& alpha, const ImageFile& photo) {
  Image out(c.width, c.height, 3);
  for (int y = 0; y < c.height; ++y)
    for (int x = 0; x < c.width; ++x) {
      const bool untouched = *alpha.at(x, y) == 0.0f;
      for (int k = 0; k < 3; ++k) {
        if (untouched && photo.display_referred) out.at(x, y)[k] = photo.stored.at(x, y)[k];
        else out.at(x, y)[k] = linear_to_srgb(c.at(x, y)[k]);
      }
    }
  return out;
}

}  // namespace insitu
