// insitu against an independent renderer (issue 12; docs/validation.md). tools/validate/ built
// the open-ground and the closed-room scenes in Blender and rendered them with Cycles 3.4: the
// empty photo, the photo with the objects (the truth, twice, with two seeds), the objects' coverage
// and six HDR shots from the insertion point. Their small outputs are test data, committed in
// tests/data/validation/<scene>; here insitu renders them with the true camera and is measured over
// the objects and the pixels they change, with the regions of tools/validate/metrics.py.
#include <gtest/gtest.h>

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>

#include "core/colour.h"
#include "scene/pipeline.h"
#include "scene/scene_file.h"
#include "test_util.h"

namespace insitu {
namespace {

// All channels of an EXR (Blender writes RGBA).
Image read_all_channels(const std::string& path) {
  auto in = OIIO::ImageInput::open(path);
  if (!in) return {};
  const OIIO::ImageSpec& spec = in->spec();
  Image img(spec.width, spec.height, spec.nchannels);
  in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, img.data.data());
  return img;
}

float lum(const Image& img, int i) {
  const float* p = &img.data[std::size_t(i) * img.channels];
  return 0.2126f * p[0] + 0.7152f * p[1] + 0.0722f * p[2];
}

// The regions of metrics.py: the objects (coverage α > 0.01), and the other pixels whose
// luminance the objects change by more than 3 % (3 × 3 mean of |Y_truth − Y_photo|).
std::vector<bool> objects_and_changed(const Image& truth, const Image& photo, const Image& coverage) {
  const int w = truth.width, h = truth.height;
  std::vector<bool> mask(std::size_t(w) * h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      double s = 0;
      int k = 0;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const int xx = x + dx, yy = y + dy;
          if (xx < 0 || yy < 0 || xx >= w || yy >= h) continue;
          s += std::abs(lum(truth, yy * w + xx) - lum(photo, yy * w + xx));
          ++k;
        }
      const int i = y * w + x;
      const bool object = coverage.data[std::size_t(i) * coverage.channels + 3] > 0.01f;
      mask[std::size_t(i)] = object || s / k > 0.03 * std::max(lum(photo, i), 1e-6f);
    }
  return mask;
}

// sqrt(Σ_R (a − t)²) / sqrt(Σ_R t²) over RGB.
double relative_rmse(const Image& a, const Image& t, const std::vector<bool>& mask) {
  double se = 0, st = 0;
  for (std::size_t i = 0; i < mask.size(); ++i)
    if (mask[i])
      for (int c = 0; c < 3; ++c) {
        const double d = a.data[i * a.channels + c] - t.data[i * t.channels + c];
        se += d * d;
        st += double(t.data[i * t.channels + c]) * t.data[i * t.channels + c];
      }
  return std::sqrt(se / st);
}

// The goals of issue 12 are 3 % (open ground, at 1024 spp) and 8 % (closed room). At the 256 spp
// rendered here insitu's own noise adds to that, and the truth's noise to both: the bound is
// sqrt(goal² + σ_insitu² + σ_truth²), with σ_insitu its standard error from the variance layer
// over the region and σ_truth the truth's own (truth against truth2, / √2).
// The scene's six HDR shots as a phone takes them (tools/validate/jpeg_shots.sh): 8-bit sRGB JPEGs
// exposed so that the floor shot's mean luminance is 18 % grey, everything brighter clipped, and
// the scene's exposure the inverse of that scale.
void use_jpeg_shots(SceneSpec& spec, const test::TempDir& dir) {
  const Image down = read_image_file(spec.environment.shots[kNegY].files.front()).stored;
  double mean = 0;
  for (int i = 0; i < down.width * down.height; ++i) mean += luminance(down.rgb(i % down.width, i / down.width));
  const double k = 0.18 / (mean / (down.width * down.height));
  for (int f = 0; f < 6; ++f) {
    auto& files = spec.environment.shots[std::size_t(f)].files;
    Image shot = read_image_file(files.front()).stored;
    for (float& v : shot.data) v = linear_to_srgb(std::clamp(float(k) * v, 0.0f, 1.0f));
    files = {dir.file(std::string("shot") + std::to_string(f) + ".jpg")};
    write_image(files.front(), shot);
  }
  spec.environment.exposure = EnvironmentSpec::Exposure::kFactor;
  spec.environment.exposure_factor = 1.0 / k;
}

