// Reading JSON with errors that say where: every value knows its path ("$.objects[2].mesh"),
// typed getters check type and range, and finish() rejects keys nobody asked for, so that a typo
// never falls back to a default silently (DESIGN.md "Scene file").
#pragma once
#include <nlohmann/json.hpp>
#include <optional>
#include <cstdint>
#include <set>
#include <string>

#include "core/error.h"
#include "core/math.h"

namespace insitu {

using nlohmann::json;

// Scene and points files are small; a larger file is refused before it is read.
constexpr std::uintmax_t kMaxJsonBytes = std::uintmax_t(64) << 20;

// Parses a JSON file; syntax errors name file, line and column. Refused too: a directory, a file
// over kMaxJsonBytes, a NUL byte (line:col), a number no double holds (1e400), and a key given
// twice in one object (its JSON path).
json read_json_file(const std::string& path);
// The same checks for JSON text held in memory; `name` stands for the file in messages.
json parse_json_text(const std::string& text, const std::string& name);
// JSON text of `j` (indent as json::dump's). Strings that are not UTF-8 (a file name in another
// encoding: Linux allows any bytes) are written with U+FFFD for their bad bytes; json::dump would
// throw instead, after the images were written and before the report.
inline std::string json_text(const json& j, int indent = -1) {
  return j.dump(indent, ' ', false, json::error_handler_t::replace);
}

class JsonValue {
 public:
  JsonValue(const json& j, std::string file, std::string path)
      : j_(j), file_(std::move(file)), path_(std::move(path)) {}
  const json& raw() const { return j_; }
  const std::string& path() const { return path_; }
  const std::string& file() const { return file_; }
  std::string where() const { return file_ + ":" + path_; }
  [[noreturn]] void fail(const std::string& what) const { throw InputError(where(), what); }

  double number(double lo = -HUGE_VAL, double hi = HUGE_VAL) const;
  long integer(long lo, long hi) const;
  bool boolean() const;
  std::string string() const;
  Vec3d vec3() const;        // [x, y, z], finite
  Mat4d mat4() const;        // 4 rows of 4, finite
  std::size_t size() const;  // of an array
  JsonValue element(std::size_t i) const;
  bool is_string() const { return j_.is_string(); }
  bool is_number() const { return j_.is_number(); }
  bool is_object() const { return j_.is_object(); }
  bool is_array() const { return j_.is_array(); }

 private:
  const json& j_;
  std::string file_, path_;
};

// How far a given rotation matrix may be from orthonormal, ‖R Rᵀ − I‖_F, before it is refused;
// within it the nearest rotation is used (exporters round R to about 6 decimals).
constexpr double kRotationTolerance = 1e-3;

// A rotation as exporters write it (camera.json's R, fSpy's camera transform): Blender and most
// JSON writers round to about 6 decimals, so R Rᵀ is the identity only to ~1e-6. Accepted up to
// ‖R Rᵀ − I‖_F ≤ kRotationTolerance with det R > 0 and replaced by the nearest rotation (SVD); a
// warning at `where` above 1e-6 says so. Beyond the tolerance, or mirrored, `where` fails.
Mat3d checked_rotation(const Mat3d& R, const JsonValue& where, Warnings* warnings);

// A JSON value kept with its file and path, read later by the code that owns its keys (an
// integrator's parameters: src/integrators/registry.h).
struct JsonBlock {
  json value;
  std::string file, path;
  JsonValue view() const { return JsonValue(value, file, path); }
};

class JsonObject {
 public:
  JsonObject(const JsonValue& v);  // fails unless v is an object
  std::string where() const { return value_.where(); }
  bool has(const std::string& key) const { return value_.raw().contains(key); }
  JsonValue get(const std::string& key);  // required
  std::optional<JsonValue> find(const std::string& key);
  // Fails naming every key that get/find never asked for.
  void finish() const;
  [[noreturn]] void fail(const std::string& what) const { value_.fail(what); }

 private:
  JsonValue value_;
  std::set<std::string> used_;
};

}  // namespace insitu
