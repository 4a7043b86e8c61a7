// insitu compare A B [--mask M] -o diff.png
//
// A and B (8-bit images are sRGB-decoded, float images are linear) must have one size; B is the
// reference. Prints RMSE, relative RMSE, SSIM and maximum error over the whole image and inside the
// mask, and writes A | B | the luminance-error heatmap with its colour bar.
#include <cstdio>
#include <fmt/format.h>
#include <memory>

#include "commands.h"
#include "output/image_compare.h"
#include "core/output_paths.h"

namespace insitu {
namespace {

struct CompareArgs {
  std::string a, b, mask, out;
};

int run_compare(const CompareArgs& args) {
  check_outputs({{args.a, "image A"}, {args.b, "image B"}, {args.mask, "the mask"}}, {{args.out, "-o"}});
  const ImageFile fa = read_image_file(args.a), fb = read_image_file(args.b);
  const Image a = linearize(fa), b = linearize(fb);
  if (a.width != b.width || a.height != b.height)
    throw InputError(args.b, fmt::format("{}x{}, but {} is {}x{}", b.width, b.height, args.a, a.width, a.height));
  Image mask;
  if (!args.mask.empty()) {
    mask = read_image_file(args.mask).stored;
    if (mask.width != a.width || mask.height != a.height)
      throw InputError(args.mask,
                       fmt::format("mask is {}x{}, the images {}x{}", mask.width, mask.height, a.width, a.height));
  }
  // A linear (scene-referred) image against a display-referred one: the latter is clipped at 1 and
  // quantized, so its highlights cannot match; the numbers still compare linear values.
  if (fa.display_referred != fb.display_referred) {
    const ImageFile& d = fa.display_referred ? fa : fb;
    const ImageFile& l = fa.display_referred ? fb : fa;
    std::fprintf(stderr,
                 "insitu: warning: %s is a display-referred %d-bit image (clipped at 1, sRGB-decoded) and %s is linear "
                 "(%s): values above 1 cannot agree; compare like with like (the EXR with an EXR)\n",
                 d.path.c_str(), d.bits, l.path.c_str(), l.format.c_str());
  }
  const CompareResult r = compare_images(a, b, args.mask.empty() ? nullptr : &mask);
  auto row = [](const char* name, const CompareNumbers& n) {
    std::printf("| %s | %ld | %.6g | %.6g | %.6f | %.6g |\n", name, n.pixels, n.rmse, n.relative_rmse, n.ssim,
                n.max_error);
  };
  std::printf("| region | pixels | RMSE | relative RMSE | SSIM | max error |\n|---|---|---|---|---|---|\n");
  row("image", r.whole);
  if (r.masked) row("mask", *r.masked);
  if (!args.out.empty()) {
    // Display-referred files are shown as stored, so the picture looks like the files.
    write_image(args.out, comparison_picture(a, b, r, fa.display_referred ? &fa.stored : nullptr,
                                             fb.display_referred ? &fb.stored : nullptr));
    std::printf("wrote %s\n", args.out.c_str());
  }
  return 0;
}

}  // namespace

Command add_compare_command(CLI::App& app) {
  auto a = std::make_shared<CompareArgs>();
  CLI::App* cmd = app.add_subcommand("compare", "error numbers and a difference heatmap of two renders");
  cmd->add_option("a", a->a, "the image to judge")->required();
  cmd->add_option("b", a->b, "the reference")->required();
  cmd->add_option("--mask", a->mask, "non-zero pixels: a region to report separately");
  cmd->add_option("-o,--output", a->out, "A | B | heatmap picture (PNG)");
  return [cmd, a] { return cmd->parsed() ? run_compare(*a) : -1; };
}

}  // namespace insitu
