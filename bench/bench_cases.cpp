#include "bench_cases.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>
#include <utility>

#include "io/config.hpp"
#include "io/input_error.hpp"
#include "io/obj_reader.hpp"
#include "linkage/bounding_box.hpp"

namespace xshell::bench {

namespace {

namespace fs = std::filesystem;

const std::vector<std::string> kDesigns = {"manta_ray", "darth_vader", "scary_face", "hourglass",
                                           "large"};

// The non-empty items of a comma-separated list.
std::vector<std::string> split_list(const std::string& text) {
  std::vector<std::string> out;
  std::stringstream in(text);
  for (std::string item; std::getline(in, item, ',');)
    if (!item.empty()) out.push_back(item);
  return out;
}

std::vector<int> parse_ints(const std::string& text) {
  std::vector<int> out;
  for (const std::string& item : split_list(text)) out.push_back(std::stoi(item));
  return out;
}

bool starts_with(const std::string& text, const std::string& prefix) {
  return text.rfind(prefix, 0) == 0;
}

// A regular grid of n x n crossings of straight rods (spacing 100 mm), each
// rod running half a spacing past its last crossing to a free end, with the
// crossings moved in the plane by up to 8 mm so that the rods are kinked at
// the joints: relaxing it from flat with straight rest shapes has work to do.
LineGraph wavy_grid(int n) {
  const double spacing = 100.0, amplitude = 8.0;
  LineGraph g;
  auto joint = [&](int i, int j) { return i * n + j; };
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const double x = spacing * j, y = spacing * i;
      g.vertices.emplace_back(x + amplitude * std::sin(1.3 * i + 0.7 * j),
                              y + amplitude * std::cos(0.9 * i - 1.1 * j), 0.0);
    }
  auto free_end = [&](double x, double y) {
    g.vertices.emplace_back(x, y, 0.0);
    return static_cast<int>(g.vertices.size()) - 1;
  };
  for (int i = 0; i < n; ++i) {  // rods along x, then along y
    g.edges.push_back({free_end(-0.5 * spacing, spacing * i), joint(i, 0)});
    for (int j = 0; j + 1 < n; ++j) g.edges.push_back({joint(i, j), joint(i, j + 1)});
    g.edges.push_back({joint(i, n - 1), free_end(spacing * (n - 0.5), spacing * i)});
  }
  for (int j = 0; j < n; ++j) {
    g.edges.push_back({free_end(spacing * j, -0.5 * spacing), joint(0, j)});
    for (int i = 0; i + 1 < n; ++i) g.edges.push_back({joint(i, j), joint(i + 1, j)});
    g.edges.push_back({joint(n - 1, j), free_end(spacing * j, spacing * (n - 0.5))});
  }
  return g;
}

// The graph files of the data folder that the selection names, in the
// order of the names (all of them for "all").
std::vector<fs::path> chosen_graph_files(const CaseSelection& selection) {
  std::vector<std::string> wanted;
  if (selection.graphs == "designs") wanted = kDesigns;
  if (selection.graphs != "designs" && selection.graphs != "all")
    wanted = split_list(selection.graphs);
  std::vector<std::pair<size_t, fs::path>> chosen;
  for (const auto& entry : fs::directory_iterator(selection.data)) {
    if (entry.path().extension() != ".obj") continue;
    const std::string stem = entry.path().stem().string();
    if (selection.graphs == "all") chosen.emplace_back(0, entry.path());
    for (size_t k = 0; k < wanted.size(); ++k)
      if (starts_with(stem, wanted[k])) chosen.emplace_back(k, entry.path());
  }
  std::sort(chosen.begin(), chosen.end());
  std::vector<fs::path> files;
  for (auto& [order, path] : chosen) files.push_back(std::move(path));
  return files;
}

// A graph case. The designs are relaxed as make_problem says; the small
// graphs are of order 1, not millimetres: they take the samples' laths
// (metres), their input shape as rest shape, gravity and the four corners
// pinned, as the validation runs use them.
BenchCase graph_case(const fs::path& path, int subdivisions, const Config& sample_config) {
  BenchCase c;
  c.name = path.stem().string().substr(0, 24);
  c.kind = "graph";
  c.graph = read_obj(path.string());
  c.subdivisions = subdivisions;
  const bool design = std::any_of(kDesigns.begin(), kDesigns.end(), [&](const std::string& d) {
    return starts_with(path.stem().string(), d);
  });
  if (design) return c;
  Config config = sample_config;
  config.subdivisions = subdivisions;
  config.rest_shape = RestShape::Input;
  config.supports.clear();
  for (int v : corner_vertices(c.graph)) config.supports.push_back({v, {Fixed::Position}});
  config.loads.forces.clear();
  c.setup = std::make_shared<const ProblemSetup>(make_problem_setup(config, c.graph));
  c.gravity = c.setup->statics.gravity.squaredNorm() > 0.0;
  return c;
}

// Each sample (samples/*.obj that is a linkage) with the material, supports
// and loads of grid_gravity.json.
std::vector<BenchCase> sample_cases(const fs::path& folder, const Config& config) {
  std::vector<fs::path> files;
  for (const auto& entry : fs::directory_iterator(folder))
    if (entry.path().extension() == ".obj") files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  std::vector<BenchCase> cases;
  for (const auto& path : files) {
    BenchCase c;
    c.name = "samples/" + path.stem().string();
    c.kind = "sample";
    LineGraph graph;
    try {
      graph = read_obj(path.string());
    } catch (const InputError& e) {  // a surface (a design's target), not a linkage
      std::printf("skipped %s: %s\n", c.name.c_str(), e.what());
      continue;
    }
    c.setup = std::make_shared<const ProblemSetup>(make_problem_setup(config, graph));
    c.subdivisions = c.setup->options.subdivisions;
    c.gravity = c.setup->statics.gravity.squaredNorm() > 0.0;
    cases.push_back(c);
  }
  return cases;
}

}  // namespace

