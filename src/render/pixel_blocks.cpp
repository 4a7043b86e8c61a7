#include "render/pixel_blocks.h"

#include "render/pixel_variance.h"

namespace insitu {

void add_sums(PixelSums& into, const PixelSums& b) {
  into.objects += b.objects, into.with += b.with, into.without += b.without, into.albedo += b.albedo;
  into.normal += b.normal;
  into.coverage += b.coverage, into.depth += b.depth, into.y += b.y, into.y2 += b.y2;
  into.w += b.w, into.n += b.n, into.w2 += b.w2, into.n2 += b.n2, into.wn += b.wn;
  into.batch_y += b.batch_y, into.batch_y2 += b.batch_y2, into.batches += b.batches;
  into.met += b.met, into.catcher += b.catcher, into.samples += b.samples;
}

namespace {

// Whether blocks of `size` samples starting at `left` and `left + size` are the two halves of
// one aligned block of 2·size.
bool siblings(int left, int size) { return left % (2 * size) == 0; }

}  // namespace

void push_block(PixelBlocks& blocks, int first, const PixelSums& block) {
  int top_start = first + block_samples(blocks);  // where `block` starts
  blocks.push_back(block);
  while (blocks.size() >= 2) {
    const PixelSums& right = blocks.back();
    PixelSums& left = blocks[blocks.size() - 2];
    const int size = right.samples, left_start = top_start - left.samples;
    if (left.samples != size || !siblings(left_start, size)) break;
    add_sums(left, right);
    if (left.samples == kBatchSamples) start_batch(left);
    blocks.pop_back();
    top_start = left_start;
  }
}

PixelSums fold_blocks(const PixelBlocks& blocks) {
  PixelSums total;
  if (blocks.empty()) return total;
  total = blocks.front();
  for (std::size_t i = 1; i < blocks.size(); ++i) add_sums(total, blocks[i]);
  return total;
}

int block_samples(const PixelBlocks& blocks) {
  int n = 0;
  for (const PixelSums& b : blocks) n += b.samples;
  return n;
}

// The largest aligned block that starts at `start` and fits before `end`, one after another.
int canonical_count(int first, int end) {
  int count = 0;
  for (int start = first; start < end; ++count) {
    int size = 1;
    while ((start % (2 * size)) == 0 && start + 2 * size <= end && size < (1 << 29)) size *= 2;
    start += size;
  }
  return count;
}

bool canonical_blocks(const PixelBlocks& blocks, int first) {
  int start = first;
  for (std::size_t i = 0; i < blocks.size(); ++i) {
    const int size = blocks[i].samples;
    if (size <= 0 || (size & (size - 1)) != 0 || start % size != 0) return false;
    if (i > 0 && blocks[i - 1].samples == size && siblings(start - size, size)) return false;
    if (blocks[i].batches != (size >= kBatchSamples ? size / kBatchSamples : 0)) return false;
    start += size;
  }
  return true;
}

}  // namespace insitu
