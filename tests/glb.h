// A glTF document and its binary chunk as one .glb, and raw arrays appended to a binary chunk
// (tests and bench/gltf_bench.cpp).
#pragma once
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace insitu::test {

template <class T>
void append(std::string& bytes, const std::vector<T>& values) {
  bytes.append(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(T));
}

// GLB: a 12-byte header, a JSON chunk and a BIN chunk, each padded to 4 bytes.
inline std::string glb(const nlohmann::json& doc, std::string bin) {
  std::string text = doc.dump();
  while (text.size() % 4) text += ' ';
  while (bin.size() % 4) bin += '\0';
  std::string out = "glTF";
  auto u32 = [&](std::uint32_t v) { out.append(reinterpret_cast<const char*>(&v), 4); };
  u32(2), u32(std::uint32_t(12 + 8 + text.size() + 8 + bin.size()));
  u32(std::uint32_t(text.size())), u32(0x4E4F534A), out += text;
  u32(std::uint32_t(bin.size())), u32(0x004E4942), out += bin;
  return out;
}

}  // namespace insitu::test
