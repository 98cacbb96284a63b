// What `xshell relax` warns of besides the solve's own result, as one-line
// texts for stderr (prefixed "xshell: warning: ") and the summary's
// "warnings": given supports that start far from where they hold their
// vertex (the held position is input + displacement, also when the run
// starts from a saved state), and joints whose opening angle has left
// (0, pi).
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "linkage/opening_angle_range.hpp"
#include "linkage/statics_problem.hpp"

namespace xshell {

// Supports farther than this fraction of the bounding-box diagonal from
// where they hold their vertex, when the problem is made, are warned of.
constexpr double kFarSupportFraction = 0.01;

// A given support whose vertex the problem moved far to hold it.
struct FarSupport {
  int index = 0;                       // supports[index] of the configuration
  int vertex = 0;                      // its vertex
  double distance = 0.0;               // length moved (held components)
  double fraction = 0.0;               // distance / bounding-box diagonal
  Eigen::Vector3d start_displacement;  // the displacement that holds it where it started
};

// The first `given` supports of `problem` (those of the configuration, in
// its order) that its construction moved farther than kFarSupportFraction
// of the bounding-box diagonal (LinkageProblem::support_start_offsets()).
std::vector<FarSupport> far_supports(const LinkageProblem& problem, size_t given);

// "supports[i] (vertex v) starts D from where it is held ...".
std::string far_support_warning(const FarSupport& support, bool from_saved_state);

// The prefix of a failed solve's reason that names them ("supports[i]
// (vertex v) started ... from where it is held; ").
std::string far_supports_reason(const std::vector<FarSupport>& supports);

// "N joints outside (0, pi) ...: vertex v at a rad, ...", or empty.
std::string opening_range_warning(const OpeningAngleRange& range);

}  // namespace xshell
