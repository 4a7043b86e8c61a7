#include "core/colour.h"

#include <algorithm>
#include <cmath>

namespace insitu {

float srgb_to_linear(float v) {
  if (!(v > 0.0f)) return 0.0f;  // also maps NaN to 0
  if (v <= 0.04045f) return v / 12.92f;
  return std::pow((v + 0.055f) / 1.055f, 2.4f);
}

float linear_to_srgb(float l) {
  if (!(l > 0.0f)) return 0.0f;
  if (l >= 1.0f) return 1.0f;
  if (l <= 0.0031308f) return 12.92f * l;
  return 1.055f * std::pow(l, 1.0f / 2.4f) - 0.055f;
}

}  // namespace insitu
