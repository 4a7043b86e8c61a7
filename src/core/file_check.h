// Whether a path names an existing file, without the throwing overloads of std::filesystem: a
// name the system refuses (too long, a file where a folder should be) must be a one-line
// InputError naming it, like a missing file — not a filesystem_error (the OBJ fuzzer found a
// texture name of 300 bytes).
#pragma once
#include <string>

namespace insitu {

// Throws InputError(path, "file not found") or InputError(path, "cannot access: <why>").
void require_existing(const std::string& path);
// False on any error.
bool exists_quietly(const std::string& path);
// A folder (false on any error).
bool is_directory_quietly(const std::string& path);
// Flushes a written file to the disk (fsync): "" or why not. A full disk or a quota may report a
// write's failure only here; a file is synced before it takes its final name.
std::string sync_to_disk(const std::string& path);

}  // namespace insitu
