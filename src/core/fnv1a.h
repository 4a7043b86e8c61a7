// FNV-1a, 64 bits (Fowler, Noll, Vo): a hash of bytes, to tell whether two inputs are the same
// (a checkpoint's scene, a batch entry's inputs); not for hash tables or security.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

namespace insitu {

// h = (h XOR byte) × 1099511628211 from 14695981039346656037.
class Fnv1a {
 public:
  void bytes(const void* data, std::size_t n) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < n; ++i) h_ = (h_ ^ p[i]) * 1099511628211ull;
  }
  template <class T>
  void value(const T& v) {
    bytes(&v, sizeof(T));
  }
  void text(const std::string& s) { value(s.size()), bytes(s.data(), s.size()); }
  template <class T>
  void array(const std::vector<T>& v) {
    value(v.size()), bytes(v.data(), v.size() * sizeof(T));
  }
  std::uint64_t digest() const { return h_; }

 private:
  std::uint64_t h_ = 14695981039346656037ull;
};

}  // namespace insitu
