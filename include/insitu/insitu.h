/* insitu: physically based insertion of 3D furniture into a photograph of a room. The C API.
 *
 * C99, no C++ types; link with -linsitu (CMake: find_package(insitu) and insitu::insitu;
 * pkg-config: insitu). The `insitu` command line is a client of the same library.
 *
 * Conventions (DESIGN.md): world Y-up, metres; pixels from the top-left corner, x right, y down;
 * matrices row-major; images row by row from the top, channels interleaved, 32-bit float, linear.
 *
 * Errors. Every call that can fail returns an insitu_status; INSITU_OK is 0. The message of the
 * last failure on the calling thread, `where: what` as the CLI prints it (e.g.
 * "scene.json:$.objects[0].mesh: sofa.obj:31: face index 0 ..."), is insitu_last_error(). No
 * exception and no exit() crosses this API; a handle is left as it was when a call on it fails.
 *
 * Threads. Different scenes may be used from different threads at once, and one calibration or
 * result may be read from many threads at once. Calls on one scene must not overlap, with one
 * exception: insitu_scene_cancel() may be called from any thread at any time. The progress
 * callback runs on one of the render's threads, never on two at once.
 */
#ifndef INSITU_INSITU_H
#define INSITU_INSITU_H

#include <stddef.h>
#include <stdint.h>

#if defined(_WIN32)
#define INSITU_API __declspec(dllimport)
#elif defined(__GNUC__)
#define INSITU_API __attribute__((visibility("default")))
#else
#define INSITU_API
#endif

