// Renders that survive interruption (issue 15): a stopped render resumes from its state or its
// checkpoint to the image an uninterrupted render gives, bit for bit; a checkpoint of other
// settings is refused; SIGINT/SIGTERM during `insitu render` write the partial image and a
// checkpoint and exit 130, SIGKILL leaves the previous checkpoint valid.
#include <gtest/gtest.h>

#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>

#include <chrono>
#include <limits>
#include <random>
#include <thread>

#include "cli_util.h"
#include "exr_pixels.h"
#include "render/checkpoint.h"
#include "render/pixel_variance.h"
#include "scene/pipeline.h"
#include "scene_fixture.h"

namespace insitu {
namespace {

using test::SceneFixture;
using test::spawn_insitu;
using test::wait_for;

LoadedScene fixture_scene(SceneFixture& fx, int spp) {
  auto j = fx.scene;
  j["render"] = {{"integrator", "path"}, {"spp", spp}};
  j["local_scene"] = {{{"plane", {{"point", {0, 0, 0}}, {"normal", {0, 1, 0}}}}}};
  return load_scene(parse_scene_file(fx.write(j)));
}

void expect_same_layers(const RenderLayers& a, const RenderLayers& b) {
  EXPECT_EQ(a.spp_done, b.spp_done);
  for (const auto& [x, y] : {std::pair{&a.objects, &b.objects},
                             {&a.alpha, &b.alpha},
                             {&a.with_objects, &b.with_objects},
                             {&a.without_objects, &b.without_objects},
                             {&a.variance, &b.variance},
                             {&a.depth, &b.depth},
                             {&a.ratio_variance, &b.ratio_variance}})
    EXPECT_EQ(x->data, y->data);
  EXPECT_EQ(a.mean_relative_noise, b.mean_relative_noise);
}

bool same_sums(const PixelSums& a, const PixelSums& b) {
  return (a.objects == b.objects).all() && (a.with == b.with).all() && (a.without == b.without).all() &&
         (a.albedo == b.albedo).all() && a.normal == b.normal && a.coverage == b.coverage && a.depth == b.depth &&
         a.m_yy == b.m_yy && a.m_ww == b.m_ww && a.m_nn == b.m_nn && a.m_wn == b.m_wn && a.m_batch == b.m_batch &&
         a.met == b.met && a.catcher == b.catcher && a.samples == b.samples && a.batch_y == b.batch_y &&
         a.batches == b.batches;
}

using test::exr_pixels;

// Stopped after pass k (a flag set from the progress callback), then continued from the state:
// the same layers as a render that was never stopped; the partial layers are the means over the
// samples taken.
TEST(Resume, StoppedAndContinuedIsBitIdentical) {
  SceneFixture fx;
  const LoadedScene s = fixture_scene(fx, 24);
  const RenderResult whole = render_scene(s);
  EXPECT_FALSE(whole.layers.interrupted);
  for (int stop_after : {3, 9, 21}) {  // pass ends at 3, 6, …, 24 samples
    std::atomic<bool> stop{false};
    RenderState state;
    const RenderResult part = render_scene(s,
                                           [&](const RenderProgress& p) {
                                             if (p.noise >= 0 && p.spp_done >= stop_after) stop = true;
                                           },
                                           {&stop, &state});
    EXPECT_TRUE(part.layers.interrupted);
    EXPECT_EQ(part.layers.spp_done, stop_after);
    EXPECT_EQ(*part.layers.samples.at(0, 0), float(stop_after));
    const RenderResult rest = render_scene(s, {}, {nullptr, &state});
    expect_same_layers(rest.layers, whole.layers);
    EXPECT_EQ(rest.composite_linear.data, whole.composite_linear.data);
  }
}

// Stopped between tiles of a pass (the flag raised as the k-th tile of the pass reports): the
// pass has done whole tiles [0, tiles_done) in order; those pixels hold the pass's samples and the
// others not (the samples layer says which); continued from the state, or from its checkpoint, to
// the uninterrupted render's layers.
TEST(Resume, StoppedBetweenTilesIsBitIdentical) {
  SceneFixture fx(160, 96);                     // 60 tiles: more than any machine's threads have in flight
  const LoadedScene s = fixture_scene(fx, 16);  // passes of 2 samples
  const RenderResult whole = render_scene(s);
  const int tiles = tiles_across(fx.width) * tiles_across(fx.height);
  ASSERT_GE(tiles, 4) << "the fixture must have several tiles";
  for (int pass : {0, 5}) {
    std::atomic<bool> stop{false};
    int tile_reports = 0;
    RenderState state;
    const RenderResult part = render_scene(s,
                                           [&](const RenderProgress& p) {
                                             if (p.noise < 0 && p.fraction > double(pass) / 8 && ++tile_reports == 2)
                                               stop = true;
                                           },
                                           {&stop, &state});
    ASSERT_TRUE(part.layers.interrupted);
    EXPECT_EQ(state.passes_done, pass);
    EXPECT_GE(state.tiles_done, 2);
    EXPECT_LT(state.tiles_done, tiles);
    EXPECT_EQ(part.layers.spp_done, 2 * pass);
    const int across = tiles_across(fx.width);
    for (int y = 0; y < fx.height; ++y)
      for (int x = 0; x < fx.width; ++x) {
        const int tile = (y / kTilePixels) * across + x / kTilePixels;
        ASSERT_EQ(*part.layers.samples.at(x, y), float(2 * pass + (tile < state.tiles_done ? 2 : 0))) << x << "," << y;
      }
    const std::string path = fx.dir.file("tiles.checkpoint");
    write_checkpoint(path, state, 7);
    RenderState back = read_checkpoint(path, 7);
    EXPECT_EQ(back.tiles_done, state.tiles_done);
    const RenderResult rest = render_scene(s, {}, {nullptr, &back});
    expect_same_layers(rest.layers, whole.layers);
    EXPECT_EQ(rest.layers.samples.data, whole.layers.samples.data);
  }
}

// Stopped at once (RenderControl::stop_at_once, the studio's stop) inside a tile: one tile of
// 16 × 16 pixels, a pass of 8192 samples a pixel (seconds of work), the stop raised 0.1 s after
// the render began. The render returns without finishing the tile: every pixel holds the pass's
// samples whole or none, not all pixels hold them, and the state can be neither resumed nor
// checkpointed. Without stop_at_once the tile would run to its end (all 256 pixels).
TEST(Resume, StoppedAtOnceLeavesWholeSamplesAndNoResumableState) {
  SceneFixture fx(16, 16);
  const LoadedScene s = fixture_scene(fx, 65536);
  std::atomic<bool> stop{false};
  std::thread stopper;
  RenderState state;
  RenderControl control{&stop, &state};
  control.stop_at_once = true;
  const RenderResult part = render_scene(
      s,
      [&](const RenderProgress&) {
        if (!stopper.joinable())
          stopper = std::thread([&] {
            std::this_thread::sleep_for(std::chrono::milliseconds(100));
            stop = true;
          });
      },
      control);
  stopper.join();
  ASSERT_TRUE(part.layers.interrupted);
  EXPECT_FALSE(state.resumable);
  int sampled = 0;
  for (float n : part.layers.samples.data) {
    EXPECT_TRUE(n == 0 || n == 8192) << n;
    sampled += n > 0;
  }
  EXPECT_LT(sampled, 256);
  EXPECT_THROW(render_scene(s, {}, {nullptr, &state}), std::invalid_argument);
  EXPECT_THROW(write_checkpoint(fx.dir.file("at_once.checkpoint"), state, 7), std::invalid_argument);
  EXPECT_FALSE(std::filesystem::exists(fx.dir.file("at_once.checkpoint")));
}

// The state of an 8-spp render of the fixture stopped once a pass is done.
RenderState stopped_after_first_pass(SceneFixture& fx) {
  const LoadedScene s = fixture_scene(fx, 8);
  std::atomic<bool> stop{false};
  RenderState state;
  render_scene(s, [&](const RenderProgress& p) { stop = stop || p.spp_done >= 1; }, {&stop, &state});
  return state;
}

// The checkpoint file: read back as written; refused for another fingerprint, when truncated, and
// when it is not a checkpoint.
// The tiles across a width, ⌈w / 16⌉, for any width a checkpoint's header may claim: near 2³¹
// the old (w + 15) / 16 overflowed (the checkpoint fuzzer found it under UBSan).
TEST(Resume, TilesAcrossAnyWidth) {
  for (int w : {1, 15, 16, 17, 640, 1920}) EXPECT_EQ(tiles_across(w), (w + 15) / 16) << w;
  const int big = std::numeric_limits<int>::max() - 10;
  EXPECT_EQ(tiles_across(big), big / 16 + 1);
  EXPECT_EQ(tiles_across(std::numeric_limits<int>::max()), std::numeric_limits<int>::max() / 16 + 1);
}

TEST(Resume, CheckpointRoundTripAndRefusals) {
  SceneFixture fx;
  const RenderState state = stopped_after_first_pass(fx);
  const std::string path = fx.dir.file("c.checkpoint");
  write_checkpoint(path, state, 42);
  const RenderState back = read_checkpoint(path, 42);
  EXPECT_EQ(back.passes_done, state.passes_done);
  EXPECT_EQ(back.tiles_done, state.tiles_done);
  EXPECT_EQ(back.spp_done, state.spp_done);
  ASSERT_EQ(back.pixels.size(), state.pixels.size());
  for (std::size_t i = 0; i < state.pixels.size(); ++i) {
    ASSERT_EQ(back.pixels[i].size(), state.pixels[i].size()) << "pixel " << i;
    for (std::size_t k = 0; k < state.pixels[i].size(); ++k)
      ASSERT_TRUE(same_sums(back.pixels[i][k], state.pixels[i][k])) << "pixel " << i << " block " << k;
  }
  EXPECT_THROW(read_checkpoint(path, 43), InputError);
  const std::string bytes = test::slurp(path);
  fx.dir.write("short.checkpoint", bytes.substr(0, bytes.size() - 1));
  EXPECT_THROW(read_checkpoint(fx.dir.file("short.checkpoint"), 42), InputError);
  fx.dir.write("text.checkpoint", "INSITUCK");
  EXPECT_THROW(read_checkpoint(fx.dir.file("text.checkpoint"), 42), InputError);
  EXPECT_THROW(read_checkpoint(fx.dir.file("none.checkpoint"), 42), InputError);
}

// A damaged checkpoint is refused by its checksum and kept (issue 46): a changed sum, a NaN and a
// changed tile count still make a consistent state, which resumed to a wrong image with exit 0
// (11 % of pixels at 7 of 8 spp in one case) before the checkpoint was deleted.
TEST(Resume, ADamagedCheckpointIsRefusedAndKept) {
  SceneFixture fx;
  const LoadedScene s = fixture_scene(fx, 8);
  const std::string image = fx.dir.file("out.png"), path = checkpoint_path(image);
  const RenderState state = stopped_after_first_pass(fx);
  write_checkpoint(path, state, render_fingerprint(s));
  const std::string good = test::slurp(path);
  // Offsets: magic, version, block size (16), fingerprint (24), then 8 int32: tiles_done at 48;
  // the pixels' frames follow the settings. A changed byte within the blocks' frame may still
  // decode (zstd checks its structure, not its content): the file's checksum refuses it.
  const float nan = std::numeric_limits<float>::quiet_NaN(), half = 0.5f;
  const std::int32_t one_tile_more = state.tiles_done + 1;
  const std::size_t inside = good.size() - 64;
  for (const auto& [offset, bytes] : std::vector<std::pair<std::size_t, std::string>>{
           {inside, std::string(reinterpret_cast<const char*>(&half), 4)},
           {inside, std::string(reinterpret_cast<const char*>(&nan), 4)},
           {48, std::string(reinterpret_cast<const char*>(&one_tile_more), 4)}}) {
    std::string damaged = good;
    damaged.replace(offset, bytes.size(), bytes);
    ASSERT_NE(damaged, good);
    fx.dir.write("out.png.checkpoint", damaged);
    try {
      read_checkpoint(path, render_fingerprint(s));
      ADD_FAILURE() << "a damaged checkpoint was read (offset " << offset << ")";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("damaged"), std::string::npos) << e.what();
    }
    const test::CliRun r = test::run_insitu(fx.dir, "render " + s.spec.path + " -o " + image + " --resume");
    test::expect_one_line_error(r, "out.png.checkpoint");
    EXPECT_EQ(test::slurp(path), damaged) << "the damaged checkpoint was not kept as it was";
    EXPECT_FALSE(std::filesystem::exists(image));
  }
}

// A pixel's samples come from the file, and its blocks from them: a pixel of more samples than
// the part's range (2^30, as a fuzzer would try, or 16 of 8) or of samples no pass ends at is
// refused as an inconsistent checkpoint before any block is decoded. A state whose blocks are not
// canonical is a caller's error, and is not written.
TEST(Resume, SampleCountsBeyondTheRenderAreRefused) {
  SceneFixture fx;
  const RenderState state = stopped_after_first_pass(fx);
  const std::string path = fx.dir.file("bad.checkpoint");
  for (const int samples : {1 << 30, 16, 3}) {
    RenderState bad = state;
    bad.pixels[0].assign(1, PixelSums{});
    bad.pixels[0][0].samples = samples;
    bad.pixels[0][0].batches = samples >= kBatchSamples ? samples / kBatchSamples : 0;
    if (samples == 3)
      bad.pixels[0] = {bad.pixels[0][0], bad.pixels[0][0]}, bad.pixels[0][0].samples = 2, bad.pixels[0][1].samples = 1;
    write_checkpoint(path, bad, 42);
    try {
      read_checkpoint(path, 42);
      ADD_FAILURE() << "read a pixel of " << samples << " samples";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("inconsistent checkpoint (pixel 0)"), std::string::npos) << e.what();
    }
  }
  RenderState odd = state;
  odd.pixels[0].assign(1, PixelSums{});
  odd.pixels[0][0].samples = 9;
  EXPECT_THROW(write_checkpoint(path, odd, 42), std::invalid_argument);
}

