// Compositing the rendered objects over the linearized photo, and encoding the result.
//
//   over:  C = O + (1 − α) P        O: objects premultiplied by coverage α, P: linear photo
//
// Encoding for a display-referred output (PNG, JPEG): pixels with α = 0 are the photo's own
// stored values, so they are bit-identical to the input; all others are linear_to_srgb(C).
#pragma once
#include "image.h"
#include "render.h"

namespace insitu {

Image composite_over(const Image& photo_linear, const RenderLayers& layers);

// `stored` is the photo as read (ImageFile::stored); display_referred says whether it is
// sRGB-encoded.
Image encode_composite(const Image& composite_linear, const Image& alpha, const ImageFile& photo);

}  // namespace insitu
