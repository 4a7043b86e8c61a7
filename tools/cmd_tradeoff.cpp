// insitu tradeoff SCENE -o DIR [--ladder 1,4,16,64] [--reference-spp 1024] [--seed N]
//                 [--noise-targets 0.04,0.02,0.01]
//
// The speed/accuracy trade of a scene: renders it with every integrator of the registry — one
// that is not Monte Carlo at 1 spp (a legacy frame) and 16 (anti-aliased), in each irradiance mode
// when it reads one; a Monte Carlo one over a ladder of sample counts — and measures each
// composite against the reference integrator's render of many samples (a different seed), over
// the pixels the reference changed visibly (changed_mask: the objects, and 3 % or more of the
// photo's luminance) — the objects and their shadows — and over the rest of the photo, which
// the reference leaves nearly as it is (there the error is speckle). The roles are the registry's capabilities
// (`reference`: path; `legacy`: realtime). Writes DIR/tradeoff.csv (mode, spp, seconds, relative
// RMSE), DIR/tradeoff.png (error against time, log–log), and DIR/ab.png (the legacy integrator's
// and the reference integrator's composites side by side with their difference). Times are
// precomputation plus rendering, on this machine's cores. --noise-targets adds the reference
// integrator with adaptive sampling (render/adaptive.h) to each target, capped at the ladder's
// largest spp; its rows give the mean spp the pixels took. Where the scene has objects and real
// surfaces, the reference integrator is also run with its real surfaces' reflection sampled by
// the cosine alone (path.cpp, toward_objects 0) and with one catcher bounce; and over the ladder
// with its composite denoised (output/denoise.h).
#include <opencv2/imgproc.hpp>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fmt/format.h>
#include <memory>

#include "commands.h"
#include "output/composite.h"
#include "output/image_compare.h"
#include "scene/pipeline.h"
#include "core/text_file.h"

