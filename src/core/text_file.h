// Whole text files, written atomically (temporary name in the same folder, then rename).
#pragma once
#include <string>

namespace insitu {

class StagedWrites;  // core/staged_writes.h

// With `stage`, the flushed file waits under its temporary name for stage->commit().
void write_text_file(const std::string& path, const std::string& text, StagedWrites* stage = nullptr);
// The same for raw bytes (binary mode; on POSIX the two are one).
void write_binary_file(const std::string& path, const std::string& bytes, StagedWrites* stage = nullptr);

}  // namespace insitu
