// A pixel's samples summed pairwise over aligned dyadic blocks of sample indices, so
// that a render split into sample ranges and merged is bit-identical to one render of the whole
// range, wherever it was split.
//
// Floating-point addition is not associative: summed one after another, the samples [0, 64) give
// other bits than (samples [0, 16)) + (samples [16, 64)). So a sum is defined by a tree that does
// not depend on the split. The samples of one pixel are the leaves; an aligned dyadic block
// [k·2^j, (k+1)·2^j) of sample indices has the value left half + right half; and the range [a, b)
// is the left-to-right sum of its canonical decomposition into maximal aligned blocks (the one a
// binary counter walks through: [0, 13) = [0, 8) + [8, 12) + [12, 13)). This is pairwise summation
// (Higham 1993, "The accuracy of floating point summation"): its rounding error grows as log n
// rather than n.
//
// A pixel keeps the blocks of the range it has so far, in order (PixelBlocks). Adding a sample
// pushes a leaf and merges the two blocks on top while they are siblings: the binary counter.
// Merging two parts pushes the second's blocks onto the first's in the same way. Any tiling of a
// range by aligned blocks with no two adjacent siblings is the canonical one (the smallest block
// of a non-maximal tiling has its sibling beside it), so every way of arriving at [a, b) gives
// the same blocks with the same bits. Each block knows its size: its `samples`.
#pragma once
#include <vector>

#include "render/render_state.h"

namespace insitu {

// into += b, field by field (the two sums of one pixel over disjoint samples).
void add_sums(PixelSums& into, const PixelSums& b);

// Pushes `block`, the aligned block that follows `blocks` (which start at sample `first`), and
// merges siblings on top; a block merged to kBatchSamples samples becomes a batch
// (render/pixel_variance.h).
void push_block(PixelBlocks& blocks, int first, const PixelSums& block);

// The pixel's sum over its whole range: its blocks added left to right (zero when empty).
PixelSums fold_blocks(const PixelBlocks& blocks);

// The samples the blocks hold.
int block_samples(const PixelBlocks& blocks);

// How many blocks the canonical decomposition of the samples [first, end) has.
int canonical_count(int first, int end);

// Whether `blocks`, starting at sample `first`, is a canonical decomposition: each block an
// aligned power of two, no two adjacent siblings, holding its whole batches (render/pixel_variance.h)
// and no others (what a part file read from disk must be).
bool canonical_blocks(const PixelBlocks& blocks, int first);

}  // namespace insitu
