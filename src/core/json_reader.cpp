#include "core/json_reader.h"
#include "core/file_check.h"

#include <filesystem>
#include <fmt/format.h>
#include <fstream>
#include <sstream>

namespace insitu {

namespace {

std::string line_col(const std::string& text, std::size_t byte) {
  int line = 1, col = 1;
  for (std::size_t i = 0; i < std::min(byte, text.size()); ++i) {
    if (text[i] == '\n') {
      ++line;
      col = 1;
    } else {
      ++col;
    }
  }
  return fmt::format("{}:{}", line, col);
}

// Rejects duplicate keys during parsing (nlohmann keeps the last one silently), naming the JSON
// path of the second occurrence. The stack mirrors the containers being parsed.
class DuplicateKeyCheck {
 public:
  explicit DuplicateKeyCheck(const std::string& file) : file_(file) {}
  bool operator()(int /*depth*/, json::parse_event_t event, json& parsed) {
    using E = json::parse_event_t;
    switch (event) {
      case E::object_start:
        stack_.push_back({true, {}, "", 0});
        break;
      case E::array_start:
        stack_.push_back({false, {}, "", 0});
        break;
      case E::key: {
        Level& top = stack_.back();
        top.key = parsed.get<std::string>();
        if (!top.keys.insert(top.key).second)
          throw InputError(file_ + ":" + path(), "duplicate key (the JSON has it twice)");
        break;
      }
      case E::object_end:
      case E::array_end:
        stack_.pop_back();
        element_done();
        break;
      case E::value:
        element_done();
        break;
    }
    return true;
  }

 private:
  struct Level {
    bool object;
    std::set<std::string> keys;
    std::string key;  // objects: the current member
    long index;       // arrays: the current element
  };
  void element_done() {
    if (!stack_.empty() && !stack_.back().object) ++stack_.back().index;
  }
  std::string path() const {
    std::string p = "$";
    for (const Level& l : stack_) p += l.object ? "." + l.key : fmt::format("[{}]", l.index);
    return p;
  }
  std::string file_;
  std::vector<Level> stack_;
};

}  // namespace

json read_json_file(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw InputError(path, "is a directory, not a JSON file");
  const auto size = std::filesystem::file_size(path, ec);
  if (!ec && size > kMaxJsonBytes)
    throw InputError(path, fmt::format("{} bytes: too large for a scene or points file (at most {} MiB)", size,
                                       kMaxJsonBytes >> 20));
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, exists_quietly(path) ? "cannot read file" : "file not found");
  std::stringstream ss;
  ss << in.rdbuf();
  return parse_json_text(ss.str(), path);
}

json parse_json_text(const std::string& text, const std::string& name) {
  if (text.size() > kMaxJsonBytes)
    throw InputError(name, fmt::format("{} bytes: too large for a scene or points text (at most {} MiB)", text.size(),
                                       kMaxJsonBytes >> 20));
  if (const auto nul = text.find('\0'); nul != std::string::npos)
    throw InputError(fmt::format("{}:{}", name, line_col(text, nul)), "a NUL byte: this is not a JSON text");
  try {
    return json::parse(text, DuplicateKeyCheck(name));
  } catch (const json::parse_error& e) {
    // e.byte is the 1-based offset of the failure; turn it into line:col.
    const std::size_t byte = e.byte == 0 ? 0 : e.byte - 1;
    std::string what = e.what();
    // nlohmann's message is "[json.exception.parse_error.101] parse error at line L, column C: ..."
    if (auto p = what.find(": "); p != std::string::npos) what = what.substr(p + 2);
    throw InputError(fmt::format("{}:{}", name, line_col(text, byte)), "malformed JSON: " + what);
  } catch (const json::exception& e) {
    // out_of_range.406 (a number such as 1e400 that no double holds) and the like.
    std::string what = e.what();
    if (auto p = what.find("] "); p != std::string::npos) what = what.substr(p + 2);
    throw InputError(name, "malformed JSON: " + what);
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
  // As written: 18446744073709551615 is unsigned and must not be read back as −1.
  if (j_.is_number_unsigned() && j_.get<unsigned long>() > static_cast<unsigned long>(hi))
    fail(fmt::format("{} is out of range [{}, {}]", j_.dump(), lo, hi));
  const long x = j_.get<long>();
  if (x < lo || x > hi) fail(fmt::format("{} is out of range [{}, {}]", j_.dump(), lo, hi));
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

Mat3d checked_rotation(const Mat3d& R, const JsonValue& where, Warnings* warnings) {
  const double orth = (R * R.transpose() - Mat3d::Identity()).norm(), det = R.determinant();
  if (!(orth <= kRotationTolerance) || !(det > 0))
    where.fail(fmt::format("not a rotation (|R Rᵀ − I| = {:.2g}, det = {:.6g}; at most {:g} is accepted, and det > 0)",
                           orth, det, kRotationTolerance));
  if (orth > 1e-6 && warnings)
    warnings->add(where.where(),
                  fmt::format("a rotation only to |R Rᵀ − I| = {:.2g}: the nearest rotation is used", orth));
  return nearest_rotation(R);
}

}  // namespace insitu
