// Whole text files, written atomically (temporary name in the same folder, then rename).
#pragma once
#include <string>

namespace insitu {

void write_text_file(const std::string& path, const std::string& text);
// The same for raw bytes (binary mode; on POSIX the two are one).
void write_binary_file(const std::string& path, const std::string& bytes);

}  // namespace insitu