std::vector<BenchCase> collect_cases(const CaseSelection& selection) {
  std::vector<BenchCase> cases;
  // The bundled sample's configuration: material, supports, loads and
  // subdivisions of the samples and of the small shared graphs.
  const fs::path samples = fs::path(selection.source_dir) / "samples";
  const Config sample_config = read_config((samples / "grid_gravity.json").string());
  if (selection.graphs != "none") {
    if (!fs::is_directory(selection.data)) {
      std::printf("graphs skipped: %s is absent\n", selection.data.c_str());
    } else {
      const std::vector<fs::path> files = chosen_graph_files(selection);
      for (int n : parse_ints(selection.subdivisions))
        for (const fs::path& path : files) cases.push_back(graph_case(path, n, sample_config));
    }
  }
  if (selection.samples == "all") {
    std::vector<BenchCase> more = sample_cases(samples, sample_config);
    cases.insert(cases.end(), more.begin(), more.end());
  }
  for (int n : parse_ints(selection.grids))
    for (bool gravity : {false, true}) {
      BenchCase c;
      c.name = "grid" + std::to_string(n) + "x" + std::to_string(n);
      c.kind = "grid";
      c.graph = wavy_grid(n);
      c.subdivisions = 8;
      c.gravity = gravity;
      cases.push_back(c);
    }
  return cases;
}

LinkageProblem make_problem(const BenchCase& c) {
  if (c.setup)
    return LinkageProblem(RodLinkage(c.setup->graph, c.setup->options), c.setup->statics);
  LineGraph graph = c.graph;
  const Eigen::Vector3d origin = bounding_box(graph.vertices).centre();
  for (auto& v : graph.vertices) v -= origin;  // as the configuration reader does
  LinkageOptions options;
  options.subdivisions = c.subdivisions;
  options.rest_shape = RestShape::Straight;
  options.material.young_modulus = 20000.0;  // N/mm^2
  options.material.poisson_ratio = 0.3;
  options.material.density = c.gravity ? 1.0e-9 : 0.0;  // t/mm^3 (1000 kg/m^3)
  options.material.section = {SectionShape::Rectangle, 10.0, 7.0};
  StaticsSetup setup;
  if (c.gravity) setup.gravity = Eigen::Vector3d(0.0, 0.0, -9810.0);  // mm/s^2
  return LinkageProblem(RodLinkage(graph, options), setup);
}

}  // namespace xshell::bench