namespace insitu {
namespace {

struct TradeoffArgs {
  std::string scene, out;
  std::vector<int> ladder = {1, 4, 16, 64};
  int reference_spp = 1024;
  long seed = 7;
  std::vector<double> noise_targets;
};

struct Row {
  std::string mode;
  int spp;  // adaptive: the mean the pixels took
  double seconds, rel_rmse;
  double rest_rmse = 0;  // relative RMSE over the pixels outside the region
  double noise_target = 0;
  bool monte_carlo = false;  // its points are labelled with their spp
  std::string label() const { return noise_target > 0 ? fmt::format("{} {:g}", mode, noise_target) : mode; }
};

// A log–log scatter of error against time, drawn with OpenCV.
Image plot(const std::vector<Row>& rows) {
  const int W = 760, H = 460, left = 70, right = 210, top = 30, bottom = 50;
  cv::Mat m(H, W, CV_8UC3, cv::Scalar(255, 255, 255));
  double tmin = 1e30, tmax = 0, emin = 1e30, emax = 0;
  for (const Row& r : rows) {
    tmin = std::min(tmin, r.seconds);
    tmax = std::max(tmax, r.seconds);
    emin = std::min(emin, std::max(r.rel_rmse, 1e-4));
    emax = std::max(emax, r.rel_rmse);
  }
  const double lt0 = std::floor(std::log10(tmin)), lt1 = std::ceil(std::log10(tmax));
  const double le0 = std::floor(std::log10(emin)), le1 = std::ceil(std::log10(emax));
  auto px = [&](double t) {
    return left + int((std::log10(t) - lt0) / std::max(1e-9, lt1 - lt0) * (W - left - right));
  };
  auto py = [&](double e) {
    return H - bottom - int((std::log10(std::max(e, 1e-4)) - le0) / std::max(1e-9, le1 - le0) * (H - top - bottom));
  };
  const cv::Scalar black(0, 0, 0), grey(200, 200, 200);
  for (double d = lt0; d <= lt1; ++d) {
    cv::line(m, {px(std::pow(10, d)), top}, {px(std::pow(10, d)), H - bottom}, grey);
    cv::putText(m, fmt::format("{:g}", std::pow(10, d)), {px(std::pow(10, d)) - 12, H - bottom + 18},
                cv::FONT_HERSHEY_SIMPLEX, 0.4, black);
  }
  for (double d = le0; d <= le1; ++d) {
    cv::line(m, {left, py(std::pow(10, d))}, {W - right, py(std::pow(10, d))}, grey);
    cv::putText(m, fmt::format("{:g}", std::pow(10, d)), {8, py(std::pow(10, d)) + 4}, cv::FONT_HERSHEY_SIMPLEX, 0.4,
                black);
  }
  cv::putText(m, "seconds", {W / 2 - 60, H - 12}, cv::FONT_HERSHEY_SIMPLEX, 0.5, black);
  cv::putText(m, "relative RMSE against the reference (objects and shadows)", {left, 18}, cv::FONT_HERSHEY_SIMPLEX,
              0.45, black);
  // One colour per mode (BGR): the demo's table has ten.
  const cv::Scalar colours[] = {{40, 40, 200}, {200, 120, 40}, {40, 160, 40},   {160, 60, 160}, {0, 140, 220},
                                {20, 20, 20},  {150, 150, 0},  {120, 120, 120}, {0, 200, 255},  {255, 80, 200}};
  constexpr std::size_t kColours = sizeof(colours) / sizeof(colours[0]);
  std::vector<std::string> modes;
  for (const Row& r : rows)
    if (std::find(modes.begin(), modes.end(), r.mode) == modes.end()) modes.push_back(r.mode);
  for (std::size_t k = 0; k < modes.size(); ++k) {
    const cv::Scalar c = colours[k % kColours];
    cv::Point prev(-1, -1);
    for (const Row& r : rows) {
      if (r.mode != modes[k]) continue;
      const cv::Point p(px(r.seconds), py(r.rel_rmse));
      cv::circle(m, p, 5, c, cv::FILLED);
      if (prev.x >= 0) cv::line(m, prev, p, c, 2);
      if (r.monte_carlo)
        cv::putText(m, fmt::format("{}", r.spp), {p.x + 6, p.y - 6}, cv::FONT_HERSHEY_SIMPLEX, 0.35, c);
      prev = p;
    }
    cv::circle(m, {W - right + 20, top + 20 + 20 * int(k)}, 5, c, cv::FILLED);
    cv::putText(m, modes[k], {W - right + 32, top + 24 + 20 * int(k)}, cv::FONT_HERSHEY_SIMPLEX, 0.45, black);
  }
  Image out(W, H, 3);
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x)
      for (int c = 0; c < 3; ++c) out.at(x, y)[c] = m.at<cv::Vec3b>(y, x)[2 - c] / 255.0f;
  return out;
}

// DIR/tradeoff.csv, DIR/tradeoff.png, DIR/ab.png, and the table on stdout.
void write_outputs(const TradeoffArgs& a, const std::vector<Row>& rows, const RenderResult& legacy_result,
                   const RenderResult& best_reference) {
  const std::filesystem::path dir(a.out);
  std::string csv = "mode,spp,seconds,relative_rmse,rest_relative_rmse\n";
  for (const Row& r : rows)
    csv += fmt::format("{},{},{:.4f},{:.6f},{:.6f}\n", r.label(), r.spp, r.seconds, r.rel_rmse, r.rest_rmse);
  write_text_file((dir / "tradeoff.csv").string(), csv);
  write_image((dir / "tradeoff.png").string(), plot(rows));
  const CompareResult ab = compare_images(legacy_result.composite_linear, best_reference.composite_linear);
  write_image((dir / "ab.png").string(),
              comparison_picture(legacy_result.composite_linear, best_reference.composite_linear, ab,
                                 &legacy_result.composite_encoded, &best_reference.composite_encoded));
  std::printf("| mode | spp | seconds | relative RMSE | rest of the photo |\n|---|---|---|---|---|\n");
  for (const Row& r : rows)
    std::printf("| %s | %d | %.3f | %.4f | %.4f |\n", r.label().c_str(), r.spp, r.seconds, r.rel_rmse, r.rest_rmse);
}

// One tradeoff: the scene loaded once (the runs differ only in their render settings), the
// reference render and the regions it sets, and the rows measured against it.
class Tradeoff {
 public:
  Tradeoff(const TradeoffArgs& a, LoadedScene scene)
      : a_(a),
        scene_(std::move(scene)),
        reference_name_(reference_integrator().name),
        legacy_name_(legacy_integrator().name) {}

