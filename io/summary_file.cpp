#include "summary_file.hpp"

#include "atomic_file.hpp"
#include "config_parts.hpp"

namespace xshell {

namespace {

nlohmann::json supports_json(const std::vector<std::vector<int>>& support_vertices) {
  nlohmann::json out = nlohmann::json::array();
  for (std::size_t i = 0; i < support_vertices.size(); ++i)
    out.push_back({{"entry", i}, {"vertices", support_vertices[i]}});
  return out;
}

// The transform as configured, with its matrix.
nlohmann::json applied(const GraphTransform& t) {
  nlohmann::json out = transform_json(t);
  const Eigen::Matrix3d a = t.linear();
  nlohmann::json matrix = nlohmann::json::array();
  for (int r = 0; r < 3; ++r) matrix.push_back({a(r, 0), a(r, 1), a(r, 2), t.translate[r]});
  matrix.push_back({0.0, 0.0, 0.0, 1.0});
  out["matrix"] = matrix;
  return out;
}

}  // namespace

nlohmann::json to_json(const RunSummary& s) {
  using nlohmann::json;
  json vertices = json::array(), angles = json::array(), history = json::array();
  for (const auto& v : s.vertices) vertices.push_back({v.x(), v.y(), v.z()});
  for (const auto& a : s.opening_angles) angles.push_back(a ? json(*a) : json(nullptr));
  json outside = json::array();
  for (const auto& j : s.joints_outside_opening_range)
    outside.push_back({{"vertex", j.vertex}, {"angle", j.angle}});
  auto optional = [](const std::optional<double>& x) { return x ? json(*x) : json(nullptr); };
  for (const auto& h : s.history)
    history.push_back({{"iteration", h.iteration},
                       {"time", h.time},
                       {"energy", h.energy},
                       {"gradient_norm", h.gradient_norm},
                       {"step", h.step},
                       {"kinetic_energy", h.kinetic_energy},
                       {"seconds", h.seconds}});
  json saddles = json::array();
  for (const auto& a : s.saddles_escaped)
    saddles.push_back({{"energy", a.energy},
                       {"lowest_eigenvalue", a.lowest_eigenvalue},
                       {"step", a.step ? json(*a.step) : json(nullptr)}});
  json out = {{"status", s.status},
              {"reason", s.reason},
              {"converged", s.converged},
              {"stable", s.stable ? json(*s.stable) : json(nullptr)},
              {"interrupted", s.interrupted},
              {"solver", s.solver},
              {"iterations", s.iterations},
              {"simulated_time", s.simulated_time ? json(*s.simulated_time) : json(nullptr)},
              {"wall_seconds", s.wall_seconds},
              {"timings",
               {{"load", s.timings.load},
                {"setup", s.timings.setup},
                {"solve", s.timings.solve},
                {"analysis", s.timings.analysis},
                {"output", s.timings.output}}},
              {"unknowns", s.unknowns},
              {"free_unknowns", s.free_unknowns},
              {"gradient_norm", s.gradient_norm},
              {"gradient_tolerance", s.gradient_tolerance},
              {"energy",
               {{"total", s.energy.total()},
                {"stretching", s.energy.stretching},
                {"bending", s.energy.bending},
                {"twisting", s.energy.twisting},
                {"external", s.energy.external}}},
              {"vertices", vertices},
              {"opening_angles", angles},
              {"min_opening_angle", optional(s.min_opening_angle)},
              {"max_opening_angle", optional(s.max_opening_angle)},
              {"joints_outside_opening_range", outside},
              {"warnings", s.warnings},
              {"default_support", s.default_support ? json(*s.default_support) : json(nullptr)},
              {"supports", supports_json(s.support_vertices)},
              {"transform", s.transform.is_identity() ? json(nullptr) : applied(s.transform)},
              {"saddles_escaped", saddles},
              {"history", history},
              {"configuration", s.configuration},
              {"version", s.version}};
  if (const auto& d = s.deployment) {
    out["deployment"] = {{"actuation", d->actuation},
                         {"status", d->status},
                         {"steps", d->steps},
                         {"failed_attempts", d->failed_attempts},
                         {"iterations", d->iterations},
                         {"start_average_angle", d->start_average_angle},
                         {"target_average_angle",
                          d->target_average_angle ? json(*d->target_average_angle) : json(nullptr)},
                         {"final_average_angle", d->final_average_angle},
                         {"final_torque", d->final_torque},
                         {"branch_switch_step",
                          d->branch_switch_step ? json(*d->branch_switch_step) : json(nullptr)},
                         {"table", d->table},
                         {"plot", d->plot ? json(*d->plot) : json(nullptr)}};
  }
  for (const auto& [key, value] : s.engineering.items()) out[key] = value;
  return out;
}

void write_summary(const std::string& path, const RunSummary& summary) {
  write_file_atomically(path, to_json(summary).dump(2) + "\n");
}

}  // namespace xshell
