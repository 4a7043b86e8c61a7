// Pairwise sums over aligned blocks of sample indices (render/pixel_blocks.h): the binary counter
// against the recursive definition it implements, and splits merged in every way against the
// whole.
#include <gtest/gtest.h>

#include <random>

#include "render/pixel_blocks.h"
#include "render/pixel_variance.h"

namespace insitu {
namespace {

// A leaf of sample s: values spread over 12 decades, so that the order of additions shows.
PixelSums leaf(int s) {
  std::mt19937 rng(std::uint32_t(s) * 2654435761u + 1);
  std::uniform_real_distribution<double> u(-6, 6);
  PixelSums p;
  const double v = std::pow(10.0, u(rng));
  p.objects = Rgb(float(v), float(v / 3), float(v * 7));
  p.with = Rgb::Constant(float(v / 9)), p.without = Rgb::Constant(float(v * 1e-3));
  p.samples = 1;
  return p;
}

// The definition, slowly: an aligned block is its left half plus its right half (and a batch of its
// own when it has kBatchSamples samples), rounded as a block keeps its sums (round_block); a range
// is its maximal aligned blocks from the left, added left to right.
PixelSums block_value(int start, int size) {
  PixelSums left = leaf(start);
  if (size > 1) {
    left = block_value(start, size / 2);
    add_sums(left, block_value(start + size / 2, size / 2));
  }
  if (size == kBatchSamples) start_batch(left);  // a batch: its own sum, squared
  if (left.batches > 0) left.batch_y = sum_y(left);
  round_block(left);
  return left;
}

PixelBlocks canonical(int a, int b) {
  PixelBlocks out;
  while (a < b) {
    int size = 1;
    while (a % (2 * size) == 0 && a + 2 * size <= b) size *= 2;
    out.push_back(block_value(a, size));
    a += size;
  }
  return out;
}

PixelBlocks counted(int a, int b) {
  PixelBlocks blocks;
  for (int s = a; s < b; ++s) push_block(blocks, a, leaf(s));
  return blocks;
}

bool same(const PixelSums& a, const PixelSums& b) {
  return (a.objects == b.objects).all() && (a.with == b.with).all() && (a.without == b.without).all() &&
         a.m_yy == b.m_yy && a.m_ww == b.m_ww && a.m_nn == b.m_nn && a.m_wn == b.m_wn && a.m_batch == b.m_batch &&
         a.samples == b.samples && a.batch_y == b.batch_y && a.batches == b.batches;
}

bool same(const PixelBlocks& a, const PixelBlocks& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (!same(a[i], b[i])) return false;
  return true;
}

TEST(PixelBlocks, TheCounterBuildsTheCanonicalBlocks) {
  for (int a : {0, 1, 3, 8, 13})
    for (int b = a + 1; b <= 70; ++b) {
      const PixelBlocks blocks = counted(a, b);
      ASSERT_TRUE(same(blocks, canonical(a, b))) << "[" << a << ", " << b << ")";
      ASSERT_TRUE(canonical_blocks(blocks, a));
      ASSERT_EQ(block_samples(blocks), b - a);
    }
  EXPECT_EQ(counted(0, 13).size(), 3u);  // [0, 8) [8, 12) [12, 13)
}

// Split [0, n) at any one or two points, render each range on its own and push the parts' blocks
// in order: the same bits as the whole.
TEST(PixelBlocks, PartsMergedAreBitIdenticalToTheWhole) {
  const int n = 37;
  const PixelSums whole = fold_blocks(counted(0, n));
  // The sequential sum of the same leaves differs in its bits: the test can fail.
  PixelSums sequential = leaf(0);
  for (int s = 1; s < n; ++s) add_sums(sequential, leaf(s));
  EXPECT_FALSE(same(sequential, whole));
  for (int cut1 = 1; cut1 < n; ++cut1)
    for (int cut2 = cut1; cut2 < n; cut2 += 5) {
      PixelBlocks merged;
      for (auto [a, b] : {std::pair{0, cut1}, {cut1, cut2}, {cut2, n}}) {
        if (a == b) continue;
        for (const PixelSums& block : counted(a, b)) push_block(merged, 0, block);
      }
      ASSERT_TRUE(same(merged, counted(0, n))) << cut1 << " " << cut2;
      ASSERT_TRUE(same(fold_blocks(merged), whole));
    }
}

TEST(PixelBlocks, NonCanonicalBlocksAreRecognized) {
  PixelBlocks two_leaves{leaf(0), leaf(1)};  // siblings left apart
  EXPECT_FALSE(canonical_blocks(two_leaves, 0));
  EXPECT_TRUE(canonical_blocks(two_leaves, 1));  // [1, 2) [2, 3): not siblings
  PixelBlocks misaligned = counted(0, 2);
  EXPECT_FALSE(canonical_blocks(misaligned, 1));  // a block of 2 cannot start at 1
  PixelSums three = leaf(0);
  three.samples = 3;
  EXPECT_FALSE(canonical_blocks({three}, 0));
  EXPECT_TRUE(canonical_blocks({}, 5));
}

}  // namespace
}  // namespace insitu

namespace insitu {
namespace {

// canonical_count against the blocks that pushing the samples one by one leaves.
TEST(PixelBlocks, CanonicalCountIsWhatPushingLeaves) {
  for (int first = 0; first < 40; ++first) {
    PixelBlocks blocks;
    for (int end = first + 1; end < first + 70; ++end) {
      PixelSums leaf;
      leaf.samples = 1;
      push_block(blocks, first, leaf);
      ASSERT_EQ(canonical_count(first, end), int(blocks.size())) << first << ":" << end;
    }
  }
  EXPECT_EQ(canonical_count(0, 1 << 20), 1);
  EXPECT_EQ(canonical_count(5, 5), 0);
}

}  // namespace
}  // namespace insitu