// The objects' mean luminance over the truth's (coverage ≥ ½).
double objects_brightness(const Image& a, const Image& truth, const Image& coverage) {
  double sa = 0, st = 0;
  for (int i = 0; i < truth.width * truth.height; ++i)
    if (coverage.data[std::size_t(i) * coverage.channels + 3] >= 0.5f) sa += lum(a, i), st += lum(truth, i);
  return sa / std::max(1e-30, st);
}

// Under AddressSanitizer the scene is loaded and rendered at 4 spp for its memory checks only:
// the physics is the release build's to check, and 256 spp sanitized would add ten minutes to CI.
// `goal` 0: the error is reported, not bounded (a goal not yet met, docs/validation.md).
// Returns the error (−1 when skipped); `edit` changes the scene first.
double check_against_cycles(const std::string& name, double goal, bool jpeg = false,
                            const std::function<void(SceneSpec&)>& edit = {}) {
  const std::string out = test::test_data("validation/" + name);
  if (!std::ifstream(out + "/scene.json")) {
    [&] { GTEST_SKIP() << out << " is absent"; }();
    return -1;
  }
  SceneSpec spec = parse_scene_file(out + "/scene.json");
  if (edit) edit(spec);
  spec.render.spp = 256;
#ifdef INSITU_UNDER_ASAN
  spec.render.spp = 4;
#endif
  test::TempDir dir;
  if (jpeg) use_jpeg_shots(spec, dir);
  const LoadedScene scene = load_scene(spec);
  const RenderResult r = render_scene(scene);
#ifdef INSITU_UNDER_ASAN
  EXPECT_EQ(r.layers.nonfinite_samples, 0u);
  [] { GTEST_SKIP() << "the error bound is checked in the release build, not under AddressSanitizer"; }();
  return -1;
#endif
  const Image truth = read_all_channels(out + "/truth.exr"), truth2 = read_all_channels(out + "/truth2.exr");
  const Image photo = read_all_channels(out + "/photo.exr"), coverage = read_all_channels(out + "/coverage.exr");
  if (truth.width != r.composite_linear.width || coverage.channels != 4) {
    ADD_FAILURE() << out << ": the truth is " << truth.width << " wide, the render " << r.composite_linear.width;
    return -1;
  }
  const std::vector<bool> mask = objects_and_changed(truth, photo, coverage);
  double var = 0, t2 = 0;
  for (std::size_t i = 0; i < mask.size(); ++i)
    if (mask[i]) {
      var += 3 * r.layers.variance.data[i];
      for (int c = 0; c < 3; ++c) t2 += double(truth.data[i * truth.channels + c]) * truth.data[i * truth.channels + c];
    }
  const double sigma_insitu = std::sqrt(var / t2), sigma_truth = relative_rmse(truth2, truth, mask) / std::sqrt(2.0);
  const double bound = std::sqrt(goal * goal + sigma_insitu * sigma_insitu + sigma_truth * sigma_truth);
  const double error = relative_rmse(r.composite_linear, truth, mask);
  if (goal > 0) {
    EXPECT_LT(error, bound) << "σ_insitu " << sigma_insitu << ", σ_truth " << sigma_truth;
  }
  const double brightness = objects_brightness(r.composite_linear, truth, coverage);
  if (jpeg) {
    EXPECT_NEAR(brightness, 1.0, 0.1);
  }
  std::printf(
      "validation: %s%s, 256 spp: %.2f %% (bound %.2f %%: σ_insitu %.2f %%, σ_truth %.2f %%), objects' brightness "
      "%.3f\n",
      name.c_str(), jpeg ? " (JPEG shots)" : "", 100 * error, 100 * bound, 100 * sigma_insitu, 100 * sigma_truth,
      brightness);
  return error;
}

