// Adaptive sampling (issue 16, render/adaptive.h): the variance bound is the χ² quantile's; the
// stopping rule is honest where a pixel's own samples would lie (a rare bright path), where the
// naive rule — a pixel's own sample variance — is shown to fail on the same data; a render with a
// noise target reaches it against an independent reference, spends fewer samples than the fixed
// count, resumes bit for bit, and refuses to be split.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <random>

#include "cli_util.h"
#include "render/adaptive.h"
#include "render/checkpoint.h"
#include "render/pixel_blocks.h"
#include "scene/pipeline.h"
#include "scene_fixture.h"

namespace insitu {
namespace {

using test::SceneFixture;

// k / χ²_0.05(k) from the published table (Abramowitz & Stegun, table 26.8): χ²_0.05(15) = 7.261,
// χ²_0.05(30) = 18.493, χ²_0.05(63) ≈ 45.741, χ²_0.05(100) = 77.929.
TEST(Adaptive, VarianceBoundIsTheChiSquareQuantile) {
  for (const auto& [n, chi2] : {std::pair{16, 7.261}, {31, 18.493}, {64, 45.741}, {101, 77.929}})
    EXPECT_NEAR(variance_upper_bound_factor(n), (n - 1) / chi2, 0.01 * (n - 1) / chi2) << n;
  EXPECT_EQ(variance_upper_bound_factor(2), INFINITY);
}

// An adaptive render's passes (render_state.h): from 0 to n, increasing, each but the last
// ending on a multiple of 16 (whole batches), the first of max(16, n/16), the rest of
// max(16, n/64) rounded up to 16.
TEST(Adaptive, PassesAreShortAndEndOnWholeBatches) {
  for (int n : {1, 10, 16, 17, 100, 256, 512, 1000, 1024, 4096, 100000}) {
    const int passes = adaptive_passes(n);
    EXPECT_EQ(adaptive_pass_start(n, 0), 0);
    EXPECT_EQ(adaptive_pass_start(n, passes), n) << n;
    EXPECT_EQ(adaptive_pass_start(n, 1), std::min(n, std::max(16, (n / 16 + 15) / 16 * 16))) << n;
    for (int k = 1; k <= passes; ++k) {
      const int a = adaptive_pass_start(n, k - 1), b = adaptive_pass_start(n, k);
      EXPECT_GT(b, a) << n << " pass " << k;
      if (k < passes) {
        EXPECT_EQ(b % 16, 0) << n << " pass " << k;
      }
      if (k > 1 && k < passes) {
        EXPECT_EQ(b - a, std::max(16, (n / 64 + 15) / 16 * 16)) << n;
      }
    }
  }
  EXPECT_EQ(adaptive_passes(1024), 61);  // 64, then 60 of 16
}

// A pixel's sums over samples of luminance `y` (all on the catcher: with = y, without = 0).
void add_sample(PixelSums& p, double y) {
  PixelSums leaf;
  leaf.with = Rgb::Constant(float(y));
  leaf.catcher = 1, leaf.samples = 1;
  add_sums(p, leaf);
}

TEST(Adaptive, ErrorPoolsTheChangedNeighbours) {
  std::vector<PixelSums> sums(9);
  for (int k = 0; k < 32; ++k)
    for (std::size_t i = 0; i < sums.size(); ++i) add_sample(sums[i], i == 0 ? 1.0 : (k % 2 ? 2.0 : 0.0));
  // Pixel 0 (value 1) has no variance of its own. Its 3 × 3 window, at the corner, holds pixels
  // 0, 1, 3 and 4, all changed; the other three have s² = 32/31. The mean over the four is raised
  // by the bound of 4 × 31 degrees of freedom.
  const double pooled = 3.0 / 4.0 * 32.0 / 31.0 * variance_upper_bound_factor(4 * 31 + 1);
  EXPECT_NEAR(honest_relative_error(sums, 3, 3, 0), std::sqrt(pooled / 32), 1e-9);
  // The centre sees all nine, 8 noisy, 9 × 31 degrees of freedom; its own s², bounded with its 31,
  // if that is more.
  const double centre = 8.0 / 9.0 * 32.0 / 31.0 * variance_upper_bound_factor(9 * 31 + 1);
  const double centre_own = 32.0 / 31.0 * variance_upper_bound_factor(32);
  EXPECT_NEAR(honest_relative_error(sums, 3, 3, 4), std::sqrt(std::max(centre, centre_own) / 32), 1e-9);
  // A pixel noisier than its neighbourhood keeps its own variance: pixel 4 of nine whose others
  // are noiseless but changed.
  std::vector<PixelSums> lone(9);
  for (int k = 0; k < 32; ++k)
    for (std::size_t i = 0; i < lone.size(); ++i) add_sample(lone[i], i == 4 ? (k % 2 ? 2.0 : 0.0) : 1.0);
  const double own = 32.0 / 31.0 * variance_upper_bound_factor(32);
  const double lone_pool = 32.0 / 31.0 / 9 * variance_upper_bound_factor(9 * 31 + 1);
  EXPECT_NEAR(honest_relative_error(lone, 3, 3, 4), std::sqrt(std::max(own, lone_pool) / 32), 1e-9);
  EXPECT_GT(own, lone_pool);
  // Unchanged everywhere: nothing to judge, error 0; noise over a value of 0: infinite.
  std::vector<PixelSums> calm(4);
  for (PixelSums& p : calm) p.samples = 16;
  EXPECT_EQ(honest_relative_error(calm, 2, 2, 0), 0.0);
  PixelSums zero;
  for (int k = 0; k < 16; ++k) add_sample(zero, k % 2 ? 1.0 : -1.0);
  EXPECT_EQ(honest_relative_error({zero}, 1, 1, 0), INFINITY);
}

// Pixels whose samples are 1, or 21 with probability 0.05 (mean 2, relative deviation 2.2 per
// sample): after 16 samples 44 % of them have not seen the bright path and have no variance of
// their own. Passes of 16 samples, up to 1024, stopping at τ = 10 % (about 480 samples): the
// stopped pixels' true error stays within the target, where the naive rule stops those 50 % too
// dark.
struct Outcome {
  double rms_over_target = 0, far_off = 0;  // RMS of error/τ; share with |error| > 3τ
};

// A sample of luminance y as the renderer stacks it: a leaf pushed onto the pixel's blocks
// (render/pixel_blocks.h), so that from 128 samples on the rule reads batch means.
void push_sample(PixelBlocks& blocks, double y) {
  PixelSums leaf;
  add_sample(leaf, y);
  push_block(blocks, 0, leaf);
}

template <class Stop>
Outcome simulate(Stop stop, std::uint32_t seed) {
  const int w = 64, h = 64;
  const double tau = 0.1, truth = 1 + 20 * 0.05;
  std::mt19937 rng(seed);
  std::bernoulli_distribution bright(0.05);
  std::vector<PixelBlocks> blocks(std::size_t(w * h));
  std::vector<PixelSums> sums(blocks.size());
  std::vector<std::uint8_t> stopped(sums.size(), 0);
  for (int pass = 0; pass < 64; ++pass) {
    for (std::size_t i = 0; i < sums.size(); ++i) {
      for (int k = 0; k < 16 && !stopped[i]; ++k) push_sample(blocks[i], bright(rng) ? 21.0 : 1.0);
      sums[i] = fold_blocks(blocks[i]);
    }
    stop(sums, w, h, tau, stopped);
  }
  Outcome o;
  int n = 0;
  for (std::size_t i = 0; i < sums.size(); ++i) {
    if (sums[i].samples >= 1024) continue;  // ran to the cap: not stopped by the rule
    const double e = (sum_y(sums[i]) / sums[i].samples - truth) / truth / tau;
    o.rms_over_target += e * e, o.far_off += std::abs(e) > 3, ++n;
  }
  EXPECT_GT(n, w * h / 2) << "most pixels stop before the cap";
  o.rms_over_target = std::sqrt(o.rms_over_target / std::max(1, n));
  o.far_off /= std::max(1, n);
  return o;
}

// The naive rule: a pixel's own sample variance, unbounded, unpooled.
void naive_stop(const std::vector<PixelSums>& sums, int, int, double tau, std::vector<std::uint8_t>& stopped) {
  for (std::size_t i = 0; i < sums.size(); ++i) {
    const PixelSums& p = sums[i];
    const double mean = sum_y(p) / p.samples, var = double(p.m_yy) / (p.samples - 1) / p.samples;
    if (!stopped[i] && std::sqrt(var) <= tau * mean) stopped[i] = 1;
  }
}

TEST(Adaptive, StoppingIsHonestWhereTheNaiveRuleIsNot) {
  const Outcome honest = simulate(stop_converged, 11);
  // An unbiased estimate stopped at τ has RMS error about τ; stopping when the estimate happens
  // to be low biases it up, which the variance bound must more than pay for.
  std::printf("honest: rms %.2f τ, %.2f%% beyond 3τ\n", honest.rms_over_target, 100 * honest.far_off);
  EXPECT_LT(honest.rms_over_target, 1.0);
  EXPECT_LT(honest.far_off, 0.01);
  const Outcome naive = simulate(naive_stop, 11);
  std::printf("naive: rms %.2f τ, %.2f%% beyond 3τ\n", naive.rms_over_target, 100 * naive.far_off);
  EXPECT_GT(naive.far_off, 0.2) << "the test must be able to fail: the naive rule is fooled here";
}

// The fixture with a sun: one texel of its environment 400× the sky, so that the quad's shadow
// on the catcher plane is sharp and its penumbra noisy.
LoadedScene sunny_scene(SceneFixture& fx, int spp, double noise_target, const char* integrator = "path",
                        bool catcher = true) {
  Image env(16, 8, 3, 0.5f);
  env.set_rgb(5, 2, Rgb(200.0f, 190.0f, 170.0f));
  write_image(fx.dir.file("sun.exr"), env);
  auto j = fx.scene;
  j["environment"] = "sun.exr";
  j["render"] = {{"integrator", integrator}, {"spp", spp}, {"noise_target", noise_target}};
  if (catcher) j["local_scene"] = {{{"plane", {{"point", {0, 0, 0}}, {"normal", {0, 1, 0}}}}}};
  j["objects"] = {{{"mesh", "good_quad.obj"}, {"translate", {0, 0.3, 0}}}};
  return load_scene(parse_scene_file(fx.write(j)));
}

double value_of(const RenderLayers& l, int x, int y) {
  return std::abs(luminance(Rgb(l.objects.rgb(x, y) + l.with_objects.rgb(x, y) - l.without_objects.rgb(x, y)))) +
         luminance(l.without_objects.rgb(x, y));
}

// Against a reference of 2048 spp with another seed: over the pixels the rule stopped, the mean
// squared relative error is at most τ² plus the reference's own (its variance layer), within the
// spread of a mean over some hundred pixels (×1.5). And the render took fewer samples.
TEST(AdaptiveRender, ReachesTheTargetAgainstAReference) {
  SceneFixture fx;
  const double tau = 0.03;
  const RenderResult adaptive = render_scene(sunny_scene(fx, 1024, tau));
  LoadedScene ref_scene = sunny_scene(fx, 2048, 0);
  ref_scene.spec.render.seed = 7;
  const RenderResult ref = render_scene(ref_scene);
  double err2 = 0, ref2 = 0, samples = 0;
  int n = 0;
  for (int y = 0; y < fx.height; ++y)
    for (int x = 0; x < fx.width; ++x) {
      const float spp = *adaptive.layers.samples.at(x, y);
      samples += spp;
      const double v = value_of(ref.layers, x, y);
      if (spp >= 1024 || !(v > 0) || *ref.layers.variance.at(x, y) == 0) continue;
      const double d = value_of(adaptive.layers, x, y) - v;
      err2 += d * d / (v * v), ref2 += *ref.layers.variance.at(x, y) / (v * v), ++n;
    }
  ASSERT_GT(n, 100);
  std::printf("%d stopped pixels: rms %.4f, target %.4f, reference's own %.4f, mean spp %.0f\n", n, std::sqrt(err2 / n),
              tau, std::sqrt(ref2 / n), samples / (fx.width * fx.height));
  EXPECT_LT(err2 / n, 1.5 * (tau * tau + ref2 / n)) << "rms " << std::sqrt(err2 / n) << " over " << n << " pixels";
  EXPECT_LT(samples / (fx.width * fx.height), 0.8 * 1024);
}

// Without a catcher, what the objects do not cover cannot change: those pixels stop at the first
// judgement (the first pass: 32 of 512 samples, render_state.h), and so does every pixel of the
// realtime path that no object's edge crosses within a pixel (its only noise is an edge's
// coverage, which the pooled variance of render/adaptive.h passes on to the neighbours).
bool near_an_edge(const RenderLayers& l, int x, int y) {
  for (int ny = std::max(0, y - 1); ny <= std::min(l.alpha.height - 1, y + 1); ++ny)
    for (int nx = std::max(0, x - 1); nx <= std::min(l.alpha.width - 1, x + 1); ++nx)
      if (*l.alpha.at(nx, ny) != 0 && *l.alpha.at(nx, ny) != 1) return true;
  return false;
}

TEST(AdaptiveRender, UnchangedAndNoiselessPixelsStopAtTheFirstPass) {
  SceneFixture fx;
  const RenderResult path = render_scene(sunny_scene(fx, 512, 0.01, "path", false));
  const RenderResult realtime = render_scene(sunny_scene(fx, 512, 0.01, "realtime", false));
  int background = 0, inside = 0;
  for (int y = 0; y < fx.height; ++y)
    for (int x = 0; x < fx.width; ++x) {
      if (!near_an_edge(realtime.layers, x, y)) {
        EXPECT_EQ(*realtime.layers.samples.at(x, y), float(adaptive_first_pass(512))) << x << "," << y;
      }
      inside += *realtime.layers.alpha.at(x, y) == 1 && !near_an_edge(realtime.layers, x, y);
      if (*path.layers.alpha.at(x, y) > 0) continue;
      EXPECT_EQ(*path.layers.samples.at(x, y), float(adaptive_first_pass(512))) << x << "," << y;
      ++background;
    }
  EXPECT_GT(background, 100);
  EXPECT_GT(inside, 20);
}

// Stopped after a pass and continued, from the state and from its checkpoint: the layers of the
// render never stopped, samples layer included (the stopped pixels are in the state).
TEST(AdaptiveRender, ResumesBitForBit) {
  SceneFixture fx;
  const LoadedScene s = sunny_scene(fx, 256, 0.05);
  const RenderResult whole = render_scene(s);
  for (int stop_after : {64, 160}) {
    std::atomic<bool> stop{false};
    RenderState state;
    render_scene(s,
                 [&](const RenderProgress& p) {
                   if (p.noise >= 0 && p.spp_done >= stop_after) stop = true;
                 },
                 {&stop, &state});
    const std::string path = fx.dir.file("adaptive.checkpoint");
    write_checkpoint(path, state, 7);
    RenderState back = read_checkpoint(path, 7);
    EXPECT_EQ(back.stopped, state.stopped);
    for (RenderState* from : {&state, &back}) {
      RenderState copy = *from;
      const RenderResult rest = render_scene(s, {}, {nullptr, &copy});
      EXPECT_EQ(rest.layers.samples.data, whole.layers.samples.data) << stop_after;
      EXPECT_EQ(rest.layers.with_objects.data, whole.layers.with_objects.data) << stop_after;
      EXPECT_EQ(rest.layers.objects.data, whole.layers.objects.data) << stop_after;
    }
  }
}

// A part of a split render cannot judge its pixels' noise: refused, on the command line with one
// line and exit code 2, in the library with an exception.
TEST(AdaptiveRender, SplitRendersAreRefused) {
  SceneFixture fx;
  const LoadedScene s = sunny_scene(fx, 64, 0.05);
  EXPECT_THROW(render_scene(s, {}, {nullptr, nullptr, 0, 32}), std::invalid_argument);
  const auto r = test::run_insitu(fx.dir, "render " + fx.dir.file("scene.json") + " --samples 0:32");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("noise"), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  const auto ok = test::run_insitu(fx.dir, "render " + fx.dir.file("scene.json") + " --samples 0:32 --noise-target 0");
  EXPECT_EQ(ok.exit_code, 0) << ok.err;
}

}  // namespace
}  // namespace insitu
