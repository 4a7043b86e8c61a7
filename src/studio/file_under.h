// Which file a request may read: only a regular file inside the scene's folder. A relative path
// with a ".." component, an absolute path, a backslash or a NUL is refused before the file system
// is asked; what remains is resolved with every symlink followed
// (std::filesystem::canonical), and refused unless it still lies under the folder. So "../x",
// "a/../../x", "%2e%2e/x" (decoded by the server first) and a symlink pointing out all fail alike.
#pragma once
#include <filesystem>
#include <optional>
#include <string>

namespace insitu {

// The file `relative` names under `folder`, canonical; nullopt when it is not allowed or not a
// regular file.
std::optional<std::filesystem::path> file_under(const std::filesystem::path& folder, const std::string& relative);

}  // namespace insitu