// The edit that adds a grey ball (albedo 0.18, radius 0.15 m) at `center`, on a plate of its own:
// the photo of validation scene `name`, the same view with the ball.
std::function<void(SceneSpec&)> grey_ball_on_a_plate(const std::string& name, const Vec3d& center) {
  return [=](SceneSpec& spec) {
    ReferenceSpec ball;
    ball.ball = BallSpec{center, 0.15};
    ball.albedo = 0.18;
    ball.photo = test::test_data("validation/" + name + "/photo.exr");
    spec.references.push_back(ball);
  };
}

constexpr double kOpenGroundGoal = 0.03;

// The grey-ball scenes' bounds: issue 13's, 1.5 × the same scene's error from its HDR shots, and an
// absolute one of their own (issue 46: a regression of both renders kept the ratio): neither the
// HDR render nor the JPEG one beyond 1.5 × the open ground's goal (4.5 %; measured 2.5 to 3.2 %
// from HDR shots, 2.9 to 3.9 % from JPEG shots).
constexpr double kBallAbsoluteGoal = 1.5 * kOpenGroundGoal;
double ball_jpeg_goal(double hdr) { return std::min(1.5 * hdr, kBallAbsoluteGoal); }

// The open ground from its HDR shots. Then, from its JPEG shots, the grey ball of the edge scene
// (tools/validate/open_ground_ball_edge; AGreyBallAtACheckEdgeFromJpegShots below) on a plate of
// its own: the photo and the truth are the open ground's, the plate the edge scene's photo, its
// shadow zone divided by the clean photo (divide_by_clean_photo) and its underside lit by the
// plate's floor. Held to the grey ball's bounds against this HDR render's error (here, so that the
// open ground's HDR render is made once).
TEST(Validation, OpenGroundAgainstCyclesWithinTheGoal) {
  const double hdr = check_against_cycles("open_ground", kOpenGroundGoal);
  if (hdr < 0) return;  // skipped: no Cycles truth, or under AddressSanitizer
  check_against_cycles("open_ground", ball_jpeg_goal(hdr), true,
                       grey_ball_on_a_plate("open_ground_ball_edge", Vec3d(1.4, 0.15, 0.6)));
}

// A closed room: a low sun through the window (an opening of the room box), a ceiling lamp, the
// sofa near a wall that catches its shadow.
TEST(Validation, ClosedRoomAgainstCyclesWithinTheGoal) { check_against_cycles("closed_room", 0.08); }

// The same room from single clipped JPEG shots (issue 13): the sun, the lamp and the bright sky
// recovered by inverse lighting against the photo, within 1.5 × the HDR goal and the objects'
// brightness within 10 %. A six-texel speck beside the window (true added power 0) is one source
// with it, and must be held at the lower bound, not fitted with it whole: 33.4 % without that.
TEST(Validation, ClosedRoomFromJpegShotsWithinTheGoal) { check_against_cycles("closed_room", 1.5 * 0.08, true); }

