// No command overwrites one of its own inputs (the user's photo is irreplaceable), and no two
// outputs of one command are one file. Paths are compared by filesystem identity, not by string:
// two existing paths are the same file when they name the same device and inode (through
// symlinks, "..", hard links); a path that does not exist yet is compared by its canonical form
// (symlinks and ".." of its existing folders resolved).
#pragma once
#include <string>
#include <vector>

namespace insitu {

struct NamedPath {
  std::string path;
  std::string role;  // for the message: "the photo", "shot +x", "--vc", "output.layers", ...
};

bool same_file(const std::string& a, const std::string& b);

// A path's extension in lower case, with its dot: ".png" for "A.PNG", "" for none.
std::string lower_extension(const std::string& path);

// Throws InputError naming the output, its role and the input (or output) it would replace.
// Then checks that each output can be written, before any work: not a directory, its folder
// created if need be, and a temporary file can be made in that folder (and is removed at once).
void check_outputs(const std::vector<NamedPath>& inputs, const std::vector<NamedPath>& outputs);

}  // namespace insitu
