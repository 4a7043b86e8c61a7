// The light that clipped in the shots, recovered for a loaded scene: inverse lighting
// (relight/inverse_lighting.h) against the photo, on the local scene's planes and the room box,
// by default whenever a shot clipped; and what determined the light, for the report.
#pragma once
#include <atomic>
#include <nlohmann/json.hpp>

#include "scene/pipeline.h"

namespace insitu {

// Balances the light of shots or a panorama to the photo's colour (environment.white_balance
// "photo", relight/photo_white_balance.h): s.white_balance, and s.environment multiplied by its
// gain when determined; a gain more than 5 % from 1 in a channel is said.
void match_white_balance(LoadedScene& s);

// With six shots or a partial panorama that left directions uncovered and a room box: those the
// photo sees on the box's walls taken from it, the rest filled again from their neighbours
// (relight/photo_fill.h), in s.environment; s.photo_fill says how many and at what level.
void fill_uncovered_from_photo(LoadedScene& s);

// With environment.inverse_lighting on: fits the clipped sources (when a shot clipped), scales
// them in s.environment, and warns when the photo does not determine them; then, in a room box
// with openings, the light through them that the capture point never saw
// (relight/unseen_outside.h), set in s.room where the photo determines it.
void recover_clipped_light(LoadedScene& s, const std::atomic<bool>* stop = nullptr);

// What determined the light: "hdr image", "shots" (nothing clipped), "brackets", "inverse
// lighting", "inverse lighting with a reference", or "lower bound" (clipped, not recovered).
std::string light_determined_by(const LoadedScene& s);

// The report's "light" object: the above, and each source's scale, σ and energy added.
nlohmann::json light_report(const LoadedScene& s);

// The report's "white_balance" object: the gain, its σ, the pixels compared; null when off.
nlohmann::json white_balance_report(const LoadedScene& s);

// The report's "photo_fill" object: the uncovered texels, those from the photo, the level and its
// pixels, or why none; null when every direction was covered or there is no room box.
nlohmann::json photo_fill_report(const LoadedScene& s);

}  // namespace insitu