// The open ground with a grey ball in the real scene, given as a reference (issue 13): from clipped
// JPEG shots the ball tells the ceiling lamps from the windows (the objects 0.67× as bright without
// it). Issue 13's goal: the error at most 1.5 × the same scene's error from its HDR shots, rendered
// here too, and the objects' brightness within 10 %. Without the smoothing within a source
// (kReferenceSmoothing) 5.2 % from the CLI's JPEG shots, against 1.5 × 2.6 %: how the fit divided
// the missing light among a window's parts (docs/validation.md "Priors on the parts").
// Not under AddressSanitizer: with it and the ball's unit tests, their shard took 824 s there
// instead of 51 s, near CI's budget; the ball's code paths run sanitized in InverseLighting's tests.
//
// The same ball on a plate of its own: the photo and the truth are the open ground's, without the
// ball; the plate is the ball scene's photo, the same view with the ball and its shadow. The plate
// holds what the ball in the photo held, so the error must be the same: within 1.3× the error with
// the ball in the photo (measured 5.25 % against 5.21 %; from the CLI's JPEG shots 33 % before the
// plate's shadow zone was read and the floor's uninformative pixels left the fit, the ceiling lamps
// then undetermined). One test, so that the ball in the photo is rendered once.
TEST(Validation, OpenGroundWithAGreyBallFromJpegShots) {
#ifdef INSITU_UNDER_ASAN
  GTEST_SKIP() << "the ball's fit runs sanitized in InverseLighting.AGreyBall*";
#endif
  const double hdr = check_against_cycles("open_ground_ball", kBallAbsoluteGoal, false);
  if (hdr < 0) return;  // skipped: no Cycles truth
  const double in_photo = check_against_cycles("open_ground_ball", ball_jpeg_goal(hdr), true);
  const double on_plate = check_against_cycles("open_ground", kBallAbsoluteGoal, true,
                                               grey_ball_on_a_plate("open_ground_ball", Vec3d(-0.6, 0.15, 1.6)));
  if (on_plate >= 0) {
    EXPECT_LT(on_plate, 1.3 * in_photo) << "on a plate";
  }
}

// The grey ball raised on a rod, beside the orange ball (tools/validate/open_ground_raised_ball,
// docs/validation.md "A raised ball"): the ceiling lamps' shadows fall clear of its foot. With the
// clipped regions beyond the fourth merged into one source, the lamps (15 texels each, the least
// power at the clip level) shared one scale with the windows' edges and the specks, and the fit
// sent the missing light to the windows: the objects 1.53× too bright, 57 % error (from the CLI's
// JPEG shots). Every region its own source and σ in scaled units: 13.3 %, brightness 1.03; regions
// closer than a part's width one source, with the parts the photo cannot tell held at the lower
// bound: 7.0 %, 1.023; with the smoothing within a source: 4.3 %. Held to issue 13's goal, as above.
TEST(Validation, OpenGroundWithARaisedGreyBallFromJpegShots) {
#ifdef INSITU_UNDER_ASAN
  GTEST_SKIP() << "the ball's fit runs sanitized in InverseLighting.AGreyBall*";
#endif
  const double hdr = check_against_cycles("open_ground_raised_ball", kBallAbsoluteGoal, false);
  if (hdr >= 0) check_against_cycles("open_ground_raised_ball", ball_jpeg_goal(hdr), true);
}

// The grey ball resting near the photo's right edge, on a dark check at the edge of a light one
// (tools/validate/open_ground_ball_edge; docs/validation.md, "What the ball sees below it"): a
// placement held out from every choice in the fit. Its underside sees the dark check, where the
// shots' floor (the cube's lower half) is both checks' mean: lit by that, the fit sent the light of
// a window at −x to a speck toward −z (from the CLI's JPEG shots 11.8 %, against 2.6 % from HDR
// shots). Lit by the floor the photo shows (light_balls_from_the_floor): 2.9 %. Held to issue 13's
// goal, 1.5 × the same scene's error from its HDR shots, rendered here too.
// The same ball on a plate of its own: in OpenGroundAgainstCyclesWithinTheGoal.
TEST(Validation, AGreyBallAtACheckEdgeFromJpegShots) {
#ifdef INSITU_UNDER_ASAN
  GTEST_SKIP() << "the ball's fit runs sanitized in InverseLighting.AGreyBall*";
#endif
  const double hdr = check_against_cycles("open_ground_ball_edge", kBallAbsoluteGoal, false);
  if (hdr < 0) return;  // skipped: no Cycles truth
  check_against_cycles("open_ground_ball_edge", ball_jpeg_goal(hdr), true);
}

}  // namespace
}  // namespace insitu
