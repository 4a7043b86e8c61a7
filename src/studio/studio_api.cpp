// The studio's /api/ routes (studio_server.h lists them).
#include <filesystem>
#include <fmt/format.h>

#include "calib/control_points.h"
#include "integrators/registry.h"
#include "output/settings.h"
#include "core/json_reader.h"
#include "scene/pipeline.h"
#include "scene/scene_file.h"
#include "studio/calibration_view.h"
#include "studio/corner_snap.h"
#include "studio/render_job.h"
#include "studio/scene_edit.h"
#include "studio/shots_view.h"
#include "studio/stitched_view.h"
#include "studio/studio_impl.h"

namespace insitu {
namespace fs = std::filesystem;

namespace {

// A save or an edit made from a version the file no longer has (PUT /api/points, POST /api/shots).
constexpr const char* kConflict = "changed since this page read it (another tab or program saved it); reload to see it";

// The request's body as JSON; its name in messages is the route's.
json body_json(const httplib::Request& req) { return parse_json_text(req.body, req.path); }

// The points panel's part of /api/state: the file, its points and version, or (for a camera
// the panel does not edit) nulls and the reason.
json points_state(const StudioServer::Impl& s) {
  if (!s.points)
    return {{"points_file", nullptr},
            {"points", nullptr},
            {"points_text", ""},
            {"version", ""},
            {"points_refusal", s.points_refusal}};
  const FileVersion p = s.points->read();
  json points;
  try {
    points = parse_json_text(p.text, s.points->path());
  } catch (const InputError&) {
    points = nullptr;  // the page shows the file's own error from /api/calibrate's read
  }
  return {{"points_file", fs::relative(s.points->path(), s.folder).string()},
          {"points", points},
          {"points_text", p.text},
          {"version", p.version},
          {"points_refusal", nullptr}};
}

json state_json(const StudioServer::Impl& s) {
  json state = points_state(s);
  state.update(json{{"scene", fs::path(s.scene.path).filename().string()},
                    {"photo", {{"url", "/api/photo.png"}, {"width", s.width}, {"height", s.height}}},
                    {"model", s.scene.camera.model.value_or("auto")},
                    // The scene's tone map: the page shows it first, as "Save outputs" writes it.
                    {"tonemap",
                     {{"op", tonemap_name(s.scene.output.tonemap.op)},
                      {"key", s.scene.output.tonemap.key.value_or(-1)},
                      {"bias", s.scene.output.tonemap.bias}}}});
  return state;
}

// PUT /api/points and /api/calibrate on a scene whose camera the points panel does not edit.
bool refuse_without_points(StudioServer::Impl& s, httplib::Response& res) {
  if (s.points) return false;
  reply_error(res, 409, s.scene.camera.where, s.points_refusal);  // where names the file already
  return true;
}

// Runs `handler`, turning bad input into a 400 with the CLI's message.
template <class F>
void guarded(httplib::Response& res, F&& handler) {
  try {
    handler();
  } catch (const InputError& e) {
    reply_error(res, 400, e.where(), e.message());
  }
}

void put_points(StudioServer::Impl& s, const httplib::Request& req, httplib::Response& res) {
  if (refuse_without_points(s, res)) return;
  const json body = body_json(req);
  if (!body.is_object() || !body.contains("points") || !body.contains("version") || !body["version"].is_string())
    throw InputError(req.path, "expected {\"version\": \"...\", \"points\": [...]}");
  const VersionedFile::UpdateResult r = s.points->save(body["points"], body["version"].get<std::string>());
  if (!r.saved) {
    reply_error(res, 409, s.points->path(), kConflict);
    return;
  }
  reply_json(res, json{{"version", r.now.version}});
}

void post_calibrate(StudioServer::Impl& s, const httplib::Request& req, httplib::Response& res) {
  if (refuse_without_points(s, res)) return;
  const json body = body_json(req);
  if (!body.is_object() || !body.contains("points"))
    throw InputError(req.path, "expected {\"points\": [...], \"model\": \"auto\"}");
  std::optional<CameraModel> model;
  if (body.contains("model") && body["model"] != "auto") {
    model = body["model"].is_string() ? parse_model(body["model"].get<std::string>()) : std::nullopt;
    if (!model) throw InputError(req.path + ":$.model", "expected \"auto\", \"f\", \"f+c\" or \"f+c+a\"");
  }
  const auto points = control_points_from_json(body["points"], s.points->path());
  try {
    reply_json(res, calibration_view(points, s.width, s.height, model, s.scene));
  } catch (const InputError& e) {
    if (!e.where().empty()) throw;  // a point's own place names the file already
    throw e.with_context(fs::path(s.points->path()).filename().string());
  }
}

void post_snap(StudioServer::Impl& s, const httplib::Request& req, httplib::Response& res) {
  const json body = body_json(req);
  static const json kMissing;
  const JsonValue uv(body.is_object() && body.contains("uv") ? body["uv"] : kMissing, req.path, "$.uv");
  if (!uv.is_array() || uv.size() != 2) uv.fail("expected [u, v]");
  const CornerSnap snap = snap_to_corner(s.gray, {uv.element(0).number(), uv.element(1).number()});
  reply_json(res, json{{"snapped", snap.snapped},
                       {"uv", {snap.uv_px.x(), snap.uv_px.y()}},
                       {"offset", {snap.offset_px.x(), snap.offset_px.y()}}});
}

// {"version", "op": "swap", "a", "b"} | {"version", "op": "turn", "key", "by_deg"} |
// {"version", "op": "faced", "wall"}: the scene file edited (scene_edit.h), or 409.
void post_shots(StudioServer::Impl& s, const httplib::Request& req, httplib::Response& res) {
  const json body = body_json(req);
  const auto text = [&](const char* k) {
    if (!body.is_object() || !body.contains(k) || !body[k].is_string())
      throw InputError(req.path, fmt::format("expected a string \"{}\"", k));
    return body[k].get<std::string>();
  };
  const std::string op = text("op"), name = fs::path(s.scene_file.path()).filename().string();
  if (op != "swap" && op != "turn" && op != "faced")
    throw InputError(req.path + ":$.op", "expected swap, turn or faced");
  const int by_deg =
      op == "turn" && body.contains("by_deg") && body["by_deg"].is_number_integer() ? body["by_deg"].get<int>() : 90;
  const VersionedFile::UpdateResult r = s.scene_file.update(text("version"), [&](const std::string& scene) {
    if (op == "swap") return swap_shots(scene, name, text("a"), text("b"));
    if (op == "turn") return turn_shot(scene, name, text("key"), by_deg);
    return set_faced_wall(scene, name, text("wall"));
  });
  if (!r.saved) return reply_error(res, 409, name, kConflict);
  reply_json(res, json{{"version", r.now.version}});
}

// {"version", "op": "add", "polygon_px": [[u, v], ...], "albedo": a} | {"version", "op": "remove",
// "index": i}: the scene file's references of known albedo edited (scene_edit.h), the result
// read as the CLI reads it (a bad corner or albedo is refused where it is, nothing written), or 409.
void post_references(StudioServer::Impl& s, const httplib::Request& req, httplib::Response& res) {
  const json body = body_json(req);
  if (!body.is_object() || !body.contains("version") || !body["version"].is_string() || !body.contains("op"))
    throw InputError(req.path, "expected {\"version\": \"...\", \"op\": \"add\" | \"remove\", ...}");
  const std::string op = body["op"].is_string() ? body["op"].get<std::string>() : "";
  if (op != "add" && op != "remove") throw InputError(req.path + ":$.op", "expected add or remove");
  if (op == "remove" && !(body.contains("index") && body["index"].is_number_integer() &&
                          body["index"].get<long long>() >= 0 && body["index"].get<long long>() < (1 << 20)))
    throw InputError(req.path + ":$.index", "expected the index of a reference");
  const std::string& path = s.scene_file.path();
  const std::string name = fs::path(path).filename().string();
  const VersionedFile::UpdateResult r =
      s.scene_file.update(body["version"].get<std::string>(), [&](const std::string& scene) {
        std::string edited =
            op == "add" ? add_reference(scene, name, body) : remove_reference(scene, name, body["index"].get<int>());
        const SceneSpec spec =
            parse_scene_json(parse_json_text(edited, path), path, fs::path(path).parent_path().string());
        check_references(spec, s.width, s.height);
        return edited;
      });
  if (!r.saved) return reply_error(res, 409, name, kConflict);
  reply_json(res, json{{"version", r.now.version}});
}

// The scene's references as the page draws them, with the scene file's version to edit from.
json references_state(const StudioServer::Impl& s) {
  const FileVersion v = s.scene_file.read();
  const json scene = parse_json_text(v.text, s.scene_file.path());
  return {{"version", v.version},
          {"references", scene.is_object() && scene.contains("references") ? scene["references"] : json::array()}};
}

json shots_state(const StudioServer::Impl& s) {
  const FileVersion v = s.scene_file.read();
  json out = shots_view(s.scene_file.path());
  out["version"] = v.version;
  out["scene"] = fs::path(s.scene_file.path()).filename().string();
  return out;
}

// A number from the query (`name`), within [lo, hi]; `fallback` when absent.
double query_number(const httplib::Request& req, const char* name, double lo, double hi, double fallback) {
  if (!req.has_param(name)) return fallback;
  const std::string text = req.get_param_value(name);
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (text.empty() || *end != '\0' || !(v >= lo && v <= hi))
    throw InputError(req.path + "?" + name, fmt::format("expected a number in [{}, {}]", lo, hi));
  return v;
}

// The tone map the page asks for: ?tonemap=photo|adaptive_log|reinhard|linear&key=&bias= (the
// ranges the scene file accepts).
ToneMapSettings query_tonemap(const httplib::Request& req) {
  ToneMapSettings t;
  const std::string op = req.has_param("tonemap") ? req.get_param_value("tonemap") : "photo";
  const auto parsed = parse_name(kToneMaps, op);
  if (!parsed) throw InputError(req.path + "?tonemap", "expected " + quoted_choices(names_of(kToneMaps)));
  t.op = *parsed;
  if (req.has_param("key")) t.key = query_number(req, "key", 1e-6, 1e6, 1);
  t.bias = query_number(req, "bias", 0.01, 0.99, t.bias);
  return t;
}

// {"integrator": "" | name, "spp": 0 | n, "denoise": true | false}: a render started (render_job.h);
// its images are shown denoised unless "denoise" is false.
void post_render(StudioServer::Impl& s, const httplib::Request& req, httplib::Response& res) {
  const json body = req.body.empty() ? json::object() : body_json(req);
  if (!body.is_object())
    throw InputError(req.path, "expected {\"integrator\": \"path\", \"spp\": 64} (either may be left out)");
  static const json kNone;
  const JsonValue integrator(body.is_object() && body.contains("integrator") ? body["integrator"] : kNone, req.path,
                             "$.integrator");
  const JsonValue spp(body.is_object() && body.contains("spp") ? body["spp"] : kNone, req.path, "$.spp");
  const JsonValue denoise(body.is_object() && body.contains("denoise") ? body["denoise"] : kNone, req.path,
                          "$.denoise");
  const std::string name = integrator.raw().is_null() ? "" : integrator.string();
  if (!name.empty() && !find_integrator(name)) integrator.fail(unknown_integrator_message(name));
  s.render.start(name, spp.raw().is_null() ? 0 : int(spp.integer(1, 1 << 20)),
                 denoise.raw().is_null() || denoise.boolean());
  reply_json(res, s.render.status());
}

// The spp of the render whose report is `path` (-1 when it cannot be read).
int reported_spp(const std::string& path) {
  try {
    return read_json_file(path).at("render").at("spp").get<int>();
  } catch (const std::exception&) {
    return -1;
  }
}

// {} | {"overwrite": true}: the last finished render written to the scene's outputs. Outputs that
// exist already (a final render, say) are replaced only when asked: else 409 with
// {"error", "existing": [paths], "spp": this render's, "existing_spp": theirs or -1}, and the page
// asks the user, so that a preview never replaces a final render without a word.
void post_save(StudioServer::Impl& s, const httplib::Request& req, httplib::Response& res) {
  const json body = req.body.empty() ? json::object() : body_json(req);
  if (!body.is_object() || (body.contains("overwrite") && !body["overwrite"].is_boolean()))
    throw InputError(req.path, "expected {} or {\"overwrite\": true}");
  int spp = 0;
  const std::vector<std::string> paths = s.render.output_paths(&spp);
  json existing = json::array();
  for (const std::string& p : paths)
    if (fs::exists(p)) existing.push_back(fs::relative(p, s.folder).string());
  if (!existing.empty() && !body.value("overwrite", false)) {
    const int theirs = reported_spp(report_path(paths.front()));
    const std::string where = existing[0].get<std::string>();
    const std::string what =
        theirs > 0 ? fmt::format("exists, a render of {} spp: replace it with this one of {} spp?", theirs, spp)
                   : fmt::format("exists: replace it with this render of {} spp?", spp);
    res.status = 409;
    reply_json(res, json{{"error", where + ": " + what},
                         {"where", where},
                         {"what", what},
                         {"existing", existing},
                         {"spp", spp},
                         {"existing_spp", theirs}});
    return;
  }
  json written = json::array();
  for (const std::string& p : s.render.save_outputs()) written.push_back(fs::relative(p, s.folder).string());
  reply_json(res, json{{"written", written}});
}

}  // namespace

void StudioServer::Impl::add_render_routes() {
  http.Post("/api/render", [this](const httplib::Request& req, httplib::Response& res) {
    guarded(res, [&] { post_render(*this, req, res); });
  });
  http.Post("/api/render/stop", [this](const httplib::Request&, httplib::Response& res) {
    render.stop();
    reply_json(res, render.status());
  });
  http.Post("/api/render/save", [this](const httplib::Request& req, httplib::Response& res) {
    guarded(res, [&] { post_save(*this, req, res); });
  });
  http.Get("/api/render",
           [this](const httplib::Request&, httplib::Response& res) { reply_json(res, render.status()); });
  http.Get(R"(/api/render/(\w+)\.png)", [this](const httplib::Request& req, httplib::Response& res) {
    guarded(res, [&] {
      const auto png = render.png(req.matches[1], query_tonemap(req));
      if (!png) return reply_error(res, 404, req.path, "no image of that render yet");
      res.set_content(*png, "image/png");
    });
  });
  http.Get(R"(/api/light/(cube|irradiance)\.png)", [this](const httplib::Request& req, httplib::Response& res) {
    guarded(res, [&] {  // the previews are made here, on the first request
      const auto png = render.light_png(req.matches[1] == "irradiance");
      if (!png) return reply_error(res, 404, req.path, "no scene loaded yet: start a render");
      res.set_content(*png, "image/png");
    });
  });
}

void StudioServer::Impl::add_api_routes() {
  add_render_routes();
  http.Get("/api/shots", [this](const httplib::Request&, httplib::Response& res) {
    guarded(res, [&] { reply_json(res, shots_state(*this)); });
  });
  http.Get(R"(/api/shot/([0-5])\.png)", [this](const httplib::Request& req, httplib::Response& res) {
    guarded(res,
            [&] { res.set_content(shot_preview_png(scene_file.path(), std::stoi(req.matches[1]), 320), "image/png"); });
  });
  http.Get("/api/shots/stitched.png", [this](const httplib::Request&, httplib::Response& res) {
    guarded(res, [&] { res.set_content(stitched_png(scene_file.path(), 160), "image/png"); });
  });
  http.Post("/api/shots", [this](const httplib::Request& req, httplib::Response& res) {
    guarded(res, [&] { post_shots(*this, req, res); });
  });
  http.Get("/api/references", [this](const httplib::Request&, httplib::Response& res) {
    guarded(res, [&] { reply_json(res, references_state(*this)); });
  });
  http.Post("/api/references", [this](const httplib::Request& req, httplib::Response& res) {
    guarded(res, [&] { post_references(*this, req, res); });
  });
  http.Get("/api/state", [this](const httplib::Request&, httplib::Response& res) {
    guarded(res, [&] { reply_json(res, state_json(*this)); });
  });
  http.Put("/api/points", [this](const httplib::Request& req, httplib::Response& res) {
    guarded(res, [&] { put_points(*this, req, res); });
  });
  http.Post("/api/calibrate", [this](const httplib::Request& req, httplib::Response& res) {
    guarded(res, [&] { post_calibrate(*this, req, res); });
  });
  http.Post("/api/snap", [this](const httplib::Request& req, httplib::Response& res) {
    guarded(res, [&] { post_snap(*this, req, res); });
  });
}

}  // namespace insitu
