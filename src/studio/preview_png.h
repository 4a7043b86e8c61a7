// Linear images as the page shows them: sRGB-encoded 8-bit PNG, optionally with marked pixels
// painted red, and optionally shrunk (OpenCV's area filter) to at most `max_side_px` on the longer
// side (0: as is).
#pragma once
#include <string>

#include "core/image.h"

namespace insitu {

std::string srgb_png(const Image& linear, const Image* red_where_positive = nullptr, int max_side_px = 0);
// An image already display-encoded (values in [0, 1], clipped) as 8-bit PNG.
std::string display_png(const Image& encoded);

}  // namespace insitu
