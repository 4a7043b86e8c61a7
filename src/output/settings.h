// The output stage's settings as the scene file gives them: the tone map (tonemap.h) and how the
// render is composited over the photo (composite.h). Plain data, below the parser.
#pragma once
#include <optional>
#include <string>

#include "core/name_table.h"

namespace insitu {

enum class ToneMap { kPhoto, kAdaptiveLog, kReinhard, kLinear };
inline constexpr Named<ToneMap> kToneMaps[] = {{ToneMap::kPhoto, "photo"},
                                               {ToneMap::kAdaptiveLog, "adaptive_log"},
                                               {ToneMap::kReinhard, "reinhard"},
                                               {ToneMap::kLinear, "linear"}};
inline const char* tonemap_name(ToneMap t) { return name_of(kToneMaps, t); }
inline std::optional<ToneMap> parse_tonemap(const std::string& name) { return parse_name(kToneMaps, name); }

struct ToneMapSettings {
  ToneMap op = ToneMap::kPhoto;
  std::optional<double> key;  // unset: the operator's default_key
  double bias = 0.85;         // Drago's b (adaptive_log)
};

// The key an operator takes when none is given: Reinhard's middle grey, 1 for the others (the
// legacy renderer's brightness slider at its rest). `photo` reads none.
inline double default_key(ToneMap op) { return op == ToneMap::kReinhard ? 0.18 : 1.0; }
inline bool reads_key(ToneMap op) { return op != ToneMap::kPhoto; }
inline bool reads_bias(ToneMap op) { return op == ToneMap::kAdaptiveLog; }

// One line on what the operator does, for `insitu modes` and docs/cli.md (docs/tonemap.md has the
// formulas).
inline const char* tonemap_summary(ToneMap op) {
  switch (op) {
    case ToneMap::kPhoto:
      return "the photo's own curve (its recovered response, else "
             "sRGB): untouched pixels stay the photo's, bit for bit";
    case ToneMap::kAdaptiveLog:
      return "the legacy renderer's operator: Drago et al. 2003's "
             "adaptive logarithmic mapping after a log-average key";
    case ToneMap::kReinhard:
      return "Reinhard et al. 2002, global";
    case ToneMap::kLinear:
      return "scaled by the key and clipped";
  }
  return "";
}

// How the catcher's change is applied to the photo (composite.h).
enum class CompositeMode { kRatio, kAdditive };
inline constexpr Named<CompositeMode> kCompositeModes[] = {{CompositeMode::kRatio, "ratio"},
                                                           {CompositeMode::kAdditive, "additive"}};

}  // namespace insitu
