// Pearson's χ² test of binned sample counts against the counts a density expects, for the tests
// of sampling routines (bsdf_test.cpp, glass_test.cpp).
#pragma once
#include <cmath>
#include <cstddef>
#include <vector>

namespace insitu::test {

// χ² = Σ (O − E)² / E over the bins, those expecting fewer than 5 samples pooled into one; the
// score (χ² − dof)/√(2 dof) is below 4 for a sampler that draws from the density.
inline double chi2_score_of(const std::vector<double>& observed, const std::vector<double>& expected,
                            double* chi2_out = nullptr) {
  double chi2 = 0, pooled_o = 0, pooled_e = 0;
  int dof = 0;
  for (std::size_t k = 0; k < observed.size(); ++k) {
    if (expected[k] < 5) {
      pooled_o += observed[k], pooled_e += expected[k];
      continue;
    }
    chi2 += (observed[k] - expected[k]) * (observed[k] - expected[k]) / expected[k];
    ++dof;
  }
  if (pooled_e >= 5) chi2 += (pooled_o - pooled_e) * (pooled_o - pooled_e) / pooled_e, ++dof;
  if (chi2_out) *chi2_out = chi2;
  return (chi2 - dof) / std::sqrt(2.0 * dof);
}

}  // namespace insitu::test