#ifdef __cplusplus
extern "C" {
#endif

/* The API this header describes; insitu_api_version() is the library's. */
#define INSITU_API_VERSION 1

typedef enum insitu_status {
  INSITU_OK = 0,
  INSITU_ERROR_INTERNAL = 1, /* a bug or an exhausted resource: the CLI's exit code 1 */
  INSITU_ERROR_INPUT = 2,    /* bad input (file, JSON, mesh, image, points): the CLI's exit code 2 */
  INSITU_ERROR_ARGUMENT = 3, /* a null handle, an unknown layer, a buffer too small */
  INSITU_CANCELLED = 4       /* the render was cancelled; its partial result is still returned */
} insitu_status;

typedef struct insitu_scene insitu_scene;
typedef struct insitu_result insitu_result;
typedef struct insitu_calibration insitu_calibration;

INSITU_API int insitu_api_version(void);
INSITU_API const char* insitu_version(void); /* "0.1.0" */
/* The last failure's message on this thread ("" if none); valid until the next call that fails. */
INSITU_API const char* insitu_last_error(void);

/* ---- Scenes --------------------------------------------------------------------------------- */

/* A scene file (docs/scene-file.md); relative paths in it are relative to the file. */
INSITU_API insitu_status insitu_scene_from_file(const char* path, insitu_scene** scene);
/* A scene as JSON text; relative paths are resolved against base_dir (NULL: the working
 * directory); `name` stands for the file in messages (NULL: "<json>"). */
INSITU_API insitu_status insitu_scene_from_json(const char* json, const char* base_dir, const char* name,
                                                insitu_scene** scene);
INSITU_API void insitu_scene_free(insitu_scene* scene);

/* Sets one scene-file value by its dotted key, the value as JSON text, exactly as if the file had
 * said so: ("render.spp", "64"), ("render.integrator", "\"path\""),
 * ("output.tonemap", "{\"op\": \"adaptive_log\"}"). Checked at once, like the file. */
INSITU_API insitu_status insitu_scene_set(insitu_scene* scene, const char* key, const char* json_value);

/* A mesh file placed by world_from_object (4x4, row-major, last row 0 0 0 1; NULL: identity):
 * OBJ with MTL, or glTF 2.0 (.gltf, .glb) with its principled materials, as the scene file's
 * "mesh" reads them. */
INSITU_API insitu_status insitu_scene_add_obj(insitu_scene* scene, const char* obj_path,
                                              const double world_from_object[16]);

/* A mesh from memory, copied: the arrays may be freed when the call returns. */
typedef struct insitu_mesh {
  const float* positions; /* 3 per vertex, object frame, metres */
  size_t vertex_count;
  const float* normals;    /* 3 per vertex, or NULL: the geometric normal */
  const float* uvs;        /* 2 per vertex, or NULL */
  const uint32_t* indices; /* 3 per triangle */
  size_t triangle_count;
  float kd[3];         /* diffuse reflectance, linear */
  float ks[3];         /* specular reflectance (0: none) */
  float ns;            /* Phong exponent of the glossy lobe */
  const float* map_kd; /* NULL, or linear RGB texels (3 floats each, top row first) that multiply kd */
  int map_kd_width, map_kd_height;
} insitu_mesh;
/* Fills a mesh with no arrays, kd 0.8 grey, no specular: set the arrays, then add it. */
INSITU_API void insitu_mesh_init(insitu_mesh* mesh);
/* `name` names the mesh in messages and reports (NULL: "mesh N"). */
INSITU_API insitu_status insitu_scene_add_mesh(insitu_scene* scene, const insitu_mesh* mesh,
                                               const double world_from_object[16], const char* name);

/* ---- Cameras and calibration ---------------------------------------------------------------- */

typedef struct insitu_camera {
  int width, height;          /* pixels; must be the photo's */
  double fx, fy, cx, cy;      /* pixels */
  double R_cam_from_world[9]; /* row-major; camera axes x right, y down, z forward (OpenCV) */
  double t_cam_from_world[3]; /* metres: p_cam = R p_world + t */
} insitu_camera;

typedef struct insitu_control_point {
  double u_px, v_px;    /* from the photo's top-left corner */
  double x_m, y_m, z_m; /* world */
} insitu_control_point;

/* Calibrates a camera for a width x height photo from n >= 5 control points, as
 * `insitu calibrate`: model NULL or "auto" (chosen by an F-test), "f", "f+c" or "f+c+a";
 * at_world (3 doubles, or NULL) is where the uncertainty in pixels is reported. */
INSITU_API insitu_status insitu_calibrate(const insitu_control_point* points, size_t n, int width, int height,
                                          const char* model, const double* at_world, insitu_calibration** out);
INSITU_API void insitu_calibration_free(insitu_calibration* calibration);
INSITU_API insitu_status insitu_calibration_camera(const insitu_calibration* calibration, insitu_camera* camera);
INSITU_API double insitu_calibration_rms_px(const insitu_calibration* calibration);
/* The report `insitu calibrate` prints, and the camera.json it writes (valid while the handle lives). */
INSITU_API const char* insitu_calibration_report(const insitu_calibration* calibration);
INSITU_API const char* insitu_calibration_json(const insitu_calibration* calibration);
/* Adds an object's bounding box (world metres): the report and the JSON gain the uncertainty at
 * its corners and, over all boxes, where one more click would help most (`--box`). */
/* What `insitu calibrate --blender` writes: a Blender Python script that creates the camera, with
 * the photo (NULL: none) as its background; valid while the handle lives. */
INSITU_API const char* insitu_calibration_blender_script(insitu_calibration* calibration, const char* photo_path);
/* What `insitu calibrate --vc` writes: the View Correlation parameter set of the camera and the
 * inlying points. Refuses to replace an existing file that is not a .vc file. */
INSITU_API insitu_status insitu_calibration_write_vc(const insitu_calibration* calibration, const char* path);
INSITU_API insitu_status insitu_calibration_add_box(insitu_calibration* calibration, const char* name,
                                                    const double lo_world[3], const double hi_world[3]);

/* The scene's camera from now on: an explicit one, or calibrated from points (as the scene file's
 * "camera": {"points": ...}; the render's report then carries the calibration). */
INSITU_API insitu_status insitu_scene_set_camera(insitu_scene* scene, const insitu_camera* camera);
INSITU_API insitu_status insitu_scene_set_control_points(insitu_scene* scene, const insitu_control_point* points,
                                                         size_t n, const char* model);
/* The camera the scene renders with (loads the scene: the photo, the light, the meshes). */
INSITU_API insitu_status insitu_scene_camera(insitu_scene* scene, insitu_camera* camera);
/* The calibration's report for a camera from points ("" otherwise); valid until the scene changes. */
INSITU_API insitu_status insitu_scene_calibration_report(insitu_scene* scene, const char** report);
/* The warnings loading the scene gave, one per line ("" if none); valid until the scene changes. */
INSITU_API insitu_status insitu_scene_warnings(insitu_scene* scene, const char** warnings);

/* ---- Rendering ------------------------------------------------------------------------------ */

typedef struct insitu_progress {
  int spp_done; /* samples per pixel every pixel has */
  int spp_planned;
  double fraction;     /* of the whole render, 0..1 */
  double noise;        /* mean relative standard error over changed pixels; < 0 between passes */
  double seconds;      /* since the render began */
  double seconds_left; /* estimated; < 0 before there is an estimate */
} insitu_progress;
/* Return nonzero to cancel the render. */
typedef int (*insitu_progress_fn)(const insitu_progress* progress, void* user);

/* Renders with the scene's settings. The scene is loaded first if it changed (the photo, the
 * light, the meshes: what insitu_scene_set and the add_ and set_ calls touched). With a progress
 * callback it is called when the render starts, as tiles finish and after every pass.
 *
 * Cancellation (the callback returning nonzero, or insitu_scene_cancel from another thread) takes
 * effect after the tile under way: at most one pass, and a fraction of a second when a pass is
 * longer. The call then returns INSITU_CANCELLED and *result holds the samples taken: the pixels
 * a cancelled pass reached have its samples, the others not (the "samples" layer says which). */
INSITU_API insitu_status insitu_render(insitu_scene* scene, insitu_progress_fn progress, void* user,
                                       insitu_result** result);
INSITU_API void insitu_scene_cancel(insitu_scene* scene);
/* As insitu_render, resumable as `insitu render --resume` is: when `checkpoint_path` holds a
 * checkpoint of this scene and these settings the render continues from it (one of another scene
 * or other settings is refused, INSITU_ERROR_INPUT); a cancelled render writes its checkpoint
 * there, and a finished one removes it. The result is bit-identical to an uninterrupted render. */
INSITU_API insitu_status insitu_render_resumable(insitu_scene* scene, const char* checkpoint_path,
                                                 insitu_progress_fn progress, void* user, insitu_result** result);

INSITU_API void insitu_result_free(insitu_result* result);
INSITU_API int insitu_result_width(const insitu_result* result);
INSITU_API int insitu_result_height(const insitu_result* result);
INSITU_API int insitu_result_spp(const insitu_result* result);       /* samples taken */
INSITU_API int insitu_result_cancelled(const insitu_result* result); /* 1 if fewer than planned */
/* The render's report (the CLI's IMAGE.report.json) as JSON text, valid while the result lives. */
INSITU_API const char* insitu_result_report(const insitu_result* result);

/* The layers, by name, as in the CLI's layered EXR: "composite" (RGB), "objects" (RGBA),
 * "with", "without", "shadow_ratio", "normal" (XYZ), "albedo", "depth" (Z), "samples" (Y),
 * "variance" (Y), "photo", and "display" (what the PNG holds, before its 8-bit rounding). */
INSITU_API int insitu_result_layer_count(const insitu_result* result);
INSITU_API const char* insitu_result_layer_name(const insitu_result* result, int index); /* NULL if out of range */
/* The layer owned by the result (valid while it lives), width x height x *channels floats. */
INSITU_API insitu_status insitu_result_layer(const insitu_result* result, const char* name, const float** data,
                                             int* channels);
/* The layer copied into the caller's buffer of `floats` floats (width x height x channels). */
INSITU_API insitu_status insitu_result_copy_layer(const insitu_result* result, const char* name, float* buffer,
                                                  size_t floats);
/* Writes what `insitu render` writes: the image (.png, .jpg, .exr, .tif), its report beside it,
 * and the layered EXR (layers_path NULL: none). Refuses a path that is one of the scene's inputs. */
INSITU_API insitu_status insitu_result_write(const insitu_result* result, const char* image_path,
                                             const char* layers_path);

#ifdef __cplusplus
}
#endif

#endif /* INSITU_INSITU_H */
