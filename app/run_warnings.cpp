#include "run_warnings.hpp"

#include <cstdio>

namespace xshell {

namespace {

std::string format(const char* pattern, double value) {
  char text[64];
  std::snprintf(text, sizeof text, pattern, value);
  return text;
}

std::string vector_text(const Eigen::Vector3d& v) {
  return "[" + format("%.9g", v.x()) + ", " + format("%.9g", v.y()) + ", " + format("%.9g", v.z()) +
         "]";
}

std::string support_name(const FarSupport& s) {
  return "supports[" + std::to_string(s.index) + "] (vertex " + std::to_string(s.vertex) + ")";
}

// "D from where it is held (input + displacement, P% of the bounding-box diagonal)".
std::string distance_text(const FarSupport& s) {
  return format("%.4g", s.distance) + " from where it is held (input + displacement, " +
         format("%.3g", 100.0 * s.fraction) + "% of the bounding-box diagonal)";
}

}  // namespace

std::vector<FarSupport> far_supports(const LinkageProblem& problem, size_t given) {
  std::vector<FarSupport> out;
  const std::vector<Eigen::Vector3d>& offsets = problem.support_start_offsets();
  for (size_t i = 0; i < given && i < offsets.size(); ++i) {
    const double distance = offsets[i].norm();
    if (!(distance > kFarSupportFraction * problem.length_scale())) continue;
    const VertexSupport& s = problem.supports()[i];
    out.push_back({static_cast<int>(i), s.vertex, distance, distance / problem.length_scale(),
                   s.displacement - offsets[i]});
  }
  return out;
}

std::string far_support_warning(const FarSupport& s, bool from_saved_state) {
  std::string text = support_name(s) + " starts " + distance_text(s) +
                     ": it is moved there in one jump before the solve";
  if (from_saved_state)
    text +=
        "; a displacement is measured from the input, not from the --init state (to hold it "
        "where the state has it, give \"displacement\": " +
        vector_text(s.start_displacement) + ")";
  return text;
}

std::string far_supports_reason(const std::vector<FarSupport>& supports) {
  if (supports.empty()) return "";
  const FarSupport& first = supports.front();
  std::string text = support_name(first) + " started " + distance_text(first);
  if (supports.size() > 1)
    text += " (and " + std::to_string(supports.size() - 1) + " more supports, " +
            (supports.size() == 2 ? "supports[" + std::to_string(supports[1].index) + "]"
                                  : std::string("see the warnings")) +
            ")";
  return text + "; ";
}

std::string opening_range_warning(const OpeningAngleRange& range) {
  if (range.outside.empty()) return "";
  const size_t n = range.outside.size();
  std::string text = std::to_string(n) + (n == 1 ? " joint has its" : " joints have their") +
                     " opening angle outside (0, pi), where the rods have passed through each "
                     "other (not physical):";
  constexpr size_t kListed = 5;
  for (size_t k = 0; k < n && k < kListed; ++k)
    text += std::string(k == 0 ? " " : ", ") + "vertex " + std::to_string(range.outside[k].vertex) +
            " at " + format("%.6g", range.outside[k].angle) + " rad";
  if (n > kListed) text += " and " + std::to_string(n - kListed) + " more";
  return text + " (all in the summary's joints_outside_opening_range)";
}

}  // namespace xshell
