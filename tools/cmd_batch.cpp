// insitu batch BATCH.json [--index I [--per-task K]] [--force] [--count]
//
// A catalogue batch (issue 17): one room, many stills. BATCH.json is
//   {"scene": "room/scene.json", "entries": [PATCH, PATCH, ...]}
// where each entry is a JSON merge patch (RFC 7386) of the room's scene file: the keys it gives
// replace the room's (arrays whole: "objects"), null removes one. It is read as if it were that
// scene file, so its relative paths are relative to the scene file's folder. Every entry must name
// its own output.image.
//
// --index I renders entry I only (a Slurm array task: --index $SLURM_ARRAY_TASK_ID); with
// --per-task K, task I renders entries I·K … I·K + K − 1 and --count prints the number of tasks.
// Without --index, every entry in turn. The room (photo, camera, environment, recovered light, and
// the room light and irradiance grids the path integrator prepares: light/room_cache.h) is loaded
// once and shared by the entries of the process that leave it as it is, so a task of K entries
// pays the room's start-up once. An entry's outputs are written atomically, the
// report last (scene/pipeline.h, write_outputs); a killed task leaves none of its files under a
// final name. A rerun skips an entry whose report exists and records the same inputs hash: the
// entry's scene as merged, the insitu version, the bytes of the files it names, and the bytes of
// every file its meshes were read from (MTL files and textures that an OBJ names). The report
// lists those mesh files: a rerun hashes the ones the last render read, so an edited MTL file or
// texture is rendered again (and an OBJ that names other files has changed bytes itself).
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fmt/format.h>
#include <fstream>
#include <limits>
#include <memory>

#include "commands.h"
#include "core/fnv1a.h"
#include "core/json_reader.h"
#include "core/output_paths.h"
#include "progress.h"
#include "render/checkpoint.h"
#include "scene/output_layers.h"
#include "scene/pipeline.h"

