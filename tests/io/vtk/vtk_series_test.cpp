// The .pvd series: cadence, step file names, an index that always matches
// the files on disk.
#include "io/vtk/vtk_series.hpp"

#include <doctest/doctest.h>
#include <vtkXMLDataElement.h>
#include <vtkXMLDataParser.h>

#include <cstdlib>
#include <set>

#include "demo_snapshot.hpp"
#include "io/atomic_file.hpp"
#include "vtk_test_support.hpp"

namespace xshell::test {
namespace {

struct PvdDataSet {
  double timestep;
  int part;
  std::string name;
  std::string file;
};

// Parses `path` as XML (VTK's parser) and returns its DataSet entries,
// requiring the structure ParaView expects.
std::vector<PvdDataSet> read_pvd(const std::filesystem::path& path) {
  vtkNew<vtkXMLDataParser> parser;
  parser->SetFileName(path.string().c_str());
  REQUIRE(parser->Parse() == 1);
  vtkXMLDataElement* root = parser->GetRootElement();
  REQUIRE(root);
  REQUIRE(std::string(root->GetName()) == "VTKFile");
  REQUIRE(std::string(root->GetAttribute("type")) == "Collection");
  REQUIRE(root->GetNumberOfNestedElements() == 1);
  vtkXMLDataElement* collection = root->GetNestedElement(0);
  REQUIRE(std::string(collection->GetName()) == "Collection");
  std::vector<PvdDataSet> sets;
  for (int i = 0; i < collection->GetNumberOfNestedElements(); ++i) {
    vtkXMLDataElement* e = collection->GetNestedElement(i);
    REQUIRE(std::string(e->GetName()) == "DataSet");
    REQUIRE(e->GetAttribute("timestep"));
    REQUIRE(e->GetAttribute("part"));
    REQUIRE(e->GetAttribute("name"));
    REQUIRE(e->GetAttribute("file"));
    sets.push_back({std::strtod(e->GetAttribute("timestep"), nullptr),
                    std::atoi(e->GetAttribute("part")), e->GetAttribute("name"),
                    e->GetAttribute("file")});
  }
  return sets;
}

bool has_temporary_file(const std::filesystem::path& directory) {
  for (const std::string& name : file_names(directory))
    if (is_temporary_file_name(name)) return true;
  return false;
}

}  // namespace

TEST_CASE("series: every=2 plus forced first and final writes") {
  ScratchDirectory dir("series");
  const auto out = dir.path() / "run";  // created by the series
  std::vector<double> written_times;
  {
    VtkSeries series(out, {2, VtkFormat::Binary, true, {}});
    CHECK(read_pvd(series.pvd_path()).empty());  // valid before any step
    int checks = 0;
    // Calls 0 (forced), 1..6, then 7 (forced): writes at 0, 2, 4, 6, 7.
    const std::vector<bool> expect_write = {true, false, true, false, true, false, true, true};
    for (int call = 0; call < 8; ++call) {
      const double time = 0.1 * call;
      const bool force = (call == 0 || call == 7);
      const bool wrote = series.write(demo_snapshot(time, call), force);
      XSHELL_COUNTED_CHECK(checks, wrote == expect_write[static_cast<size_t>(call)]);
      if (wrote) written_times.push_back(time);
      // The index is valid after every call and lists every complete step.
      XSHELL_COUNTED_CHECK(checks, read_pvd(series.pvd_path()).size() == 4 * written_times.size());
    }
    CHECK(checks == 16);
    CHECK(series.steps_written() == 5);
  }  // destructor closes

  const auto sets = read_pvd(out / "series.pvd");
  REQUIRE(sets.size() == 4 * 5);
  const char* names[] = {"rods", "frames", "joints", "solids"};
  std::set<std::string> indexed;
  int checks = 0;
  for (size_t i = 0; i < sets.size(); ++i) {
    const int step = static_cast<int>(i / 4), part = static_cast<int>(i % 4);
    char expected_file[64];
    std::snprintf(expected_file, sizeof expected_file, "%s_%06d.vtp", names[part], step);
    XSHELL_COUNTED_CHECK(checks, sets[i].file == expected_file);
    XSHELL_COUNTED_CHECK(checks, sets[i].part == part);
    XSHELL_COUNTED_CHECK(checks, sets[i].name == names[part]);
    XSHELL_COUNTED_CHECK(checks, sets[i].timestep == written_times[static_cast<size_t>(step)]);
    indexed.insert(sets[i].file);
  }
  CHECK(checks == 4 * 20);

  // Exactly the indexed files and the index itself exist: no leftovers, no
  // temporaries.
  std::set<std::string> expected = indexed;
  expected.insert("series.pvd");
  CHECK(file_names(out) == expected);
  CHECK_FALSE(has_temporary_file(out));
  // And each is a readable poly data file.
  for (const std::string& file : indexed) CHECK(read_polydata(out / file)->GetNumberOfPoints() > 0);
}

TEST_CASE("series: without solids, three files per step, and every=1 writes every call") {
  ScratchDirectory dir("series_nosolids");
  VtkSeries series(dir.path(), {1, VtkFormat::Ascii, false, {}});
  int checks = 0;
  for (int call = 0; call < 3; ++call)
    XSHELL_COUNTED_CHECK(checks, series.write(demo_snapshot(call)));
  series.close();
  const auto sets = read_pvd(series.pvd_path());
  REQUIRE(sets.size() == 3 * 3);
  for (const PvdDataSet& set : sets) XSHELL_COUNTED_CHECK(checks, set.part != 3);
  CHECK(file_names(dir.path()).size() == 3 * 3 + 1);
  CHECK(file_head(dir.path() / "rods_000002.vtp").find("format=\"ascii\"") != std::string::npos);
  CHECK(checks == 3 + 9);
}

TEST_CASE("series: misuse is rejected") {
  ScratchDirectory dir("series_misuse");
  CHECK_THROWS_AS(VtkSeries(dir.path(), {0, VtkFormat::Binary, true, {}}), std::invalid_argument);
  VtkSeries series(dir.path());
  series.close();
  series.close();  // idempotent
  CHECK_THROWS_AS(series.write(demo_snapshot(), true), std::logic_error);
  CHECK(read_pvd(series.pvd_path()).empty());
}

TEST_CASE("series: at max_steps every other step goes and the cadence halves") {
  ScratchDirectory dir("series-thin");
  SeriesOptions options;
  options.max_steps = 4;
  options.solids = false;
  VtkSeries series(dir.path(), options);
  // Calls 0..19: before, 20 steps (60 files) were kept.
  std::vector<double> kept_times;
  for (int call = 0; call < 20; ++call) series.write(demo_snapshot(0.1 * call, call), call == 0);
  series.write(demo_snapshot(2.0, 20), true);  // the final state
  CHECK(series.thinnings() >= 2);
  CHECK(series.every() == (1 << series.thinnings()));
  CHECK(series.steps_kept() < 4);
  series.close();
  const auto sets = read_pvd(series.pvd_path());
  REQUIRE(sets.size() == 3 * static_cast<size_t>(series.steps_kept()));
  // The first and the final state stay; every entry's file exists, and no
  // step file is left that the index does not list.
  CHECK(sets.front().timestep == 0.0);
  CHECK(sets.back().timestep == 2.0);
  std::set<std::string> indexed;
  for (const auto& set : sets) {
    CHECK(std::filesystem::exists(dir.path() / set.file));
    indexed.insert(set.file);
  }
  int step_files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir.path()))
    if (entry.path().extension() == ".vtp") {
      ++step_files;
      CHECK(indexed.count(entry.path().filename().string()) == 1);
    }
  CHECK(step_files == static_cast<int>(sets.size()));
}

}  // namespace xshell::test
