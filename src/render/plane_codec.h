// Planes of 32-bit words in one zstd frame (Collet, RFC 8878), each plane byte-shuffled: the
// first bytes of all its words, then the second bytes, and so on, as Blosc and HDF5's shuffle
// filter lay them out. A plane of floats that vary smoothly, or whose low significand bits are
// zero (render/pixel_blocks.h, round_block), then shows the compressor long runs where the words
// interleaved show none: a render's part compresses to about a quarter of its 100 bytes a block
// (docs/farm.md). What a checkpoint and a part store their pixels in (render/checkpoint.h).
//
// The reader trusts nothing of the frame: it must declare exactly the size its file's header
// implies (so an allocation is never sized by a stranger's frame), no more than a frame of its
// size can hold (32768 bytes a byte), its window is capped, and each plane is decoded into a
// buffer of that plane's size.
#pragma once
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace insitu {

class PlaneWriter {
 public:
  // A frame of exactly `content_bytes` (the planes' words × 4 plus the raw bytes added).
  explicit PlaneWriter(std::uint64_t content_bytes);
  ~PlaneWriter();
  void words(const std::vector<std::uint32_t>& plane);  // shuffled
  void bytes(const std::uint8_t* data, std::size_t n);  // as they are
  std::string finish();                                 // the frame; throws if the sizes differ

 private:
  void feed(const void* data, std::size_t n);
  struct Stream;
  std::unique_ptr<Stream> z_;
  std::string frame_;
};

class PlaneReader {
 public:
  // Throws InputError(path, ...) unless `frame` declares `content_bytes`.
  PlaneReader(const char* frame, std::size_t frame_bytes, std::uint64_t content_bytes, std::string path);
  ~PlaneReader();
  std::vector<std::uint32_t> words(std::size_t n);  // the next plane of n words
  void bytes(std::uint8_t* out, std::size_t n);
  void finish();  // throws unless the frame ended, with every byte of it read

 private:
  void take(void* out, std::size_t n);
  struct Stream;
  std::unique_ptr<Stream> z_;
  std::string path_;
};

}  // namespace insitu
