// The statements of an OBJ or MTL file as text, for the validating passes that run before
// tinyobjloader reads a file (render/mesh.cpp, render/obj_materials.cpp): every error names the
// file and the line.
#pragma once
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fmt/format.h>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "core/error.h"

namespace insitu::obj_text {

inline std::vector<std::string> split_ws(const std::string& s) {
  std::istringstream is(s);
  std::vector<std::string> out;
  std::string tok;
  while (is >> tok) out.push_back(tok);
  return out;
}

[[noreturn]] inline void fail(const std::string& path, int line, const std::string& what) {
  throw InputError(fmt::format("{}:{}", path, line), what);
}

// Tokens 1 … max_count must be finite numbers (|x| ≤ 1e30), and there must be at least min_count.
inline void check_numbers(const std::string& path, int line, const std::vector<std::string>& tok, std::size_t min_count,
                          std::size_t max_count, const char* what) {
  if (tok.size() - 1 < min_count)
    fail(path, line, fmt::format("{} needs {} numbers, has {}", what, min_count, tok.size() - 1));
  for (std::size_t k = 1; k < tok.size() && k <= max_count; ++k) {
    const char* s = tok[k].c_str();
    char* end = nullptr;
    errno = 0;
    const double x = std::strtod(s, &end);
    if (end == s || *end != '\0') fail(path, line, fmt::format("{}: '{}' is not a number", what, tok[k]));
    if (!std::isfinite(x) || errno == ERANGE || std::abs(x) > 1e30)
      fail(path, line, fmt::format("{}: '{}' is not a finite number", what, tok[k]));
  }
}

// Calls f(line number, tokens) for each non-empty line, comments removed.
template <typename F>
void for_each_statement(std::ifstream& in, F&& f) {
  std::string line;
  for (int lineno = 1; std::getline(in, line); ++lineno) {
    if (const auto hash = line.find('#'); hash != std::string::npos) line.resize(hash);
    const auto tok = split_ws(line);
    if (!tok.empty()) f(lineno, tok);
  }
}

}  // namespace insitu::obj_text
