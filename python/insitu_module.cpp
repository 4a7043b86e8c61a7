// The insitu Python module: the C API (include/insitu/insitu.h) for Python and numpy, with
// pybind11. Layers come back as float32 arrays of shape (height, width, channels), the floats of
// the CLI's layered EXR; errors are insitu.Error with the CLI's `where: what` and its code.
//
//   import insitu
//   scene = insitu.Scene("scenes/demo/scene.json")
//   scene.set("render.spp", 16)
//   result = scene.render(progress=lambda p: print(p["spp_done"]))
//   alpha = result.layers["objects"][..., 3]
//
// The render releases the GIL; the progress callback takes it back while it runs. A callback that
// returns True, or raises, cancels the render (the exception is raised again afterwards).
#include <pybind11/functional.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <insitu/insitu.h>

#include <array>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace py = pybind11;

namespace {

struct Error : std::runtime_error {
  insitu_status code;
  Error(insitu_status c, const std::string& message) : std::runtime_error(message), code(c) {}
};

void check(insitu_status status) {
  if (status != INSITU_OK && status != INSITU_CANCELLED) throw Error(status, insitu_last_error());
}

std::string json_text(const py::object& value) { return py::str(py::module_::import("json").attr("dumps")(value)); }

// A 4x4 row-major matrix from anything numpy reads as one (None: identity).
std::optional<std::array<double, 16>> matrix(const py::object& m) {
  if (m.is_none()) return std::nullopt;
  auto a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(m);
  if (!a || a.size() != 16) throw py::value_error("matrix: expected a 4x4 array");
  std::array<double, 16> out;
  std::copy(a.data(), a.data() + 16, out.begin());
  return out;
}

using FloatArray = py::array_t<float, py::array::c_style | py::array::forcecast>;

FloatArray floats(const py::object& a, std::size_t per_row, const char* what) {
  auto arr = FloatArray::ensure(a);
  if (!arr || arr.size() % py::ssize_t(per_row) != 0)
    throw py::value_error(std::string(what) + ": expected an array of shape (n, " + std::to_string(per_row) + ")");
  return arr;
}

py::dict camera_dict(const insitu_camera& c) {
  py::dict d;
  d["width"] = c.width, d["height"] = c.height, d["fx"] = c.fx, d["fy"] = c.fy, d["cx"] = c.cx, d["cy"] = c.cy;
  py::array_t<double> R({3, 3});
  std::copy(c.R_cam_from_world, c.R_cam_from_world + 9, R.mutable_data());
  d["R_cam_from_world"] = R;
  d["t_cam_from_world"] = py::make_tuple(c.t_cam_from_world[0], c.t_cam_from_world[1], c.t_cam_from_world[2]);
  return d;
}

std::vector<insitu_control_point> control_points(const py::object& points) {
  auto a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(points);
  if (!a || a.ndim() != 2 || a.shape(1) != 5)
    throw py::value_error("points: expected an array of shape (n, 5): u_px, v_px, x, y, z");
  std::vector<insitu_control_point> out(std::size_t(a.shape(0)));
  for (std::size_t i = 0; i < out.size(); ++i) {
    const double* p = a.data() + 5 * i;
    out[i] = {p[0], p[1], p[2], p[3], p[4]};
  }
  return out;
}

class Result {
 public:
  explicit Result(insitu_result* r) : r_(r, insitu_result_free) {}
  int width() const { return insitu_result_width(r_.get()); }
  int height() const { return insitu_result_height(r_.get()); }
  int spp() const { return insitu_result_spp(r_.get()); }
  bool cancelled() const { return insitu_result_cancelled(r_.get()) != 0; }
  py::object report() const { return py::module_::import("json").attr("loads")(insitu_result_report(r_.get())); }
  py::array_t<float> layer(const std::string& name) const {
    const float* data = nullptr;
    int channels = 0;
    check(insitu_result_layer(r_.get(), name.c_str(), &data, &channels));
    py::array_t<float> out({py::ssize_t(height()), py::ssize_t(width()), py::ssize_t(channels)});
    std::copy(data, data + out.size(), out.mutable_data());
    return out;
  }
  py::dict layers() const {
    py::dict d;
    for (int i = 0; i < insitu_result_layer_count(r_.get()); ++i) {
      const char* name = insitu_result_layer_name(r_.get(), i);
      d[name] = layer(name);
    }
    return d;
  }
  void write(const std::string& image, const std::optional<std::string>& layers) const {
    check(insitu_result_write(r_.get(), image.c_str(), layers ? layers->c_str() : nullptr));
  }