  // The reference integrator at --reference-spp with another seed, and the regions it sets: the
  // pixels it changes visibly, and the rest of the photo.
  void render_reference() {
    std::fprintf(stderr, "tradeoff: reference, %s at %d spp...\n", reference_name_.c_str(), a_.reference_spp);
    run(reference_name_, IrradianceMode::kExact, a_.reference_spp, std::uint64_t(a_.seed) + 1000, &reference_);
    mask_ = changed_mask(scene_.photo_linear, reference_.composite_linear, reference_.layers);
    rest_ = mask_;
    for (float& v : rest_.data) v = v != 0.0f ? 0.0f : 1.0f;
  }

  // Every integrator of the registry: a Monte Carlo one over the ladder, the others at 1 spp (a
  // legacy frame) and 16 (anti-aliased), in each irradiance mode when it reads one. The A/B
  // picture sets the legacy path against the best path-traced render.
  void measure_registry() {
    for (const IntegratorEntry& e : integrator_registry()) {
      const std::string name = e.name;
      Warnings ignored;
      const bool reads_mode =
          resolve_integrator(name, {json::object(), "", "$.render"}, ignored).params.contains("irradiance");
      for (const auto& [mode, mode_name] : kIrradianceModes) {
        if (!reads_mode && mode != IrradianceMode::kExact) continue;
        if (mode == IrradianceMode::kVolume && !scene_.spec.environment.room_box) continue;  // it needs one
        const std::string label = reads_mode ? name + "/" + mode_name : name;
        if (!e.uses.monte_carlo) {
          for (int spp : {1, 16})
            measure(label, name, mode, spp, name == legacy_name_ && spp == 16 ? &legacy_result_ : nullptr);
          continue;
        }
        for (int spp : a_.ladder) measure(label, name, mode, spp, name == reference_name_ ? &best_reference_ : nullptr);
      }
    }
  }

  // The reference integrator's own variants over the ladder.
  void measure_reference_variants() {
    Warnings ignored;
    const json params = resolve_integrator(reference_name_, scene_.spec.render.block, ignored).params;
    // Debevec's one-bounce catcher (path.cpp, catcher_bounces), where the scene has real surfaces
    // for the objects' change to travel between: faster, and biased where the walls are bright.
    if ((scene_.room || scene_.spec.local_scene.size() > 1) && params.value("catcher_bounces", 1) > 1)
      for (int spp : a_.ladder) measure_reference("/1 catcher bounce", spp, {{"catcher_bounces", 1}});
    // The real surfaces' reflection by the cosine alone: where the objects' change far from them is
    // a few lucky hits (path.cpp, "Toward the objects").
    if ((scene_.room || !scene_.spec.local_scene.empty()) && params.value("toward_objects", 0.0) > 0)
      for (int spp : a_.ladder) measure_reference("/cosine only", spp, {{"toward_objects", 0}});
    // The composite denoised (output/denoise.h): the time includes the denoiser's.
    for (int spp : a_.ladder) measure_reference(" denoised", spp, json::object(), 0, true);
    const int cap = *std::max_element(a_.ladder.begin(), a_.ladder.end());
    for (double target : a_.noise_targets) measure_reference(" adaptive", cap, json::object(), target);
  }

  void write() const {
    write_outputs(a_, rows_, legacy_result_, best_reference_);
    std::printf("wrote tradeoff.csv, tradeoff.png and ab.png to %s (reference: %s, %d spp, %ld pixels changed)\n",
                a_.out.c_str(), reference_name_.c_str(), a_.reference_spp,
                long(std::count(mask_.data.begin(), mask_.data.end(), 1.0f)));
  }

 private:
  // One render with these settings; its seconds: precomputation, render and denoiser.
  double run(const std::string& integrator, IrradianceMode mode, int spp, std::uint64_t seed, RenderResult* result,
             double noise_target = 0, const json& params = json::object(), bool denoise = false) {
    scene_.spec.render.integrator = integrator;
    scene_.spec.denoise = denoise;
    JsonBlock render = scene_.spec.render.block;
    render.value["irradiance"] = irradiance_mode_name(mode);
    for (const auto& [key, value] : params.items()) render.value[key] = value;
    Warnings printed_once;  // the scene's warnings were printed after loading
    scene_.integrator = resolve_integrator(integrator, render, printed_once);
    scene_.spec.render.spp = spp;
    scene_.spec.render.seed = seed;
    scene_.spec.render.noise_target = noise_target;
    *result = render_scene(scene_);
    return result->prepare_seconds + result->layers.seconds + result->denoise_seconds;
  }