namespace insitu {
namespace {

struct BatchArgs {
  std::string batch;
  int index = -1;
  int per_task = 1;  // entries per --index
  bool force = false, count = false;
};

struct Entry {
  json scene;  // the room's scene file with the entry's patch
  SceneSpec spec;
};

// The whole batch before its first render, as `render` checks one scene: no entry's output (image,
// layers, report) is the batch file, the room's scene file, or any entry's input (photo, shots,
// points, meshes), and no two outputs of the batch are one file, however spelled (same_file:
// symlinks, "..", hard links). An entry checked alone could not see the others (issue 46: a
// report on the batch file or another entry's photo, with exit 0). The files an OBJ names (MTL,
// textures) are known once it loads: load_scene checks them against that entry's outputs.
void check_batch_outputs(const std::string& batch, const std::string& room, const std::vector<Entry>& entries) {
  std::vector<NamedPath> inputs = {{batch, "the batch file"}, {room, "the room's scene file"}}, outputs;
  for (std::size_t i = 0; i < entries.size(); ++i) {
    for (NamedPath& in : scene_input_files_with_meshes(entries[i].spec))
      if (in.path != entries[i].spec.path) inputs.push_back({in.path, fmt::format("{} of entry {}", in.role, i)});
    for (NamedPath& out : scene_output_files(entries[i].spec))
      if (out.path != checkpoint_path(entries[i].spec.output.image))  // a batch writes no checkpoint
        outputs.push_back({out.path, fmt::format("{} of entry {}", out.role, i)});
  }
  check_outputs(inputs, outputs);
}

// The room's scene file, then each entry merged into it and parsed (every error names the entry).
std::vector<Entry> read_batch(const std::string& path) {
  const json doc = read_json_file(path);
  if (!doc.is_object()) throw InputError(path, "a batch is a JSON object {\"scene\": ..., \"entries\": [...]}");
  for (const auto& [key, value] : doc.items())
    if (key != "scene" && key != "entries")
      throw InputError(path + ":$." + key, "unknown key (a batch has scene and entries)");
  if (!doc.contains("scene") || !doc["scene"].is_string())
    throw InputError(path + ":$.scene", "the room's scene file is required (a string)");
  if (!doc.contains("entries") || !doc["entries"].is_array() || doc["entries"].empty())
    throw InputError(path + ":$.entries", "a non-empty array of entries is required");
  const std::filesystem::path scene_path = std::filesystem::path(path).parent_path() / doc["scene"].get<std::string>();
  const json room = read_json_file(scene_path.string());
  parse_scene_file(scene_path.string());  // the room's own errors, named in its own file
  std::vector<Entry> entries;
  for (std::size_t i = 0; i < doc["entries"].size(); ++i) {
    const json& patch = doc["entries"][i];
    const std::string where = fmt::format("{}:$.entries[{}]", path, i);
    if (!patch.is_object())
      throw InputError(where, "an entry is a JSON object (a merge patch of the room's scene file)");
    if (!patch.contains("output") || !patch["output"].is_object() || !patch["output"].contains("image"))
      throw InputError(where, "every entry names its own output.image");
    json merged = room;
    merged.merge_patch(patch);
    entries.push_back({merged, parse_scene_json(merged, where, scene_path.parent_path().string())});
  }
  check_batch_outputs(path, scene_path.string(), entries);
  return entries;
}

// A file's path and bytes into h (a missing file hashes unlike an empty one).
void hash_file(Fnv1a& h, const std::string& path) {
  h.text(path);
  std::ifstream f(path, std::ios::binary);
  h.text(f ? "present" : "absent");
  std::vector<char> buffer(1 << 16);
  while (f.read(buffer.data(), std::streamsize(buffer.size())) || f.gcount() > 0)
    h.bytes(buffer.data(), std::size_t(f.gcount()));
}

// The entry's inputs hash (see the top of the file), in hex; `mesh_files`: what its meshes read.
std::string inputs_hash(const Entry& e, const std::vector<std::string>& mesh_files) {
  Fnv1a h;
  h.text("insitu batch entry 2"), h.text(INSITU_VERSION), h.text(json_text(e.scene));
  for (const NamedPath& in : scene_input_files(e.spec)) hash_file(h, in.path);
  h.text("mesh files");
  for (const std::string& path : mesh_files) hash_file(h, path);
  return fmt::format("{:016x}", h.digest());
}

// Whether the entry's outputs are there, of these inputs (the mesh files its report lists).
bool done_already(const Entry& e) {
  const std::string report = report_path(e.spec.output.image);
  if (!std::filesystem::exists(report) || !std::filesystem::exists(e.spec.output.image)) return false;
  if (!e.spec.output.layers.empty() && !std::filesystem::exists(e.spec.output.layers)) return false;
  try {
    const json batch = read_json_file(report).at("batch");
    return batch.at("inputs_hash") == inputs_hash(e, batch.at("mesh_files").get<std::vector<std::string>>());
  } catch (const std::exception&) {
    return false;  // not a batch's report, or unreadable: render again
  }
}

// The keys of a scene file that make the room (a batch's entries that leave them as the room has
// them share its loaded room).
json room_keys(const json& scene) {
  json keys = json::object();
  for (const char* k : {"photo", "camera", "environment", "local_scene", "references"})
    if (scene.contains(k)) keys[k] = scene[k];
  return keys;
}

struct SharedRoom {
  json keys;
  std::unique_ptr<LoadedScene> scene;
};

void render_entry(const BatchArgs& a, const Entry& e, int index, SharedRoom& room) {
  const bool share = room.scene && room_keys(e.scene) == room.keys;
  auto scene = std::make_unique<LoadedScene>(load_scene(e.spec, {}, share ? room.scene.get() : nullptr));
  // Hashed as loaded, before the render: a file edited meanwhile makes the next run render again.
  std::vector<std::string> mesh_files;
  for (const NamedPath& f : loaded_mesh_files(*scene)) mesh_files.push_back(f.path);
  const json batch = {
      {"file", a.batch}, {"index", index}, {"inputs_hash", inputs_hash(e, mesh_files)}, {"mesh_files", mesh_files}};
  print_warnings(scene->warnings);
  Progress progress(fmt::format("entry {}", index));
  std::string detail;
  const RenderResult result = render_scene(*scene, [&](const RenderProgress& p) {
    if (p.noise >= 0) detail = fmt::format("{}/{} spp, noise {:.1f}%", p.spp_done, e.spec.render.spp, 100 * p.noise);
    progress.update(p.fraction, detail, p.noise >= 0);
  });
  write_outputs(*scene, result, nullptr, {{"batch", batch}});
  std::printf("%s\n", e.spec.output.image.c_str());
  std::fprintf(stderr, "insitu: entry %d: %s: load %.2f s%s, prepare %.2f s, render %.2f s\n", index,
               e.spec.output.image.c_str(), scene->load_seconds, share ? " (room shared)" : "", result.prepare_seconds,
               result.layers.seconds);
  if (!share) room = {room_keys(e.scene), std::move(scene)};
}

int run_batch(const BatchArgs& a) {
  const std::vector<Entry> entries = read_batch(a.batch);
  const int n = int(entries.size());
  const int tasks = int((std::int64_t(n) + a.per_task - 1) / a.per_task);
  if (a.count) {
    std::printf("%d\n", tasks);
    return 0;
  }
  if (a.index >= tasks)
    throw InputError("--index " + std::to_string(a.index),
                     a.per_task == 1 ? fmt::format("{} has entries 0 to {}", a.batch, n - 1)
                                     : fmt::format("{} has {} entries: tasks 0 to {} of {} entries", a.batch, n,
                                                   tasks - 1, a.per_task));
  const int first = a.index < 0 ? 0 : int(std::int64_t(a.index) * a.per_task);
  const int last = a.index < 0 ? n : int(std::min<std::int64_t>(n, std::int64_t(first) + a.per_task));
  SharedRoom room;
  int rendered = 0, skipped = 0;
  for (int i = first; i < last; ++i) {
    if (!a.force && done_already(entries[std::size_t(i)])) {
      std::fprintf(stderr, "insitu: entry %d: %s is done, of the same inputs (--force renders it again)\n", i,
                   entries[std::size_t(i)].spec.output.image.c_str());
      ++skipped;
      continue;
    }
    render_entry(a, entries[std::size_t(i)], i, room);
    ++rendered;
  }
  std::fprintf(stderr, "insitu: %s: %d rendered, %d done already\n", a.batch.c_str(), rendered, skipped);
  return 0;
}

}  // namespace

Command add_batch_command(CLI::App& app) {
  auto a = std::make_shared<BatchArgs>();
  CLI::App* cmd = app.add_subcommand("batch", "render the entries of a batch file: one room, many objects and outputs");
  cmd->add_option("batch", a->batch, "the batch file (JSON: the room's scene file and its entries)")->required();
  cmd->add_option("--index", a->index, "render entry I only (a Slurm array task's $SLURM_ARRAY_TASK_ID)")
      ->check(CLI::Range(0, std::numeric_limits<int>::max()));
  cmd->add_option("--per-task", a->per_task, "entries per --index: task I renders entries I*K to I*K+K-1 (default 1)")
      ->check(CLI::Range(1, std::numeric_limits<int>::max()));
  cmd->add_flag("--force", a->force, "render entries whose outputs are there, of the same inputs, again");
  cmd->add_flag(
      "--count", a->count,
      "print the number of tasks (entries, or groups of --per-task) and render nothing (for sbatch --array=0-(N-1))");
  return [cmd, a] { return cmd->parsed() ? run_batch(*a) : -1; };
}

}  // namespace insitu
