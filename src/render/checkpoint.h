// Checkpoints of an interrupted render (issue 15): the render state (render_state.h) in a binary
// file beside the output, OUT.checkpoint, written atomically (temporary name, then rename), so that
// a kill at any moment leaves either the previous checkpoint or the new one, never half of one.
//
// Layout (little-endian): "INSITUCK", u32 version (2), u32 bytes per pixel (144), u64
// fingerprint, i32 width, height, spp, passes_done, tiles_done, spp_done, u64 nonfinite, then per
// pixel its PixelSums field by field (4 RGB and the normal as float32, 9 float64 sums, 3 int32
// counts).
// The fingerprint names the scene and settings it belongs to (scene/pipeline.h,
// render_fingerprint): a checkpoint of another scene, other inputs or other settings is refused.
#pragma once
#include <cstdint>
#include <string>

#include "render/render_state.h"

namespace insitu {

std::string checkpoint_path(const std::string& image_path);  // OUT.checkpoint

void write_checkpoint(const std::string& path, const RenderState& state, std::uint64_t fingerprint);
// Throws InputError("path", ...) when it is absent, truncated, of another layout, or of another
// fingerprint.
RenderState read_checkpoint(const std::string& path, std::uint64_t fingerprint);

}  // namespace insitu
