#include "studio/shots_view.h"

#include <algorithm>
#include <filesystem>
#include <fmt/format.h>

#include "core/math.h"
#include "core/image.h"
#include "light/cubemap.h"
#include "light/environment.h"
#include "light/hdr_merge.h"
#include "scene/scene_file.h"
#include "scene/shots_report.h"
#include "studio/preview_png.h"
#include "studio/stitched_view.h"

namespace insitu {
namespace fs = std::filesystem;

namespace {

json error_json(const InputError& e) { return {{"where", e.where()}, {"what", e.message()}}; }

// The shot an error is about: its key's JSON path, or one of its files, in the error's place.
int shot_of(const EnvironmentSpec& env, const std::string& where) {
  for (int f = 0; f < 6; ++f) {
    const ShotSpec& s = env.shots[std::size_t(f)];
    if (!s.where.empty() && where.find(s.where) != std::string::npos) return f;
    for (const std::string& file : s.files)
      if (where.find(file) != std::string::npos) return f;
  }
  return -1;
}

json shot_json(const ShotSpec& s, int face, const fs::path& folder) {
  json files = json::array();
  for (const std::string& f : s.files) files.push_back(fs::relative(f, folder).string());
  json out = {
      {"face", face_name(face)}, {"key", s.key}, {"files", files}, {"rotate_deg", s.rotate_deg}, {"error", nullptr}};
  try {
    const auto [w, h] = read_image_size(s.files.front());
    const bool quarter = s.rotate_deg % 180 != 0;
    out["width"] = quarter ? h : w, out["height"] = quarter ? w : h;
  } catch (const InputError& e) {
    out["error"] = error_json(e.with_context(s.where));
  }
  return out;
}

// Coverage, clipping and field of view from the library's assembly of the cube.
void add_assembly(const SceneSpec& spec, const fs::path& folder, json& out) {
  const EnvironmentSpec& env = spec.environment;
  try {
    Warnings warnings;
    EnvironmentInfo info;
    std::string photo_note;
    load_shots_as_rendered(spec, warnings, info, photo_note);

    for (int f = 0; f < 6; ++f) {
      json& shot = out["shots"][std::size_t(f)];
      shot["coverage_percent"] = 100 * info.coverage[std::size_t(f)];
      shot["clipped_percent"] = 100 * info.clipped[std::size_t(f)];
      shot["hfov_deg"] = info.hfov_deg[std::size_t(f)];
      shot["registration"] = registration_json(info.registration, f);
      shot["room_lines"] = room_lines_json(info.line_anchor, f);
      shot["photo_anchor"] = photo_anchor_json(info.photo_anchor, f);
      shot["outline"] = outline_colour(f);
    }
    out["gap_percent"] = 100 * gap_fraction(shot_frames(env, info));
    // The library's warnings name files by their full path; the page names them from the folder.
    const std::string prefix = folder.string() + "/";
    const auto from_folder = [&](std::string w) {
      for (std::size_t at; (at = w.find(prefix)) != std::string::npos;) w.erase(at, prefix.size());
      return w;
    };
    for (const std::string& w : warnings.items) out["warnings"].push_back(from_folder(w));
    if (!photo_note.empty()) out["photo_anchor_note"] = from_folder(photo_note);
  } catch (const InputError& e) {
    const int f = shot_of(env, e.where());
    (f >= 0 ? out["shots"][std::size_t(f)]["error"] : out["error"]) = error_json(e);
  }
}

}  // namespace

json shots_view(const std::string& scene_path) {
  json out = {{"shots", json::array()}, {"error", nullptr}, {"warnings", json::array()}};
  SceneSpec spec;
  try {
    spec = parse_scene_file(scene_path);
  } catch (const InputError& e) {
    out["error"] = error_json(e);
    return out;
  }
  const EnvironmentSpec& env = spec.environment;
  const fs::path folder = fs::absolute(scene_path).parent_path();
  if (!env.from_shots()) {
    out["image"] = fs::relative(env.image, folder).string();
    try {
      // An 8- or 16-bit panorama is read as one single shot; a float image is radiance.
      const ImageHeader h = read_image_header(env.image);
      out["image_kind"] = h.display_referred ? fmt::format("{}-bit panorama", h.bits) : std::string("HDR image");
    } catch (const InputError& e) {
      out["error"] = error_json(e.with_context(env.where));
    }
    return out;
  }
  out["faced"] = face_name(env.faced_face);
  bool readable = true;
  for (int f = 0; f < 6; ++f) {
    out["shots"].push_back(shot_json(env.shots[std::size_t(f)], f, folder));
    readable = readable && out["shots"].back()["error"].is_null();
  }
  if (readable) add_assembly(spec, folder, out);
  return out;
}

std::string shot_preview_png(const std::string& scene_path, int face, int max_side_px) {
  const SceneSpec spec = parse_scene_file(scene_path);
  const EnvironmentSpec& env = spec.environment;
  if (!env.from_shots()) throw InputError(env.where, "this scene has no six shots");  // where names the file
  const ShotSpec& s = env.shots[std::size_t(face)];
  std::vector<ImageFile> files;
  for (const std::string& path : s.files) {
    try {
      files.push_back(read_image_file(path));
    } catch (const InputError& e) {
      throw e.with_context(s.where);
    }
    files.back().stored = rotated_clockwise(files.back().stored, s.rotate_deg);
  }
  // A bracket's middle exposure is shown, with what clipped in its shortest (the one that clipped
  // least), whose clipping the library reports.
  std::vector<double> clipped_fractions;
  for (const ImageFile& f : files) clipped_fractions.push_back(clipped_fraction(f));
  const ImageFile& file = files[files.size() / 2];
  const ImageFile& shortest = files[std::size_t(std::min_element(clipped_fractions.begin(), clipped_fractions.end()) -
                                                clipped_fractions.begin())];
  Image linear = linearize(file);
  if (!file.display_referred) {
    double sum = 0;
    for (int y = 0; y < linear.height; ++y)
      for (int x = 0; x < linear.width; ++x) sum += luminance(linear.rgb(x, y));
    const double mean = sum / std::max<double>(1, double(linear.width) * linear.height);
    if (mean > 0)
      for (float& v : linear.data) v *= float(0.18 / mean);
  }
  const Image clipped = clipped_mask(shortest);
  return srgb_png(linear, &clipped, max_side_px);
}

}  // namespace insitu
