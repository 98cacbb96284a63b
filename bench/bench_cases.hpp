// The cases xshell_bench measures: the real linkage graphs, the bundled
// samples and generated grids, and the statics problem of each.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "io/problem_setup.hpp"
#include "linkage/graph.hpp"
#include "linkage/statics_problem.hpp"

namespace xshell::bench {

struct BenchCase {
  std::string name;
  std::string kind;  // "graph", "grid" or "sample"
  LineGraph graph;
  int subdivisions = 8;
  bool gravity = false;
  std::shared_ptr<const ProblemSetup>
      setup;  // a sample's, from its configuration; else the fields above
};

// Which cases to measure (xshell_bench's options of the same names).
struct CaseSelection {
  std::string graphs = "designs";  // "designs", "all", "none" or names (prefixes), comma-separated
  std::string subdivisions = "8,10";   // for the graphs, comma-separated
  std::string grids = "4,8,14,25,44";  // crossings per side, comma-separated
  std::string samples = "all";         // "all" or "none"
  std::string data;                    // folder of the real linkage graphs
  std::string source_dir;              // the repository (samples/)
};

// The chosen graphs at each subdivision count (said on stdout and left out
// when the data folder is absent), then the samples, then the grids
// without and with gravity.
std::vector<BenchCase> collect_cases(const CaseSelection& selection);

// The statics problem of a relaxation of c from its flat input: a sample's
// own setup, or straight laths in millimetres (E = 20000, nu = 0.3,
// rectangle 10 x 7, the default pin; density 1e-9 t/mm^3 and gravity when
// c.gravity).
LinkageProblem make_problem(const BenchCase& c);

}  // namespace xshell::bench
