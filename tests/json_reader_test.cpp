#include <gtest/gtest.h>

#include <fstream>

#include "core/json_reader.h"
#include "test_util.h"

namespace insitu {
namespace {

// Expects read_json_file(path) to fail with a place equal to `where` and a message containing `what`.
void expect_refused(const std::string& path, const std::string& where, const std::string& what) {
  try {
    read_json_file(path);
    ADD_FAILURE() << "accepted " << path;
  } catch (const InputError& e) {
    EXPECT_EQ(e.where(), where) << e.what();
    EXPECT_NE(e.message().find(what), std::string::npos) << e.what();
  }
}

TEST(JsonReader, NumbersNoDoubleHoldsAreInputErrors) {
  test::TempDir dir;
  expect_refused(dir.write("a.json", R"({"spp": 1e400})"), dir.file("a.json"), "1e400");
  expect_refused(dir.write("b.json", R"([1, -1e999])"), dir.file("b.json"), "1e999");
}

TEST(JsonReader, DuplicateKeysNameTheirPath) {
  test::TempDir dir;
  const std::string p = dir.write("s.json", R"({"render": {"spp": 4, "spp": 8}})");
  expect_refused(p, p + ":$.render.spp", "duplicate key");
  const std::string q = dir.write("t.json", R"({"objects": [{"mesh": "a"}, {"mesh": "b", "mesh": "c"}]})");
  expect_refused(q, q + ":$.objects[1].mesh", "duplicate key");
  // The same key in two objects is fine.
  EXPECT_NO_THROW(read_json_file(dir.write("u.json", R"([{"a": 1}, {"a": 2}, {"b": {"a": 3}}])")));
}

TEST(JsonReader, NulByteDirectoryAndHugeFilesAreRefused) {
  test::TempDir dir;
  {
    std::ofstream out(dir.file("n.json"), std::ios::binary);
    out << "{\"a\": 1}\n  " << '\0' << "garbage";
  }
  expect_refused(dir.file("n.json"), dir.file("n.json") + ":2:3", "NUL byte");
  expect_refused(dir.path().string(), dir.path().string(), "is a directory");
  {
    std::ofstream out(dir.file("big.json"), std::ios::binary);
    out.seekp(std::streamoff(kMaxJsonBytes));  // a sparse file just over the limit
    out << ' ';
  }
  expect_refused(dir.file("big.json"), dir.file("big.json"), "too large");
}

}  // namespace
}  // namespace insitu
