// Fuzz target: the control-point readers. The first byte picks the format: JSON, CSV or a View
// Correlation file; then the points are calibrated, as the CLI would.
#include "calib/calibration.h"
#include "calib/control_points.h"
#include "fuzz_common.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace insitu;
  if (size == 0) return 0;
  static const char* names[3] = {"p.json", "p.csv", "p.vc"};
  return fuzz::run([&] {
    const auto points =
        read_control_points(fuzz::write_input(names[data[0] % 3], data + 1, size - 1), data[0] & 4, 480);
    if (points.size() <= 40) calibrate(points, 640, 480);
  });
}
