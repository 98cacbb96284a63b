#include "design_outputs.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "design_targets.hpp"
#include "integrators/deployment/average_constraint.hpp"
#include "io/atomic_file.hpp"
#include "io/design_config.hpp"
#include "io/fabrication_file.hpp"
#include "io/vtk/linkage_snapshot.hpp"
#include "io/vtk/vtk_series.hpp"
#include "vtk_write_options.hpp"

namespace xshell {

namespace fs = std::filesystem;

namespace {

nlohmann::json null_if_nan(double x) { return std::isfinite(x) ? nlohmann::json(x) : nullptr; }

// {"max", "rms"} of the targeted vertices' distances to their targets.
nlohmann::json fit_json(const std::vector<double>& distances) {
  double max = 0.0, squares = 0.0;
  int n = 0;
  for (double d : distances)
    if (std::isfinite(d)) {
      max = std::max(max, d);
      squares += d * d;
      ++n;
    }
  return {{"max", max}, {"rms", n ? std::sqrt(squares / n) : 0.0}, {"targets", n}};
}

// The largest distance of the flat state's vertices from their mean plane z.
double flat_planarity(const LinkageProblem& flat) {
  const std::vector<Eigen::Vector3d> x = flat.vertex_positions();
  double mean = 0.0;
  for (const Eigen::Vector3d& p : x) mean += p.z() / x.size();
  double worst = 0.0;
  for (const Eigen::Vector3d& p : x) worst = std::max(worst, std::abs(p.z() - mean));
  return worst;
}

nlohmann::json state_json(const LinkageProblem& problem) {
  return {{"energy", problem.energy().total()},
          {"average_opening_angle", average_opening_angle(problem.linkage())}};
}

// The flat layout: the graph's vertices at the flat state, its edges.
std::string flat_layout_obj(const LinkageProblem& flat, const Eigen::Vector3d& origin) {
  std::ostringstream out;
  out.precision(17);
  out << "# xshell design: the optimized flat layout (vertices in the input's order)\n";
  for (const Eigen::Vector3d& p : flat.vertex_positions()) {
    const Eigen::Vector3d x = p + origin;
    out << "v " << x.x() << ' ' << x.y() << ' ' << x.z() << '\n';
  }
  for (const auto& e : flat.linkage().graph().edges)
    out << "l " << e[0] + 1 << ' ' << e[1] + 1 << '\n';
  return out.str();
}

void write_series(const DesignReport& report, const Config& config, const Eigen::Vector3d& origin) {
  SeriesOptions options;
  const WriteOptions encoding = vtk_write_options(config.output);
  options.format = encoding.format;
  options.compression = encoding.compression;
  options.solids = config.output.solids != Toggle::Off;
  VtkSeries series(config.output.directory, options);
  series.write(linkage_snapshot(report.flat.linkage(), origin, 0.0), true);
  const RodLinkage& deployed = report.objective.deployed().linkage();
  Snapshot snapshot = linkage_snapshot(deployed, origin, 1.0);
  const std::vector<double> d = target_distances(deployed, report.objective.targets());
  for (JointSnapshot& joint : snapshot.joints)
    if (std::isfinite(d[joint.vertex])) joint.target_distance = d[joint.vertex];
  series.write(snapshot, true);
  series.close();
}

}  // namespace

nlohmann::json history_record(const DesignIteration& it, const DesignScales& scales, int targets) {
  const DesignTerms t = unit_free_terms(it.terms, scales);
  return {{"iteration", it.iteration},
          {"objective", it.objective},
          {"fit", t.fit},
          {"deployed_energy", t.deployed_energy},
          {"flat_energy", t.flat_energy},
          {"regularization", t.regularization},
          {"fit_rms", std::sqrt(2.0 * it.terms.fit / std::max(targets, 1))},
          {"optimality", it.optimality},
          {"evaluations", it.evaluations},
          {"failed_evaluations", it.failed_evaluations},
          {"seconds", it.seconds}};
}

nlohmann::json design_report_json(const DesignReport& report, const Config& config) {
  const DesignLoopResult& r = report.result;
  const RodLinkage& deployed = report.objective.deployed().linkage();
  const int targets = static_cast<int>(report.objective.targets().size());
  nlohmann::json history = nlohmann::json::array();
  for (const DesignIteration& it : r.history)
    history.push_back(history_record(it, report.scales, targets));
  nlohmann::json warnings = nlohmann::json::array();
  if (!report.warning.empty()) warnings.push_back(report.warning);
  return {{"status", minimizer_status_name(r.status)},
          {"reason", r.reason},
          {"rest_lengths", r.lengths},
          {"start_rest_lengths", report.objective.start_lengths()},
          {"fit", fit_json(target_distances(deployed, report.objective.targets()))},
          {"objective", null_if_nan(r.final.value)},
          {"iterations", r.iterations},
          {"evaluations", r.evaluations},
          {"failed_evaluations", r.failed_evaluations},
          {"wall_seconds", report.wall_seconds},
          {"weights", design_json(*config.design)["weights"]},
          {"scales",
           {{"fit", report.scales.fit},
            {"energy", report.scales.energy},
            {"regularization", report.scales.regularization}}},
          {"deployed", state_json(report.objective.deployed())},
          {"flat",
           {{"energy", report.flat.energy().total()},
            {"average_opening_angle", average_opening_angle(report.flat.linkage())},
            {"held_planar", report.flat_planar},
            {"planarity", flat_planarity(report.flat)}}},
          {"history", history},
          {"warnings", warnings},
          {"units", {{"length", fabrication_units(config).length}}},
          {"version", XSHELL_VERSION},
          {"configuration", to_json(config)}};
}

void write_design_outputs(const DesignReport& report, const Config& config,
                          const Eigen::Vector3d& origin, const nlohmann::json& design,
                          const std::string& deployed_state, const std::string& flat_state) {
  const fs::path dir = config.output.directory;
  write_series(report, config, origin);
  write_file_atomically(dir / "deployed_state.json", deployed_state);
  write_file_atomically(dir / "flat_state.json", flat_state);
  write_file_atomically(dir / "flat_layout.obj", flat_layout_obj(report.flat, origin));
  write_fabrication(report.flat.linkage(), fabrication_units(config), dir);
  write_file_atomically(dir / "design.json", design.dump(2) + "\n");
}

}  // namespace xshell
