// Fuzz target: the reader of checkpoints and of a split render's parts (render/checkpoint.h): the
// header's plan, the blocks of every pixel, adaptive sampling's stopped pixels. A file that is
// not a consistent state must be refused with an InputError, never read past its end or trusted
// to size an allocation. The input is a file's bytes without their checksum (parse_state_bytes):
// a fuzzer's input would almost never match one, and the parser behind it would go untested.
#include "fuzz_common.h"
#include "render/checkpoint.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace insitu;
  return fuzz::run([&] { parse_state_bytes(std::string(reinterpret_cast<const char*>(data), size), "x.checkpoint"); });
}
