// insitu irradiance-report ENV... [--normals N] [--exact-size S] [--face-size F] [--csv FILE]
//
// For each environment (scene file or HDR image) and each irradiance mode: precomputation time,
// time per lookup, and the error against the brute-force reference (irradiance_report.h). Prints
// a Markdown table; --csv writes the same rows.
#include <cstdio>
#include <filesystem>
#include <fmt/format.h>
#include <memory>
#include <optional>

#include "commands.h"
#include "core/output_paths.h"
#include "light/environment.h"
#include "scene/scene_file.h"
#include "light/irradiance_report.h"
#include "core/text_file.h"

namespace insitu {
namespace {

struct ReportArgs {
  std::vector<std::string> envs;
  int normals = 256, exact_size = 32, face_size = 0;
  std::string csv;
};

int run_report(const ReportArgs& a) {
  std::vector<NamedPath> inputs;
  for (const auto& e : a.envs) inputs.push_back({e, "an environment argument"});
  check_outputs(inputs, {{a.csv, "--csv"}});
  std::string csv =
      "environment,face_size,mode,precompute_ms,lookup_ns,mean_rel_error,max_rel_error,brightest_rel_error\n";
  std::printf(
      "| environment | face | mode | precompute (ms) | lookup (ns) | mean rel. error | max rel. error | error facing "
      "the brightest texel |\n");
  std::printf("|---|---|---|---|---|---|---|---|\n");
  for (const std::string& env : a.envs) {
    std::string photo_path;
    EnvironmentSpec spec = environment_from_argument(env, &photo_path);
    if (a.face_size > 0) spec.face_size = a.face_size;
    Warnings w;
    std::optional<ImageFile> photo;
    if (!photo_path.empty()) photo = read_image_file(photo_path);
    const CubeMap cube = load_environment(spec, w, nullptr, photo ? &*photo : nullptr);
    print_warnings(w);
    const IrradianceReport rep = irradiance_report(cube, a.normals, a.exact_size);
    // A scene is named by its folder (scenes/demo/scene.json -> demo), an image by its stem.
    const std::filesystem::path ep(env);
    const std::string name = ep.extension() == ".json" ? ep.parent_path().filename().string() : ep.stem().string();
    for (const ModeReport& m : rep.modes) {
      std::printf("| %s | %d | %s | %.2f | %.1f | %.4f | %.4f | %.4f |\n", name.c_str(), rep.face_size,
                  irradiance_mode_name(m.mode), m.precompute_ms, m.lookup_ns, m.mean_rel_error, m.max_rel_error,
                  m.brightest_rel_error);
      csv += fmt::format("{},{},{},{:.4f},{:.2f},{:.6f},{:.6f},{:.6f}\n", name, rep.face_size,
                         irradiance_mode_name(m.mode), m.precompute_ms, m.lookup_ns, m.mean_rel_error, m.max_rel_error,
                         m.brightest_rel_error);
    }
    std::fflush(stdout);
  }
  if (!a.csv.empty()) write_text_file(a.csv, csv);
  return 0;
}

}  // namespace

Command add_irradiance_report_command(CLI::App& app) {
  auto a = std::make_shared<ReportArgs>();
  CLI::App* cmd =
      app.add_subcommand("irradiance-report", "time and error of each irradiance mode against the exact integral");
  cmd->add_option("env", a->envs, "scene files or HDR images")->required();
  cmd->add_option("--normals", a->normals, "number of test normals (Fibonacci sphere)")
      ->check(CLI::Range(1, 100000))
      ->capture_default_str();
  cmd->add_option("--exact-size", a->exact_size, "face size of the exact irradiance cube")
      ->check(CLI::Range(1, 512))
      ->capture_default_str();
  cmd->add_option("--face-size", a->face_size, "resample images to this cube face size [default: the image's own]")
      ->check(CLI::Range(1, 4096));
  cmd->add_option("--csv", a->csv, "also write the rows as CSV");
  return [cmd, a] { return cmd->parsed() ? run_report(*a) : -1; };
}

}  // namespace insitu
