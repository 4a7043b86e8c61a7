// Errors and warnings (DESIGN.md "Errors").
//
// Bad input is an InputError that says where: `file:line` for OBJ/MTL/text, `file:$.json.path`
// for JSON, the image's name for images. Context is prepended as the error propagates, so the
// CLI can print `insitu: error: scene.json:$.objects[2].mesh: sofa.obj:31: face index 0 ...`.
#pragma once
#include <stdexcept>
#include <string>
#include <vector>

namespace insitu {

class InputError : public std::runtime_error {
 public:
  InputError(std::string where, std::string what)
      : std::runtime_error(where.empty() ? what : where + ": " + what),
        where_(std::move(where)),
        what_(std::move(what)) {}
  const std::string& where() const { return where_; }
  const std::string& message() const { return what_; }
  // A copy with `outer` prepended to the place: "outer: where: what". A place that already begins
  // with `outer` (an error named at the same place twice on its way out) keeps it once: not
  // "sh.json:$.shots.+x: sh.json:$.shots.+x: ...".
  InputError with_context(const std::string& outer) const {
    if (outer.empty() || where_ == outer || where_.rfind(outer + ":", 0) == 0) return *this;
    return InputError(where_.empty() ? outer : outer + ": " + where_, what_);
  }

 private:
  std::string where_;
  std::string what_;
};

// Non-fatal findings (counted, never silent). Collected by the caller and printed by the CLI.
struct Warnings {
  std::vector<std::string> items;
  void add(const std::string& where, const std::string& what) {
    items.push_back(where.empty() ? what : where + ": " + what);
  }
};

}  // namespace insitu
