#include "render/pixel_blocks.h"

#include "core/float_bits.h"
#include "render/pixel_variance.h"

namespace insitu {

namespace {

// Chan, Golub and LeVeque's pairwise update of centred co-moments (1979, eq. 2.1b): the union of
// a (n_a samples, means x̄_a, ȳ_a) and b has
//   M_xy = M_xy,a + M_xy,b + (n_a n_b / (n_a + n_b)) (x̄_b − x̄_a)(ȳ_b − ȳ_a),
// with the means from the sums S here.
double comoment_update(double sa_x, double sb_x, double sa_y, double sb_y, double na, double nb) {
  const double dx = sb_x / nb - sa_x / na, dy = sb_y / nb - sa_y / na;
  return na * nb / (na + nb) * dx * dy;
}

}  // namespace

void add_sums(PixelSums& into, const PixelSums& b) {
  if (b.samples == 0) return;
  if (into.samples == 0) {
    into = b;
    return;
  }
  const double na = into.samples, nb = b.samples;
  const double ya = sum_y(into), yb = sum_y(b), wa = sum_w(into), wb = sum_w(b), xa = sum_n(into), xb = sum_n(b);
  into.m_yy = float(double(into.m_yy) + b.m_yy + comoment_update(ya, yb, ya, yb, na, nb));
  into.m_ww = float(double(into.m_ww) + b.m_ww + comoment_update(wa, wb, wa, wb, na, nb));
  into.m_nn = float(double(into.m_nn) + b.m_nn + comoment_update(xa, xb, xa, xb, na, nb));
  into.m_wn = float(double(into.m_wn) + b.m_wn + comoment_update(wa, wb, xa, xb, na, nb));
  if (b.batches > 0 && into.batches > 0)
    into.m_batch = float(double(into.m_batch) + b.m_batch +
                         comoment_update(into.batch_y, b.batch_y, into.batch_y, b.batch_y, into.batches, b.batches));
  else if (b.batches > 0)
    into.m_batch = b.m_batch;
  into.batch_y += b.batch_y, into.batches += b.batches;
  into.objects += b.objects, into.with += b.with, into.without += b.without, into.albedo += b.albedo;
  into.normal += b.normal;
  into.coverage += b.coverage, into.depth += b.depth;
  into.met += b.met, into.catcher += b.catcher, into.samples += b.samples;
}

namespace {

// Whether blocks of `size` samples starting at `left` and `left + size` are the two halves of
// one aligned block of 2·size.
bool siblings(int left, int size) { return left % (2 * size) == 0; }

}  // namespace

void round_block(PixelSums& p) {
  for (int k = 0; k < 3; ++k) p.albedo[k] = round_significand(p.albedo[k], kFeatureBits);
  p.depth = round_significand(p.depth, kFeatureBits);
  for (float* m : {&p.m_yy, &p.m_ww, &p.m_nn, &p.m_wn, &p.m_batch}) *m = round_significand(*m, kMomentBits);
}

void push_block(PixelBlocks& blocks, int first, const PixelSums& block) {
  int top_start = first + block_samples(blocks);  // where `block` starts
  blocks.push_back(block);
  round_block(blocks.back());
  while (blocks.size() >= 2) {
    const PixelSums& right = blocks.back();
    PixelSums& left = blocks[blocks.size() - 2];
    const int size = right.samples, left_start = top_start - left.samples;
    if (left.samples != size || !siblings(left_start, size)) break;
    add_sums(left, right);
    if (left.samples == kBatchSamples) start_batch(left);
    if (left.batches > 0) left.batch_y = sum_y(left);  // what a block read from a file has
    round_block(left);
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
std::vector<int> canonical_sizes(int first, int end) {
  std::vector<int> sizes;
  for (int start = first; start < end;) {
    int size = 1;
    while ((start % (2 * size)) == 0 && long(start) + 2 * long(size) <= end && size < (1 << 29)) size *= 2;
    sizes.push_back(size);
    start += size;
  }
  return sizes;
}

int canonical_count(int first, int end) { return int(canonical_sizes(first, end).size()); }

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
