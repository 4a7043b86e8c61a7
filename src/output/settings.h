// The output stage's settings as the scene file gives them: the tone map (tonemap.h) and how the
// render is composited over the photo (composite.h). Plain data, below the parser.
#pragma once
#include <optional>
#include <string>

#include "core/name_table.h"

namespace insitu {

enum class ToneMap { kPhoto, kAdaptiveLog, kReinhard, kLinear };
inline constexpr Named<ToneMap> kToneMaps[] = {
    {ToneMap::kPhoto, "photo"}, {ToneMap::kAdaptiveLog, "adaptive_log"}, {ToneMap::kReinhard, "reinhard"}, {ToneMap::kLinear, "linear"}};
inline const char* tonemap_name(ToneMap t) { return name_of(kToneMaps, t); }
inline std::optional<ToneMap> parse_tonemap(const std::string& name) { return parse_name(kToneMaps, name); }

struct ToneMapSettings {
  ToneMap op = ToneMap::kPhoto;
  std::optional<double> key;  // per operator: adaptive_log 1, reinhard 0.18, linear 1
  double bias = 0.85;         // Drago's b
};

// How the catcher's change is applied to the photo (composite.h).
enum class CompositeMode { kRatio, kAdditive };
inline constexpr Named<CompositeMode> kCompositeModes[] = {{CompositeMode::kRatio, "ratio"}, {CompositeMode::kAdditive, "additive"}};

}  // namespace insitu
