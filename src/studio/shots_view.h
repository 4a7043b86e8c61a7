// The shots panel's data: the scene's six shots as insitu uses them, read
// afresh from the scene file on every call (the panel edits it).
//
// shots_view gives, per face: its key in the scene file, its files, its turn and its field of
// view, its size as used, the percentage of its pixels that clipped and of its cube face that it
// covers (from the library's own assembly, load_environment), its registration and room lines as
// the render report gives them (scene/shots_report.h), its outline's colour in the stitched view
// (stitched_view.h), and any error the library raised about it ({"where", "what"}, as the CLI
// prints them); and `gap_percent`, the share of the sphere that no shot sees. An error that names no single shot (or a
// scene that does not parse) is the view's own "error".
#pragma once
#include <string>

#include "core/json_reader.h"

namespace insitu {

json shots_view(const std::string& scene_path);

// The shot of `face` (0..5: +x, −x, up, down, +z, −z) as insitu uses it (turned), sRGB, its
// clipped pixels red, at most `max_side_px` on its longer side; a bracket's middle exposure.
// HDR shots are scaled so that their mean luminance shows as mid-grey.
std::string shot_preview_png(const std::string& scene_path, int face, int max_side_px);

}  // namespace insitu
