// Checkpoints of an interrupted render and the parts of a split one: the
// render state (render_state.h) in a binary file, written atomically (temporary name, then
// rename), so that a kill at any moment leaves either the previous file or the new one, never half
// of one. A checkpoint lies beside the output, OUT.checkpoint; a part is the state of a finished
// render of a sample range, which `insitu merge` adds to the others.
//
// Layout (little-endian): "INSITUCK", u32 version (7), u32 bytes per block (100), u64
// fingerprint, i32 width, height, spp, sample_begin, sample_end, passes_done, tiles_done, spp_done,
// u64 nonfinite, f64 noise target (0: not adaptive), u32 length and the text of the settings (what
// `insitu merge` needs to load the scene again: JSON, may be empty), then per pixel an i32 count
// of blocks and the blocks (render/pixel_blocks.h), each a PixelSums field by field (4 RGB, the
// normal, coverage, depth and 5 centred moments as float32, 3 int32 counts: met, catcher,
// samples; the batches and batch_y follow from them); with a noise target, then one u8 per pixel:
// 1 where adaptive sampling stopped it (render/adaptive.h); last, a u64 FNV-1a (core/fnv1a.h) of
// every byte before it. A file whose sum differs (a bad disk, an edit: a changed sum or tile count
// that is still a consistent state) is refused, and the CLI keeps it.
// The fingerprint names the scene and settings it belongs to (scene/pipeline.h,
// render_fingerprint): a checkpoint of another scene, other inputs or other settings is refused.
#pragma once
#include <cstdint>
#include <string>

#include "render/render_state.h"

namespace insitu {

std::string checkpoint_path(const std::string& image_path);  // OUT.checkpoint

struct StateFile {
  RenderState state;
  std::uint64_t fingerprint = 0;
  std::string settings;
};

void write_checkpoint(const std::string& path, const RenderState& state, std::uint64_t fingerprint,
                      const std::string& settings = "");
// Throws InputError("path", ...) when it is absent, truncated, damaged (its checksum), of another
// layout or inconsistent (blocks that are not the canonical ones of the samples the pass reached).
StateFile read_state_file(const std::string& path);
// The same from a file's bytes without their checksum: every check but the sum (the fuzz target's
// entry, whose inputs could not match one).
StateFile parse_state_bytes(const std::string& bytes, const std::string& path);
// read_state_file, and refused unless of this fingerprint.
RenderState read_checkpoint(const std::string& path, std::uint64_t fingerprint);

}  // namespace insitu
