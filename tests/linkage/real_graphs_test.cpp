#include <doctest/doctest.h>

#include <filesystem>
#include <sstream>

#include "io/obj_reader.hpp"
#include "linkage/rod_linkage.hpp"
#include "skip.hpp"

namespace xshell::test {

// Builds a linkage from every graph of the reference implementation (when
// ../shared/data/elasticrods is present) and reports its size.
TEST_CASE("Every real linkage graph builds with joints opening in (0 pi) and zero input energy" *
          doctest::test_suite("validation")) {
  const std::filesystem::path dir = XSHELL_SHARED_DATA_DIR;
  if (!std::filesystem::is_directory(dir)) XSHELL_SKIP(dir.string() + " is absent");
  int built = 0;
  std::vector<std::filesystem::path> files;
  for (const auto& entry : std::filesystem::directory_iterator(dir))
    if (entry.path().extension() == ".obj") files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  for (const auto& path : files) {
    CAPTURE(path.filename().string());
    const LineGraph graph = read_obj(path.string());
    LinkageOptions options;
    options.subdivisions = 8;
    options.material.young_modulus = 20000.0;
    options.material.section = {SectionShape::Rectangle, 10.0, 7.0};
    const RodLinkage linkage(graph, options);
    int collinear = 0;
    for (int j = 0; j < linkage.num_joints(); ++j) {
      CHECK(linkage.joint(j).opening_angle() > 0.0);
      CHECK(linkage.joint(j).opening_angle() < M_PI);
      collinear += linkage.topology().joints[j].collinear;
    }
    const double scale = linkage.segment(0).stiffness().stretching;
    CHECK(linkage.energy().total() <= 1e-16 * scale * graph.edges.size());
    MESSAGE(path.filename().string()
            << ": " << linkage.num_joints() << " joints, " << linkage.num_segments()
            << " segments, " << linkage.topology().rods.size() << " rods, " << linkage.num_dofs()
            << " unknowns, " << collinear << " near-collinear joints");
    ++built;
  }
  CHECK(built == static_cast<int>(files.size()));
  CHECK(built == 10);
}

}  // namespace xshell::test
