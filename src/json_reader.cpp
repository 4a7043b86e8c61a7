#include "json_reader.h"

#include <filesystem>
#include <fmt/format.h>
#include <fstream>
#include <sstream>

namespace insitu {

json read_json_file(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path, std::filesystem::exists(path) ? "cannot read file" : "file not found");
  std::stringstream ss;
  ss << in.rdbuf();
  const std::string text = ss.str();
  try {
    return json::parse(text);
  } catch (const json::parse_error& e) {
    // e.byte is the 1-based offset of the failure; turn it into line:col.
    const std::size_t byte = e.byte == 0 ? 0 : std::min<std::size_t>(e.byte - 1, text.size());
    int line = 1, col = 1;
    for (std::size_t i = 0; i < byte; ++i) {
      if (text[i] == '\n') { ++line; col = 1; } else { ++col; }
    }
    std::string what = e.what();
    // nlohmann's message is "[json.exception.parse_error.101] parse error at line L, column C: ..."
    if (auto p = what.find(": "); p != std::string::npos) what = what.substr(p + 2);
    throw InputError(fmt::format("{}:{}:{}", path, line, col), "malformed JSON: " + what);
  }
}

double JsonValue::number(double lo, double hi) const {
  if (!j_.is_number()) fail(fmt::format("expected a number, got {}", j_.type_name()));
  const double x = j_.get<double>();
  if (!std::isfinite(x)) fail("expected a finite number");
  if (x < lo || x > hi) fail(fmt::format("{} is out of range [{}, {}]", x, lo, hi));
  return x;
}

long JsonValue::integer(long lo, long hi) const {
  if (!j_.is_number_integer()) fail(fmt::format("expected an integer, got {}", j_.dump()));
  const long x = j_.get<long>();
  if (x < lo || x > hi) fail(fmt::format("{} is out of range [{}, {}]", x, lo, hi));
  return x;
}

bool JsonValue::boolean() const {
  if (!j_.is_boolean()) fail(fmt::format("expected true or false, got {}", j_.type_name()));
  return j_.get<bool>();
}

std::string JsonValue::string() const {
  if (!j_.is_string()) fail(fmt::format("expected a string, got {}", j_.type_name()));
  return j_.get<std::string>();
}

std::size_t JsonValue::size() const {
  if (!j_.is_array()) fail(fmt::format("expected an array, got {}", j_.type_name()));
  return j_.size();
}

JsonValue JsonValue::element(std::size_t i) const {
  return JsonValue(j_.at(i), file_, fmt::format("{}[{}]", path_, i));
}

Vec3d JsonValue::vec3() const {
  if (!j_.is_array() || j_.size() != 3) fail("expected an array of 3 numbers");
  return {element(0).number(), element(1).number(), element(2).number()};
}

Mat4d JsonValue::mat4() const {
  if (!j_.is_array() || j_.size() != 4) fail("expected 4 rows of 4 numbers");
  Mat4d m;
  for (std::size_t r = 0; r < 4; ++r) {
    const JsonValue row = element(r);
    if (!row.raw().is_array() || row.raw().size() != 4) row.fail("expected a row of 4 numbers");
    for (std::size_t c = 0; c < 4; ++c) m(long(r), long(c)) = row.element(c).number();
  }
  return m;
}

JsonObject::JsonObject(const JsonValue& v) : value_(v) {
  if (!v.raw().is_object()) v.fail(fmt::format("expected an object, got {}", v.raw().type_name()));
}

JsonValue JsonObject::get(const std::string& key) {
  auto v = find(key);
  if (!v) fail(fmt::format("missing required key '{}'", key));
  return *v;
}

std::optional<JsonValue> JsonObject::find(const std::string& key) {
  used_.insert(key);
  const auto it = value_.raw().find(key);
  if (it == value_.raw().end()) return std::nullopt;
  return JsonValue(*it, value_.file(), value_.path() + "." + key);
}

void JsonObject::finish() const {
  for (auto it = value_.raw().begin(); it != value_.raw().end(); ++it)
    if (!used_.count(it.key())) {
      std::string known;
      for (const auto& k : used_) known += (known.empty() ? "" : ", ") + k;
      throw InputError(value_.where() + "." + it.key(), fmt::format("unknown key (expected one of: {})", known));
    }
}

}  // namespace insitu
