#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>

#include "io/input_error.hpp"
#include "io/obj_reader.hpp"
#include "scratch_directory.hpp"

namespace xshell::test::obj_surface_test {
namespace {

std::string rejection(const std::string& text) {
  try {
    parse_obj_surface_text(text, "s.obj");
  } catch (const InputError& e) {
    return e.what();
  }
  FAIL_CHECK("accepted: " << text);
  return "";
}

}  // namespace

TEST_CASE("A surface file's polygons become fans of triangles") {
  const ObjSurface s = parse_obj_surface_text(
      "# a square and a pentagon\r\no square\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
      "vn 0 0 1\nf 1//1 2//1 3//1 4//1\nv 2 0 0\nv 3 0 0\nv 3 1 0\nv 2.5 2 0\nv 2 1 0\n"
      "f -5 -4 -3 -2 -1\n",
      "s.obj");
  REQUIRE(s.vertices.size() == 9);
  REQUIRE(s.triangles.size() == 2 + 3);
  CHECK(s.triangles[0] == std::array<int, 3>{0, 1, 2});
  CHECK(s.triangles[1] == std::array<int, 3>{0, 2, 3});
  CHECK(s.triangles[2] == std::array<int, 3>{4, 5, 6});
  CHECK(s.triangles[4] == std::array<int, 3>{4, 7, 8});
  CHECK(s.vertices[7] == Eigen::Vector3d(2.5, 2, 0));
}

TEST_CASE("A surface file that is not a triangle mesh is refused with its line") {
  CHECK(rejection("v 0 0 0\nv 1 0 0\nv 0 1 0\n") ==
        "s.obj: no faces: a surface needs at least one 'f' line");
  CHECK(rejection("v 0 0 0\nv 1 0 0\nf 1 2\n") ==
        "s.obj:3: 'f' needs at least three vertex indices ('f i j k')");
  CHECK(rejection("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n") ==
        "s.obj:4: vertex index 4 is out of range: the file defines 3 vertices");
  CHECK(rejection("v 0 0 0\nv 1 0 0\nv 0 1 0\nl 1 2\n")
            .find("s.obj:4: unknown statement 'l'; a surface file has 'v' and 'f' lines") == 0);
  CHECK(rejection("v 0 0 x\n") == "s.obj:1: coordinate 'x' is not a number");
}

TEST_CASE("A surface file is read from disk, and a missing one named") {
  const ScratchDirectory dir("obj-surface");
  const std::filesystem::path path = dir / "surface.obj";
  std::ofstream(path) << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
  CHECK(read_obj_surface(path.string()).triangles.size() == 1);
  std::filesystem::remove(path);
  CHECK_THROWS_WITH_AS(read_obj_surface(path.string()),
                       doctest::Contains("cannot open surface file"), InputError);
}

TEST_CASE("A linkage file still refuses faces") {
  std::string message;
  try {
    parse_obj_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "t.obj");
  } catch (const InputError& e) {
    message = e.what();
  }
  CHECK(message.find("t.obj:4: faces ('f') are not allowed") == 0);
}

}  // namespace xshell::test::obj_surface_test