// The fuzz target's seeds (tests/fuzz/corpus/fuzz_checkpoint, written by hand to the layout of
// render/checkpoint.h and converted to each later one) are consistent states, so that fuzzing starts past the header's
// checks: a finished part, and an adaptive render's checkpoint with a pixel stopped after its first pass. A stopped
// pixel whose samples are not those of a pass's end, or a mask byte other than 0 or 1, is refused.
TEST(Resume, FuzzSeedsAreConsistentStates) {
  const std::string dir = test::source_dir() + "/tests/fuzz/corpus/fuzz_checkpoint/";
  const StateFile part = parse_state_bytes(test::slurp(dir + "finished_part.bin"), "finished_part.bin");
  EXPECT_EQ(part.state.spp_done, 4);
  EXPECT_EQ(part.settings, "{\"args\":{}}");
  const StateFile adaptive = parse_state_bytes(test::slurp(dir + "adaptive_checkpoint.bin"), "adaptive_checkpoint.bin");
  EXPECT_EQ(adaptive.state.noise_target, 0.05);
  EXPECT_EQ(adaptive.state.stopped, (std::vector<std::uint8_t>{1, 0}));
  SceneFixture fx;
  const std::string path = fx.dir.file("mask.checkpoint");
  RenderState mask = adaptive.state;
  mask.stopped = {1, 2};
  write_checkpoint(path, mask, adaptive.fingerprint);
  EXPECT_THROW(read_state_file(path), InputError);
  mask.stopped = {1, 1};  // both pixels stopped: pixel 1 has 16 samples, a pass's end too
  write_checkpoint(path, mask, adaptive.fingerprint);
  EXPECT_NO_THROW(read_state_file(path));
}

