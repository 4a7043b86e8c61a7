// A pixel's variance, from its sums (render_state.h): what the variance layer, the noise figure
// and adaptive sampling's stopping rule read.
//
// The per-sample estimate, s² = Σ(y − ȳ)² / (n − 1) and Var(mean) = s²/n, is that of
// independent samples. A pixel's samples are scrambled Sobol points (core/sampler.h), whose mean
// errs less than that: the spread between two seeds was 0.24 of it at 64 spp
// (Layers.VariancePredictsTheSpreadAcrossSeeds), so adaptive sampling stopped late. Batch means
// bring that to 0.6 (0.58 at 256 spp).
//
// Batch means (Schmeiser 1982, "Batch size effects in the analysis of simulation output") are
// tighter and keep the sequence whole. The samples are cut into aligned blocks of B = 16 indices,
// each a (0, 4, 2)-net in every pair of the sampler's dimensions. With b such blocks of sums Y_k:
//   s_B² = Σ (Y_k − Ȳ)² / (b − 1),   Var(mean of n samples) ≈ s_B² · (n/B) / n² = s_B² / (B n).
// The block sums of one Owen-scrambled sequence are exchangeable, with covariance c ≤ 0 between
// blocks (the nets of a larger net stratify against each other), so E[s_B²] = V − c ≥ V: the
// estimate errs high, never low, and by less than the per-sample one, since each block's own
// stratification is in V. (Independent replicates — K scrambles of n/K points each — would be
// unbiased, but lose the sequence's convergence between them: the mean of four independent
// 16-point sequences has about the variance that batch means over 16 estimate, up to 1/0.6 ≈ 1.7×
// the single 64-point sequence's in Layers.VariancePredictsTheSpreadAcrossSeeds' scene.)
//
// The block sums are also nearer normal than single samples, which the χ² bound of
// render/adaptive.h assumes. Below kMinBatches whole blocks (n < 128) the per-sample estimate
// stands in.
#pragma once
#include "render/render_state.h"

namespace insitu {

constexpr int kBatchSamples = 16, kMinBatches = 8;

// Called on a block the moment it holds kBatchSamples samples: it is one batch.
inline void start_batch(PixelSums& block) { block.batch_y = sum_y(block), block.m_batch = 0, block.batches = 1; }

// The variance of one sample's y, as it bears on the pixel's mean (Var(mean) = per_sample / n),
// and the degrees of freedom of its estimate.
struct SampleVariance {
  double per_sample = 0;
  int dof = 0;
};
SampleVariance sample_variance(const PixelSums& p);

// Var(mean of y) after the pixel's samples (0 below 2 samples).
double variance_of_mean(const PixelSums& p);

}  // namespace insitu
