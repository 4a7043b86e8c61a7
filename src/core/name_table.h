// Enumerations by their scene-file and command-line names: one table per enumeration (irradiance
// modes, tone maps, composite modes), so that the parser, the CLI's choices and the messages read
// the same list.
#pragma once
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace insitu {

template <class E>
struct Named {
  E value;
  const char* name;
};

template <class E, std::size_t N>
const char* name_of(const Named<E> (&table)[N], E value) {
  for (const auto& row : table)
    if (row.value == value) return row.name;
  return table[0].name;  // unreachable for a complete table
}

template <class E, std::size_t N>
std::optional<E> parse_name(const Named<E> (&table)[N], const std::string& name) {
  for (const auto& row : table)
    if (name == row.name) return row.value;
  return std::nullopt;
}

template <class E, std::size_t N>
std::vector<std::string> names_of(const Named<E> (&table)[N]) {
  std::vector<std::string> names;
  for (const auto& row : table) names.emplace_back(row.name);
  return names;
}

// "\"a\", \"b\" or \"c\"", for messages.
inline std::string quoted_choices(const std::vector<std::string>& names) {
  std::string s;
  for (std::size_t i = 0; i < names.size(); ++i)
    s += (i == 0 ? "" : i + 1 == names.size() ? " or " : ", ") + ("\"" + names[i] + "\"");
  return s;
}

}  // namespace insitu
