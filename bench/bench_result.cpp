#include "bench_result.hpp"

#include <cstdlib>
#include <sstream>
#include <string>
#include <type_traits>
#include <variant>
#include <vector>

namespace xshell::bench {

namespace {

using Field = std::variant<std::string BenchResult::*, int BenchResult::*, long BenchResult::*,
                           double BenchResult::*>;

struct Column {
  const char* name;
  Field field;
};

// The CSV's columns, in order: one table for the header, the writer and
// the reader.
const std::vector<Column>& columns() {
  using R = BenchResult;
  static const std::vector<Column> table = {
      {"case", &R::name},
      {"kind", &R::kind},
      {"subdivisions", &R::subdivisions},
      {"gravity", &R::gravity},
      {"threads", &R::threads},
      {"unknowns", &R::unknowns},
      {"free_unknowns", &R::free_unknowns},
      {"hessian_nonzeros", &R::hessian_nonzeros},
      {"energy_gradient_ms", &R::energy_gradient_ms},
      {"hessian_ms", &R::hessian_ms},
      {"factorization_ms", &R::factorization_ms},
      {"iteration_ms", &R::iteration_ms},
      {"factorizations_per_iteration", &R::factorizations_per_iteration},
      {"iteration_over_factorizations", &R::iteration_over_factorizations},
      {"newton_iterations", &R::iterations},
      {"solve_s", &R::solve_s},
      {"status", &R::status},
      {"gradient_measure", &R::gradient_measure},
      {"peak_rss_mb", &R::peak_rss_mb},
      {"hessian_cpu_ms", &R::hessian_cpu_ms},
      {"factorization_cpu_ms", &R::factorization_cpu_ms},
      {"iteration_cpu_ms", &R::iteration_cpu_ms},
      {"iteration_over_factorizations_cpu", &R::iteration_over_factorizations_cpu},
      {"dynamics_steps", &R::dynamics_steps},
      {"dynamics_s", &R::dynamics_s},
      {"dynamics_status", &R::dynamics_status},
      {"kinetic_iterations", &R::kinetic_iterations},
      {"kinetic_s", &R::kinetic_s},
      {"kinetic_status", &R::kinetic_status},
      {"solve_hessian_ms", &R::solve_hessian_ms},
      {"solve_factorization_ms", &R::solve_factorization_ms},
      {"solve_rest_ms", &R::solve_rest_ms},
      {"hessian_1thread_ms", &R::hessian_1thread_ms},
      {"hessian_speedup", &R::hessian_speedup},
      {"iteration_over_solve_factorizations", &R::iteration_over_solve_factorizations},
      {"newton_median_s", &R::newton_median_s},
      {"comparison_newton_iterations", &R::comparison_newton_iterations},
      {"comparison_newton_status", &R::comparison_newton_status},
      {"hessian_slowest_core_ms", &R::hessian_slowest_core_ms},
      {"hessian_fastest_core_ms", &R::hessian_fastest_core_ms},
      {"hessian_speedup_ceiling", &R::hessian_speedup_ceiling},
      {"deployment_iterations", &R::deployment_iterations},
      {"deployment_s", &R::deployment_s},
      {"deployment_status", &R::deployment_status},
      {"deployment_peak_rss_mb", &R::deployment_peak_rss_mb},
  };
  return table;
}

// Sets r's field from its CSV text (std::invalid_argument when an integer
// does not parse).
void parse_into(BenchResult& r, const Field& field, const std::string& text) {
  std::visit(
      [&](auto member) {
        using T = std::decay_t<decltype(r.*member)>;
        if constexpr (std::is_same_v<T, std::string>) r.*member = text;
        if constexpr (std::is_same_v<T, int>) r.*member = std::stoi(text);
        if constexpr (std::is_same_v<T, long>) r.*member = std::stol(text);
        if constexpr (std::is_same_v<T, double>) r.*member = std::strtod(text.c_str(), nullptr);
      },
      field);
}

}  // namespace

std::string csv_header() {
  std::string header;
  for (const Column& c : columns()) header += (header.empty() ? "" : ",") + std::string(c.name);
  return header;
}

std::string to_csv(const BenchResult& r) {
  std::ostringstream o;
  o.precision(6);
  bool first = true;
  for (const Column& c : columns()) {
    if (!first) o << ',';
    first = false;
    std::visit([&](auto member) { o << r.*member; }, c.field);
  }
  return o.str();
}

BenchResult from_csv(const std::string& line) {
  std::vector<std::string> f;
  std::stringstream in(line);
  for (std::string item; std::getline(in, item, ',');) f.push_back(item);
  BenchResult r;
  if (f.size() != columns().size()) {
    r.status = "failed";
    return r;
  }
  try {
    for (size_t i = 0; i < f.size(); ++i) parse_into(r, columns()[i].field, f[i]);
  } catch (const std::exception&) {
    r = BenchResult();
    r.status = "failed";
  }
  return r;
}

}  // namespace xshell::bench
