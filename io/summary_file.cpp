#include "summary_file.hpp"

#include "atomic_file.hpp"
#include "config_parts.hpp"
#include "optional_json.hpp"

namespace xshell {

namespace {

nlohmann::json summary_supports_json(const std::vector<std::vector<int>>& support_vertices) {
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

nlohmann::json history_json(const RunSummary& s) {
  nlohmann::json history = nlohmann::json::array();
  for (const auto& h : s.history)
    history.push_back({{"iteration", h.iteration},
                       {"time", h.time},
                       {"energy", h.energy},
                       {"gradient_norm", h.gradient_norm},
                       {"step", h.step},
                       {"kinetic_energy", h.kinetic_energy},
                       {"seconds", h.seconds}});
  return history;
}

nlohmann::json saddles_json(const RunSummary& s) {
  nlohmann::json saddles = nlohmann::json::array();
  for (const auto& a : s.saddles_escaped)
    saddles.push_back({{"energy", a.energy},
                       {"lowest_eigenvalue", a.lowest_eigenvalue},
                       {"step", optional_json(a.step)}});
  return saddles;
}

// The final shape: vertices, opening angles and the joints outside (0, pi).
void add_shape(const RunSummary& s, nlohmann::json& out) {
  using nlohmann::json;
  json vertices = json::array(), angles = json::array(), outside = json::array();
  for (const auto& v : s.vertices) vertices.push_back({v.x(), v.y(), v.z()});
  for (const auto& a : s.opening_angles) angles.push_back(optional_json(a));
  for (const auto& j : s.joints_outside_opening_range)
    outside.push_back({{"vertex", j.vertex}, {"angle", j.angle}});
  out["vertices"] = vertices;
  out["opening_angles"] = angles;
  out["min_opening_angle"] = optional_json(s.min_opening_angle);
  out["max_opening_angle"] = optional_json(s.max_opening_angle);
  out["joints_outside_opening_range"] = outside;
}

nlohmann::json summary_deployment_json(const DeploymentSummary& d) {
  return {{"actuation", d.actuation},
          {"status", d.status},
          {"steps", d.steps},
          {"failed_attempts", d.failed_attempts},
          {"curvature_dropped", d.curvature_dropped},
          {"round_off_floor_steps", d.round_off_floor_steps},
          {"iterations", d.iterations},
          {"factorizations", d.factorizations},
          {"chord_corrections", d.chord_corrections},
          {"start_average_angle", d.start_average_angle},
          {"target_average_angle", optional_json(d.target_average_angle)},
          {"final_average_angle", d.final_average_angle},
          {"final_torque", d.final_torque},
          {"branch_switch_step", optional_json(d.branch_switch_step)},
          {"table", d.table},
          {"plot", optional_json(d.plot)}};
}

}  // namespace

nlohmann::json to_json(const RunSummary& s) {
  using nlohmann::json;
  json out = {{"status", s.status},
              {"reason", s.reason},
              {"converged", s.converged},
              {"stable", optional_json(s.stable)},
              {"interrupted", s.interrupted},
              {"solver", s.solver},
              {"iterations", s.iterations},
              {"simulated_time", optional_json(s.simulated_time)},
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
              {"warnings", s.warnings},
              {"default_support", optional_json(s.default_support)},
              {"supports", summary_supports_json(s.support_vertices)},
              {"transform", s.transform.is_identity() ? json(nullptr) : applied(s.transform)},
              {"saddles_escaped", saddles_json(s)},
              {"history", history_json(s)},
              {"configuration", s.configuration},
              {"version", s.version}};
  add_shape(s, out);
  if (s.deployment) out["deployment"] = summary_deployment_json(*s.deployment);
  for (const auto& [key, value] : s.engineering.items()) out[key] = value;
  return out;
}

void write_summary(const std::string& path, const RunSummary& summary) {
  write_file_atomically(path, to_json(summary).dump(2) + "\n");
}

}  // namespace xshell