// The fingerprint follows what the sums depend on, and only that.
TEST(Resume, FingerprintFollowsTheSettingsAndInputs) {
  SceneFixture fx;
  const std::uint64_t a = render_fingerprint(fixture_scene(fx, 8));
  EXPECT_EQ(a, render_fingerprint(fixture_scene(fx, 8)));
  EXPECT_NE(a, render_fingerprint(fixture_scene(fx, 9)));
  SceneSpec spec = fixture_scene(fx, 8).spec;
  spec.render.seed = 2;
  EXPECT_NE(a, render_fingerprint(load_scene(spec)));
  spec.render.seed = 1;
  spec.output.image = fx.dir.file("elsewhere.png");
  EXPECT_EQ(a, render_fingerprint(load_scene(spec)));
  Image photo(fx.width, fx.height, 3, 0.5f);
  write_image(fx.dir.file("photo.png"), photo);
  EXPECT_NE(a, render_fingerprint(fixture_scene(fx, 8)));
}

// Waits for the render's first progress line, "render: 38% (1.2 s) ...": the sample loop is under
// way (tools/progress.cpp prints after its first second). Returns the seconds of sample loop left
// at this pace, 0 when the process ended first (its exit code in *ended) or no line came in 5
// minutes. Timed from the process's own progress, not from the reference render's seconds, so
// that the delay does not depend on how loaded the machine was during the reference run.
double wait_for_sample_loop(pid_t pid, const std::string& err_file, int* ended) {
  const auto give_up = std::chrono::steady_clock::now() + std::chrono::minutes(5);
  while (std::chrono::steady_clock::now() < give_up) {
    const std::string err = test::slurp(err_file);
    const std::size_t at = err.find("render: ");
    double percent = 0, elapsed = 0;
    if (at != std::string::npos && err.find('\n', at) != std::string::npos &&
        std::sscanf(err.c_str() + at, "render: %lf%% (%lf s)", &percent, &elapsed) == 2 && percent > 0)
      return elapsed * (100 - percent) / percent;
    int status = 0;
    if (waitpid(pid, &status, WNOHANG) == pid) {
      *ended = WIFEXITED(status) ? WEXITSTATUS(status) : 1000 + WTERMSIG(status);
      return 0;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return 0;
}

// Interrupted by SIGINT or SIGTERM at random moments of the sample loop, resumed (and interrupted
// again) until done: the image and the layers are those of an uninterrupted render, bit for bit.
// A SIGKILL on the way leaves the last checkpoint valid. Each signal is sent at a random moment
// of what is left of the loop once its first progress line shows; one that lands after the
// render finished is the end of that trial.
TEST(Resume, KilledAtRandomMomentsResumesToTheSameImage) {
  SceneFixture fx;
  auto j = fx.scene;
  // About 2 s of sample loop in the release build (a few times that under the sanitizers, whose
  // share of the load time grows alike): room for a signal to land in it.
  j["render"] = {{"integrator", "path"}, {"spp", test::kUnderAsan ? 512 : 4096}};
  j["local_scene"] = {{{"plane", {{"point", {0, 0, 0}}, {"normal", {0, 1, 0}}}}}};
  const std::string scene = fx.write(j);
  const std::string ref_args = "render " + scene + " -o " + fx.dir.file("ref.exr");
  ASSERT_EQ(test::run_insitu(fx.dir, ref_args).exit_code, 0);
  std::mt19937 rng(7);
  int interrupted = 0;
  // Three trials; under the sanitizers one (35 s there; its signals are the same three kinds).
  for (int trial = 0; trial < (test::kUnderAsan ? 1 : 3); ++trial) {
    const std::string out = fx.dir.file("run" + std::to_string(trial) + ".exr");
    std::string resume;
    for (int attempt = 0; attempt < 12; ++attempt) {
      std::filesystem::remove(fx.dir.file("bg.err"));  // not the last run's line
      const pid_t pid = spawn_insitu(fx.dir, "render " + scene + " -o " + out + resume);
      int code = -1;
      const double left_s = wait_for_sample_loop(pid, fx.dir.file("bg.err"), &code);
      const int sig = attempt == 2 ? SIGKILL : (attempt % 2 ? SIGTERM : SIGINT);
      if (code < 0) {
        std::this_thread::sleep_for(
            std::chrono::duration<double>(std::uniform_real_distribution<double>(0.0, 0.8)(rng) * left_s));
        kill(pid, sig);
        code = wait_for(pid);
      }
      if (code == 0) break;
      if (code == 130) {
        ++interrupted, resume = " --resume";
        EXPECT_TRUE(std::filesystem::exists(out + ".checkpoint"));
      } else {
        EXPECT_EQ(code, 1000 + sig) << test::slurp(fx.dir.file("bg.err"));
        // Killed after the render had finished — its image written, its checkpoint used up and
        // removed — on its way out (under the sanitizers the leak check at exit leaves time for
        // that): it is done, and a --resume would rightly find no checkpoint (CI of f4c678a).
        if (!resume.empty() && !std::filesystem::exists(out + ".checkpoint")) break;
      }
    }
    if (!std::filesystem::exists(out) || std::filesystem::exists(out + ".checkpoint")) {  // never finished: finish now
      ASSERT_EQ(test::run_insitu(fx.dir, "render " + scene + " -o " + out + resume).exit_code, 0);
    }
    EXPECT_TRUE(exr_pixels(out) == exr_pixels(fx.dir.file("ref.exr"))) << "trial " << trial;
    EXPECT_TRUE(exr_pixels(fx.dir.file("run" + std::to_string(trial) + ".layers.exr")) ==
                exr_pixels(fx.dir.file("ref.layers.exr")))
        << "trial " << trial;
    EXPECT_FALSE(std::filesystem::exists(out + ".checkpoint")) << "a finished render leaves no checkpoint";
  }
  EXPECT_GT(interrupted, 0) << "no signal landed in the sample loop";
}

// A checkpoint is refused for other settings (one-line error, exit 2), and --resume without one.
TEST(Resume, CheckpointOfOtherSettingsIsRefused) {
  SceneFixture fx;
  auto j = fx.scene;
  j["render"] = {{"integrator", "path"}, {"spp", 8}};
  const std::string scene = fx.write(j);
  const std::string out = fx.dir.file("o.exr");
  test::expect_one_line_error(test::run_insitu(fx.dir, "render " + scene + " -o " + out + " --resume"),
                              "no checkpoint");
  // A checkpoint written for spp 8, resumed with spp 9.
  const LoadedScene s = load_scene(parse_scene_file(scene));
  std::atomic<bool> stop{true};
  RenderState state;
  render_scene(s, {}, {&stop, &state});
  write_checkpoint(out + ".checkpoint", state, render_fingerprint(s));
  test::expect_one_line_error(test::run_insitu(fx.dir, "render " + scene + " -o " + out + " --resume --spp 9"),
                              "another scene, other inputs or other settings");
  EXPECT_EQ(test::run_insitu(fx.dir, "render " + scene + " -o " + out + " --resume").exit_code, 0);
}

}  // namespace
}  // namespace insitu