 private:
  std::shared_ptr<insitu_result> r_;
};

// The progress callback's state: the Python function, and what it raised.
struct Progress {
  py::function fn;
  std::optional<py::error_already_set> error;
};

int call_progress(const insitu_progress* p, void* user) {
  auto& prog = *static_cast<Progress*>(user);
  py::gil_scoped_acquire gil;
  if (prog.error) return 1;
  try {
    py::dict d;
    d["spp_done"] = p->spp_done, d["spp_planned"] = p->spp_planned, d["fraction"] = p->fraction;
    d["noise"] = p->noise, d["seconds"] = p->seconds, d["seconds_left"] = p->seconds_left;
    return py::bool_(prog.fn(d)) ? 1 : 0;
  } catch (py::error_already_set& e) {
    prog.error = std::move(e);
    return 1;
  }
}

// A Scene is used by one call at a time (the C API's rule, include/insitu/insitu.h). render()
// releases the GIL, so another Python thread could call into the same scene meanwhile: set()
// freed what the render read (issue 46: a use-after-free). Such a call is refused with an
// insitu.Error instead (serialising it would deadlock: the waiting thread holds the GIL, which
// the render's progress callback needs); cancel() alone may come from another thread. `busy_` is
// set and cleared with the GIL held, and every other method runs with the GIL held throughout,
// so the check cannot race.
class Scene {
 public:
  explicit Scene(const std::string& path) {
    insitu_scene* s = nullptr;
    check(insitu_scene_from_file(path.c_str(), &s));
    s_.reset(s);
  }
  static Scene from_json(const py::object& scene, const std::optional<std::string>& base_dir,
                         const std::optional<std::string>& name) {
    const std::string text = py::isinstance<py::str>(scene) ? scene.cast<std::string>() : json_text(scene);
    insitu_scene* s = nullptr;
    check(insitu_scene_from_json(text.c_str(), base_dir ? base_dir->c_str() : nullptr, name ? name->c_str() : nullptr,
                                 &s));
    return Scene(s);
  }
  void set(const std::string& key, const py::object& value) {
    require_idle();
    check(insitu_scene_set(s_.get(), key.c_str(), json_text(value).c_str()));
  }
  void add_obj(const std::string& path, const py::object& m) {
    require_idle();
    const auto M = matrix(m);
    check(insitu_scene_add_obj(s_.get(), path.c_str(), M ? M->data() : nullptr));
  }
  void add_mesh(const py::object& positions, const py::object& indices, const py::object& normals,
                const py::object& uvs, std::array<float, 3> kd, std::array<float, 3> ks, float ns,
                const py::object& map_kd, const py::object& m, const std::optional<std::string>& name) {
    require_idle();
    const FloatArray p = floats(positions, 3, "positions");
    const auto idx = py::array_t<std::uint32_t, py::array::c_style | py::array::forcecast>::ensure(indices);
    if (!idx || idx.size() % 3 != 0) throw py::value_error("indices: expected an array of shape (n, 3)");
    std::optional<FloatArray> n, t, tex;
    insitu_mesh mesh;
    insitu_mesh_init(&mesh);
    mesh.positions = p.data(), mesh.vertex_count = std::size_t(p.size() / 3);
    mesh.indices = idx.data(), mesh.triangle_count = std::size_t(idx.size() / 3);
    if (!normals.is_none()) n = floats(normals, 3, "normals"), mesh.normals = n->data();
    if (!uvs.is_none()) t = floats(uvs, 2, "uvs"), mesh.uvs = t->data();
    if ((n && n->size() != p.size()) || (t && t->size() / 2 != p.size() / 3))
      throw py::value_error("normals and uvs: one per vertex");
    std::copy(kd.begin(), kd.end(), mesh.kd), std::copy(ks.begin(), ks.end(), mesh.ks), mesh.ns = ns;
    if (!map_kd.is_none()) {
      tex = FloatArray::ensure(map_kd);
      if (!tex || tex->ndim() != 3 || tex->shape(2) != 3)
        throw py::value_error("map_kd: expected an array of shape (h, w, 3)");
      mesh.map_kd = tex->data(), mesh.map_kd_height = int(tex->shape(0)), mesh.map_kd_width = int(tex->shape(1));
    }
    const auto M = matrix(m);
    check(insitu_scene_add_mesh(s_.get(), &mesh, M ? M->data() : nullptr, name ? name->c_str() : nullptr));
  }
  void set_camera(const py::dict& c) {
    require_idle();
    insitu_camera cam{};
    cam.width = c["width"].cast<int>(), cam.height = c["height"].cast<int>();
    cam.fx = c["fx"].cast<double>(), cam.fy = c["fy"].cast<double>(), cam.cx = c["cx"].cast<double>(),
    cam.cy = c["cy"].cast<double>();
    auto R = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(c["R_cam_from_world"]);
    auto t = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(c["t_cam_from_world"]);
    if (!R || R.size() != 9 || !t || t.size() != 3)
      throw py::value_error("camera: R_cam_from_world 3x3 and t_cam_from_world 3");
    std::copy(R.data(), R.data() + 9, cam.R_cam_from_world), std::copy(t.data(), t.data() + 3, cam.t_cam_from_world);
    check(insitu_scene_set_camera(s_.get(), &cam));
  }
  void set_control_points(const py::object& points, const std::optional<std::string>& model) {
    require_idle();
    const auto pts = control_points(points);
    check(insitu_scene_set_control_points(s_.get(), pts.data(), pts.size(), model ? model->c_str() : nullptr));
  }
  py::dict camera() {
    require_idle();
    insitu_camera c;
    check(insitu_scene_camera(s_.get(), &c));
    return camera_dict(c);
  }
  std::string text(insitu_status (*get)(insitu_scene*, const char**)) {
    require_idle();
    const char* t = nullptr;
    check(get(s_.get(), &t));
    return t;
  }
  Result render(const std::optional<py::function>& progress, const std::optional<std::string>& checkpoint) {
    require_idle();
    const Busy busy(busy_);
    Progress prog{progress ? *progress : py::function(), std::nullopt};
    insitu_result* r = nullptr;
    insitu_status status;
    {
      py::gil_scoped_release release;
      status = checkpoint ? insitu_render_resumable(s_.get(), checkpoint->c_str(), progress ? call_progress : nullptr,
                                                    &prog, &r)
                          : insitu_render(s_.get(), progress ? call_progress : nullptr, &prog, &r);
    }
    Result result(r);
    if (prog.error) throw std::move(*prog.error);
    check(status);
    return result;
  }
  void cancel() { insitu_scene_cancel(s_.get()); }

