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

// Pushes `block`, the aligned block that follows `blocks` (which start at sample `first`),
// rounded (round_block), and merges siblings on top, rounding each merge; a block merged to kBatchSamples samples
// becomes a batch (render/pixel_variance.h).
void push_block(PixelBlocks& blocks, int first, const PixelSums& block);

// The pixel's sum over its whole range: its blocks added left to right (zero when empty).
PixelSums fold_blocks(const PixelBlocks& blocks);

// The samples the blocks hold.
int block_samples(const PixelBlocks& blocks);

// The sizes of the canonical decomposition of the samples [first, end), in order, and how many
// there are.
std::vector<int> canonical_sizes(int first, int end);
int canonical_count(int first, int end);

// What a block keeps of each sum. The RGB sums, the normal, the coverage and the counts are
// float32 and int as added. The denoiser's albedo and depth features are rounded to binary16's
// precision (kFeatureBits stored significand bits: 2.4e-4 relative each time) and the centred
// moments to kMomentBits (7.6e-6), both in float32's range (core/float_bits.h). push_block rounds
// every block it makes, a leaf or a merge, so the rounding depends only on the tree: a part or a
// checkpoint holds exactly what memory holds, resume and merge stay bit for bit, and the bits
// dropped are zeros that a file's compression removes (render/checkpoint.h).
constexpr int kFeatureBits = 10, kMomentBits = 16;
void round_block(PixelSums& block);

// Whether `blocks`, starting at sample `first`, is a canonical decomposition: each block an
// aligned power of two, no two adjacent siblings, holding its whole batches (render/pixel_variance.h)
// and no others (what a part file read from disk must be).
bool canonical_blocks(const PixelBlocks& blocks, int first);

}  // namespace insitu
