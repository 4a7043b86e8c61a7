// Images: reading, writing, EXIF, limits (core/image.h).
#include <gtest/gtest.h>

#include <cmath>

#include "core/colour.h"
#include "core/error.h"
#include "core/image.h"
#include "test_util.h"

namespace insitu {
namespace {

TEST(Image, SanitizeClampsAndCounts) {
  Image img(2, 1, 3);
  img.data = {1.0f, -2.0f, std::nanf(""), INFINITY, 1e-6f, 1e5f};
  EXPECT_EQ(sanitize(img), 3u);
  EXPECT_EQ(img.data, (std::vector<float>{1.0f, 0.0f, 0.0f, 0.0f, 1e-6f, 1e5f}));
}

TEST(Image, ExrKeepsHighDynamicRange) {
  test::TempDir dir;
  Image img(2, 1, 3);
  img.data = {1e-6f, 1.0f, 1e5f, 0.5f, 2.0f, 3.0f};
  write_image(dir.file("x.exr"), img);  // stored as 32-bit float (half would overflow at 65504)
  const ImageFile f = read_image_file(dir.file("x.exr"));
  EXPECT_FALSE(f.display_referred);
  for (std::size_t i = 0; i < img.data.size(); ++i) EXPECT_EQ(f.stored.data[i], img.data[i]);
}

TEST(Image, ErrorsNameTheFile) {
  test::TempDir dir;
  const std::string junk = dir.write("junk.png", "this is not a png");
  try {
    read_image_file(junk);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.where(), junk);
  }
  try {
    read_image_file(dir.file("absent.jpg"));
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.where(), dir.file("absent.jpg"));
    EXPECT_EQ(e.message(), "file not found");
  }
}

TEST(Image, FailedWriteLeavesNothing) {
  test::TempDir dir;
  // A folder where the file should go: rename fails, and the temporary file is removed.
  std::filesystem::create_directories(dir.file("taken.png"));
  std::filesystem::create_directories(dir.file("taken.png/inner"));
  EXPECT_THROW(write_image(dir.file("taken.png"), Image(2, 2, 3, 0.5f)), InputError);
  int files = 0;
  for (const auto& e : std::filesystem::directory_iterator(dir.path())) files += e.is_regular_file();
  EXPECT_EQ(files, 0);
}

}  // namespace
}  // namespace insitu
