// insitu cubemap ENV -o DIR [--irradiance-size N]
//
// ENV is a scene file (its environment: six shots or an HDR image) or an HDR image. Writes
//   DIR/cube.exr               the radiance cube, a vertical strip of the faces +X…−Z (linear);
//                              from a scene with clipped shots, with the clipped light recovered
//                              against the photo (scene/light_recovery.h), and a line per source
//   DIR/cube.png               the cube unfolded as a cross, seen from inside (preview.h)
//   DIR/equirect.exr           the radiance as an equirectangular image (4n × 2n, linear)
//   DIR/irradiance_MODE.exr    each mode's irradiance E (not E/π), sampled at the texel centres of
//                              an N² cube (default 32), as a strip
//   DIR/irradiance_MODE.png    its cross, E/π at the radiance preview's exposure, so that all
//                              previews compare directly
#include <cstdio>
#include <fmt/format.h>
#include <filesystem>
#include <memory>
#include <optional>

#include "commands.h"
#include "light/environment.h"
#include "scene/scene_file.h"
#include "light/equirect.h"
#include "light/irradiance.h"
#include "core/output_paths.h"
#include "light/preview.h"
#include "scene/light_recovery.h"
#include "scene/pipeline.h"

namespace insitu {
namespace {

struct CubemapArgs {
  std::string env, out;
  int irradiance_size = 32;
};

// Clipped shots and a scene: the cube with the clipped light recovered against the photo, as the
// render will use it (scene/light_recovery.h), and what to print of it.
std::string recover_light(const std::string& scene_path, CubeMap& cube) {
  const LoadedScene scene = load_scene(parse_scene_file(scene_path));
  cube = scene.environment;
  const auto& il = *scene.inverse_lighting;
  std::string out = "light: " + light_determined_by(scene) + " (" + il.status + "): " + il.message + "\n";
  for (const SourceFit& f : il.sources)
    out += fmt::format("  source toward ({:.2f}, {:.2f}, {:.2f}), {:.3g} sr: scale {:.4g} ± {:.2g}{}\n",
                       f.source.dir_world.x(), f.source.dir_world.y(), f.source.dir_world.z(), f.source.solid_angle_sr,
                       f.scale, f.sigma, f.determined ? "" : " (not determined: lower bound)");
  return out;
}

// A shot's aim as registration found it (light/shot_registration.h), or why it has none.
std::string aim_text(const std::optional<Registration>& r, int f) {
  if (!r) return "";
  const ShotAim& a = r->shots[std::size_t(f)];
  if (!a.registered) return ", nominal aim (" + a.reason + ")";
  return fmt::format(", turned {:.2f}° (yaw {:+.2f}°, pitch {:+.2f}°, roll {:+.2f}°), {} matches, residual {:.3f}°",
                     a.rotation_deg, a.yaw_deg, a.pitch_deg, a.roll_deg, a.matches, a.residual_deg);
}

int run_cubemap(const CubemapArgs& a) {
  Warnings warnings;
  EnvironmentInfo info;
  std::string photo_path;
  const EnvironmentSpec spec = environment_from_argument(a.env, &photo_path);
  {  // Before any work: the outputs replace none of the inputs.
    std::vector<NamedPath> inputs = {
        {a.env, "the environment argument"}, {spec.image, "the environment image"}, {photo_path, "the photo"}};
    for (int f = 0; f < 6; ++f)
      for (const auto& file : spec.shots[std::size_t(f)].files)
        inputs.push_back({file, std::string("shot ") + face_name(f)});
    std::vector<NamedPath> outputs;
    for (const char* name : {"cube.exr", "cube.png", "equirect.exr"})
      outputs.push_back({(std::filesystem::path(a.out) / name).string(), "an output"});
    // The directional modes only: the volume needs a room box, which this verb does not take.
    for (IrradianceMode mode : directional_irradiance_modes())
      for (const char* ext : {".exr", ".png"})
        outputs.push_back(
            {(std::filesystem::path(a.out) / (std::string("irradiance_") + irradiance_mode_name(mode) + ext)).string(),
             "an output"});
    check_outputs(inputs, outputs);
  }
  std::optional<ImageFile> photo;
  if (!photo_path.empty()) photo = read_image_file(photo_path);
  CubeMap cube = load_environment(spec, warnings, &info, photo ? &*photo : nullptr);
  print_warnings(warnings);
  const std::string light_line =
      (!photo_path.empty() && info.clipped_cube && spec.inverse_lighting) ? recover_light(a.env, cube) : std::string();
  namespace fs = std::filesystem;
  const fs::path dir(a.out);
  const double exposure = preview_exposure(cube);
  auto out = [&](const std::string& name) { return (dir / name).string(); };
  write_image(out("cube.exr"), cube_to_strip(cube));
  write_image(out("cube.png"), cube_cross_preview(cube, exposure));
  write_image(out("equirect.exr"), cube_to_equirect(cube));
  std::string written;  // "gaussian,sh9,exact"
  for (IrradianceMode mode : directional_irradiance_modes()) {
    written += (written.empty() ? "" : ",") + std::string(irradiance_mode_name(mode));
    const auto field = make_irradiance(mode, cube, a.irradiance_size);
    const CubeMap e = irradiance_cube(*field, a.irradiance_size),
                  e_over_pi = irradiance_cube(*field, a.irradiance_size, 1 / kPiF);
    const std::string name = std::string("irradiance_") + irradiance_mode_name(mode);
    write_image(out(name + ".exr"), cube_to_strip(e));
    write_image(out(name + ".png"), cube_cross_preview(e_over_pi, exposure));
  }
  std::printf("%s: face size %d, %zu clamped values, exposure %s (x%.4g)%s\n", a.env.c_str(), cube.size(),
              info.clamped_values, info.exposure_source.c_str(), info.exposure_factor,
              info.response ? ", camera response recovered from brackets" : "");
  if (spec.from_shots())
    for (int f = 0; f < 6; ++f)
      std::printf("  %-3s %-40s coverage %5.1f%%, clipped %5.2f%%%s\n", face_name(f),
                  spec.shots[std::size_t(f)].files.front().c_str(), 100 * info.coverage[std::size_t(f)],
                  100 * info.clipped[std::size_t(f)], aim_text(info.registration, f).c_str());
  std::printf("%s", light_line.c_str());
  std::printf("wrote cube.exr, cube.png, equirect.exr and irradiance_{%s}.{exr,png} to %s\n", written.c_str(),
              a.out.c_str());
  return 0;
}

}  // namespace

Command add_cubemap_command(CLI::App& app) {
  auto a = std::make_shared<CubemapArgs>();
  CLI::App* cmd =
      app.add_subcommand("cubemap", "assemble the environment into an HDR cube, previews and irradiance cubes");
  cmd->add_option("env", a->env, "a scene file (its environment) or an HDR image")->required();
  cmd->add_option("-o,--output", a->out, "output folder")->required();
  cmd->add_option("--irradiance-size", a->irradiance_size, "face size of the irradiance cubes")
      ->check(CLI::Range(1, 512))
      ->capture_default_str();
  return [cmd, a] { return cmd->parsed() ? run_cubemap(*a) : -1; };
}

}  // namespace insitu