  // A row: one render against the reference, over the changed region and the rest of the photo.
  void measure(const std::string& name, const std::string& integrator, IrradianceMode mode, int spp, RenderResult* keep,
               double noise_target = 0, const json& params = json::object(), bool denoise = false) {
    RenderResult r;
    const double seconds = run(integrator, mode, spp, std::uint64_t(a_.seed), &r, noise_target, params, denoise);
    const CompareResult c = compare_images(r.composite_linear, reference_.composite_linear, &mask_);
    const CompareResult c_rest = compare_images(r.composite_linear, reference_.composite_linear, &rest_);
    if (noise_target > 0) spp = int(std::lround(mean_spp(r.layers)));
    rows_.push_back({name, spp, seconds, c.masked->relative_rmse, c_rest.masked->relative_rmse, noise_target,
                     find_integrator(integrator)->uses.monte_carlo});
    std::fprintf(stderr, "tradeoff: %-20s %5d spp %8.3f s  rel. RMSE %.4f, rest %.4f\n", rows_.back().label().c_str(),
                 spp, seconds, c.masked->relative_rmse, c_rest.masked->relative_rmse);
    if (keep) *keep = std::move(r);
  }

  // A row of the reference integrator, named after it with `suffix`, in the exact irradiance.
  void measure_reference(const std::string& suffix, int spp, const json& params, double noise_target = 0,
                         bool denoise = false) {
    measure(reference_name_ + suffix, reference_name_, IrradianceMode::kExact, spp, nullptr, noise_target, params,
            denoise);
  }

  const TradeoffArgs& a_;
  LoadedScene scene_;
  const std::string reference_name_, legacy_name_;
  RenderResult reference_, legacy_result_, best_reference_;
  Image mask_, rest_;  // the pixels the reference changes visibly, and the rest of the photo
  std::vector<Row> rows_;
};

int run_tradeoff(const TradeoffArgs& a) {
  SceneSpec spec = parse_scene_file(a.scene);
  spec.output = {};
  std::vector<NamedPath> outputs;
  for (const char* name : {"tradeoff.csv", "tradeoff.png", "ab.png"})
    outputs.push_back({(std::filesystem::path(a.out) / name).string(), "an output"});
  check_outputs(scene_input_files(spec), outputs);
  LoadedScene scene = load_scene(spec);
  print_warnings(scene.warnings);
  Tradeoff tradeoff(a, std::move(scene));
  tradeoff.render_reference();
  tradeoff.measure_registry();
  tradeoff.measure_reference_variants();
  tradeoff.write();
  return 0;
}

}  // namespace

Command add_tradeoff_command(CLI::App& app) {
  auto a = std::make_shared<TradeoffArgs>();
  CLI::App* cmd = app.add_subcommand("tradeoff", "time and error of every mode against a path-traced reference");
  cmd->add_option("scene", a->scene, "the scene file")->required();
  cmd->add_option("-o,--output", a->out, "output folder")->required();
  cmd->add_option("--ladder", a->ladder, "path sample counts, comma-separated")
      ->delimiter(',')
      ->check(CLI::Range(1, kMaxSpp))
      ->capture_default_str();
  cmd->add_option("--reference-spp", a->reference_spp, "samples of the reference")
      ->check(CLI::Range(1, kMaxSpp))
      ->capture_default_str();
  cmd->add_option("--noise-targets", a->noise_targets,
                  "also path with adaptive sampling to these relative standard errors, comma-separated, capped at the "
                  "ladder's largest spp")
      ->delimiter(',')
      ->check(CLI::Range(1e-6, 1.0));
  cmd->add_option("--seed", a->seed, "seed of the measured renders (the reference uses seed + 1000)")
      ->check(CLI::Range(0L, kMaxSeed - 1000))
      ->capture_default_str();
  return [cmd, a] { return cmd->parsed() ? run_tradeoff(*a) : -1; };
}

}  // namespace insitu
