// Tone mapping of the linear composite for display (docs/tonemap.md).
//
//   photo         (default) re-encode with the photo's own curve (its recovered response, else
//                 sRGB): untouched pixels stay identical to the input photo (composite.h).
//   adaptive_log  the operator of Ogre's HDRlib used by the legacy renderer: the log-average
//                 luminance L̄w = exp(mean(ln(δ + Lw))), δ = 10⁻⁶, scales the scene to the key,
//                 Lw' = key·Lw/L̄w, then Drago et al. 2003's adaptive logarithmic mapping
//                   Ld = (Ld_max/100) / log10(L'max + 1) · ln(Lw' + 1) / ln(2 + 8 (Lw'/L'max)^(ln b / ln ½))
//                 with Ld_max = 100 cd/m² (so the first factor is 1/log10(L'max + 1)) and bias
//                 b = 0.85; colours keep their ratios (C·Ld/Lw), then the sRGB curve.
//   reinhard      Reinhard et al. 2002, global: L = key·Lw/L̄w, Ld = L/(1 + L) (key 0.18).
//   linear        C·key (key 1), clipped, then the sRGB curve.
// Luminance is Rec.709 (DESIGN.md). Negative and non-finite inputs count as 0; an all-black
// frame maps to black. Where the photo clipped (`clipped_photo`, composite.h: a weight w per
// pixel) the colour is unknown, and that share of the pixel is shown neutral at its luminance:
// C' = (1 − w)·C + w·Lw before the operator's scale Ld/Lw (the sRGB curve and `photo` keep the
// photo's own white there already).
#pragma once
#include "core/image.h"
#include "output/settings.h"

namespace insitu {

// Display-referred values in [0, 1] (sRGB-encoded) for every operator but `photo`, which the
// pipeline encodes itself.
Image tonemap(const Image& linear, const ToneMapSettings& settings, const Image* clipped_photo = nullptr);

// The log-average luminance exp(mean(ln(δ + Y))), δ = 10⁻⁶, over finite non-negative pixels.
double log_average_luminance(const Image& linear);

}  // namespace insitu
