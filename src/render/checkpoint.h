// Checkpoints of an interrupted render and the parts of a split one: the
// render state (render_state.h) in a binary file, written atomically (temporary name, then
// rename), so that a kill at any moment leaves either the previous file or the new one, never half
// of one. A checkpoint lies beside the output, OUT.checkpoint; a part is the state of a finished
// render of a sample range, which `insitu merge` adds to the others.
//
// Layout (little-endian): "INSITUCK", u32 version (8), u32 bytes per block before compression
// (96), u64 fingerprint, i32 width, height, spp, sample_begin, sample_end, passes_done,
// tiles_done, spp_done, u64 nonfinite, f64 noise target (0: not adaptive), u32 length and the
// text of the settings (what `insitu merge` needs to load the scene again: JSON, may be empty);
// then two zstd frames of byte-shuffled planes (render/plane_codec.h), each after its u64 size:
// every pixel's samples (u32; with a noise target, then one u8 per pixel: 1 where adaptive
// sampling stopped it, render/adaptive.h), and every pixel's blocks (render/pixel_blocks.h), the
// canonical ones of its samples, in chunks of 2^16 blocks, each chunk 24 planes of one PixelSums
// field (checkpoint.cpp, block_words); last, a u64 FNV-1a (core/fnv1a.h) of every byte before it.
// A block is 96 bytes before compression and about 27 after (docs/farm.md). A file whose sum
// differs (a bad disk, an edit: a changed sum or tile count that is still a consistent state) is
// refused, and the CLI keeps it. The reader checks the header and the pixels' samples before it
// decodes a block, so that what it allocates is what the state it describes holds.
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