 private:
  struct Busy {
    explicit Busy(bool& b) : b_(b) { b_ = true; }
    ~Busy() { b_ = false; }
    bool& b_;
  };
  void require_idle() const {
    if (busy_)
      throw Error(INSITU_ERROR_ARGUMENT,
                  "insitu.Scene: a render of this scene is under way in another thread; "
                  "wait for it, or cancel() it first");
  }
  bool busy_ = false;
  explicit Scene(insitu_scene* s) : s_(s, insitu_scene_free) {}
  std::unique_ptr<insitu_scene, decltype(&insitu_scene_free)> s_{nullptr, insitu_scene_free};
};

class Calibration {
 public:
  Calibration(const py::object& points, int width, int height, const std::optional<std::string>& model,
              const py::object& at) {
    const auto pts = control_points(points);
    std::optional<std::array<double, 3>> at_world;
    if (!at.is_none()) at_world = at.cast<std::array<double, 3>>();
    insitu_calibration* c = nullptr;
    check(insitu_calibrate(pts.data(), pts.size(), width, height, model ? model->c_str() : nullptr,
                           at_world ? at_world->data() : nullptr, &c));
    c_.reset(c);
  }
  py::dict camera() const {
    insitu_camera cam;
    check(insitu_calibration_camera(c_.get(), &cam));
    return camera_dict(cam);
  }
  double rms_px() const { return insitu_calibration_rms_px(c_.get()); }
  std::string report() const { return insitu_calibration_report(c_.get()); }
  std::string json() const { return insitu_calibration_json(c_.get()); }
  std::string blender_script(const std::optional<std::string>& photo) {
    return insitu_calibration_blender_script(c_.get(), photo ? photo->c_str() : nullptr);
  }
  void write_vc(const std::string& path) const { check(insitu_calibration_write_vc(c_.get(), path.c_str())); }
  void add_box(const std::string& name, std::array<double, 3> lo, std::array<double, 3> hi) {
    check(insitu_calibration_add_box(c_.get(), name.c_str(), lo.data(), hi.data()));
  }

 private:
  std::unique_ptr<insitu_calibration, decltype(&insitu_calibration_free)> c_{nullptr, insitu_calibration_free};
};

}  // namespace

