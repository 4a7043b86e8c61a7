// The counter-based random numbers (core/sampler.h).
#include <gtest/gtest.h>

#include "scene/pipeline.h"
#include "core/sampler.h"
#include <OpenImageIO/imageio.h>

#include "scene_fixture.h"

namespace insitu {
namespace {

// permute() is a bijection of [0, n) for every n and key (a slow, obvious check: every index is
// hit once), and keys give different orders.
TEST(Sampler, PermuteIsABijection) {
  for (std::uint32_t n : {1u, 2u, 3u, 7u, 16u, 100u, 144u, 1000u, 4097u})
    for (std::uint32_t key : {0u, 1u, 0xdeadbeefu, 12345u}) {
      std::vector<int> hits(n, 0);
      for (std::uint32_t i = 0; i < n; ++i) {
        const std::uint32_t j = permute(i, n, key);
        ASSERT_LT(j, n);
        ++hits[j];
      }
      for (std::uint32_t j = 0; j < n; ++j) ASSERT_EQ(hits[j], 1) << "n " << n << " key " << key;
    }
  int same = 0;
  for (std::uint32_t i = 0; i < 144; ++i) same += permute(i, 144, 1) == permute(i, 144, 2);
  EXPECT_LT(same, 20);
}

}  // namespace
}  // namespace insitu
