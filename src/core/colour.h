// The sRGB transfer function (IEC 61966-2-1) and its inverse, per channel.
#pragma once

namespace insitu {

// Encoded sRGB value in [0,1] -> linear:  v <= 0.04045 ? v/12.92 : ((v+0.055)/1.055)^2.4
float srgb_to_linear(float v);
// Linear -> encoded sRGB in [0,1] (input clamped to [0,1]):
//   l <= 0.0031308 ? 12.92 l : 1.055 l^(1/2.4) - 0.055
float linear_to_srgb(float l);

}  // namespace insitu