PYBIND11_MODULE(insitu, m) {
  m.doc() = "insitu: physically based insertion of 3D furniture into a photograph of a room";
  // insitu.Error(message) with .code: INPUT_ERROR (bad input), ARGUMENT_ERROR or INTERNAL_ERROR.
  static py::exception<Error> error_type(m, "Error");
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const Error& e) {
      py::object exc = py::reinterpret_borrow<py::object>(error_type.ptr())(e.what());
      exc.attr("code") = int(e.code);
      PyErr_SetObject(error_type.ptr(), exc.ptr());
    }
  });
  m.attr("INPUT_ERROR") = int(INSITU_ERROR_INPUT);
  m.attr("ARGUMENT_ERROR") = int(INSITU_ERROR_ARGUMENT);
  m.attr("INTERNAL_ERROR") = int(INSITU_ERROR_INTERNAL);
  m.def("version", [] { return std::string(insitu_version()); });

  py::class_<Result>(m, "Result", "a render's layers, report and files")
      .def_property_readonly("width", &Result::width)
      .def_property_readonly("height", &Result::height)
      .def_property_readonly("spp", &Result::spp, "samples per pixel taken")
      .def_property_readonly("cancelled", &Result::cancelled)
      .def_property_readonly("report", &Result::report, "the render's report (the CLI's IMAGE.report.json)")
      .def_property_readonly("layers", &Result::layers, "every layer: name -> float32 array (height, width, channels)")
      .def("layer", &Result::layer, py::arg("name"))
      .def("write", &Result::write, py::arg("image"), py::arg("layers") = py::none(),
           "write the image, its report and (optionally) the layered EXR, as `insitu render` does");

  py::class_<Scene>(m, "Scene", "a scene: a photo, a camera, the room's light and objects")
      .def(py::init<const std::string&>(), py::arg("path"))
      .def_static("from_json", &Scene::from_json, py::arg("scene"), py::arg("base_dir") = py::none(),
                  py::arg("name") = py::none(), "a scene from JSON text or a dict")
      .def("set", &Scene::set, py::arg("key"), py::arg("value"),
           "set a scene-file value by dotted key: set('render.spp', 64)")
      .def("add_obj", &Scene::add_obj, py::arg("path"), py::arg("matrix") = py::none(),
           "add a mesh file, OBJ or glTF 2.0 (.gltf, .glb), placed by a 4 x 4 matrix")
      .def("add_mesh", &Scene::add_mesh, py::arg("positions"), py::arg("indices"), py::arg("normals") = py::none(),
           py::arg("uvs") = py::none(), py::arg("kd") = std::array<float, 3>{0.8f, 0.8f, 0.8f},
           py::arg("ks") = std::array<float, 3>{0, 0, 0}, py::arg("ns") = 0.0f, py::arg("map_kd") = py::none(),
           py::arg("matrix") = py::none(), py::arg("name") = py::none())
      .def("set_camera", &Scene::set_camera, py::arg("camera"))
      .def("set_control_points", &Scene::set_control_points, py::arg("points"), py::arg("model") = py::none(),
           "calibrate from points: an array (n, 5) of u_px, v_px, x, y, z")
      .def_property_readonly("camera", &Scene::camera)
      .def_property_readonly("calibration_report", [](Scene& s) { return s.text(insitu_scene_calibration_report); })
      .def_property_readonly("warnings", [](Scene& s) { return s.text(insitu_scene_warnings); })
      .def("render", &Scene::render, py::arg("progress") = py::none(), py::arg("checkpoint") = py::none(),
           "render; progress(dict) is called as tiles and passes finish, and cancels the render by returning True; "
           "with a checkpoint path, a cancelled render writes its checkpoint and the next call continues from it")
      .def("cancel", &Scene::cancel, "cancel the render under way (from another thread)");

  py::class_<Calibration>(m, "Calibration", "a camera calibrated from 2D-3D control points")
      .def(py::init<const py::object&, int, int, const std::optional<std::string>&, const py::object&>(),
           py::arg("points"), py::arg("width"), py::arg("height"), py::arg("model") = py::none(),
           py::arg("at") = py::none())
      .def_property_readonly("camera", &Calibration::camera)
      .def_property_readonly("rms_px", &Calibration::rms_px)
      .def_property_readonly("report", &Calibration::report)
      .def_property_readonly("json", &Calibration::json)
      .def("blender_script", &Calibration::blender_script, py::arg("photo") = py::none())
      .def("write_vc", &Calibration::write_vc, py::arg("path"))
      .def("add_box", &Calibration::add_box, py::arg("name"), py::arg("lo"), py::arg("hi"));
}
