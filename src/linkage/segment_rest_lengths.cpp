// Per-segment rest lengths (rod_linkage.hpp, docs/model.md section 3.8).
#include <cmath>
#include <string>

#include "model_error.hpp"
#include "rod_linkage.hpp"

namespace xshell {

namespace {

double share_weighted_length(const ElasticRod& rod) {
  double length = 0.0;
  const std::vector<double>& rest = rod.rest_lengths();
  for (int j = 0; j < static_cast<int>(rest.size()); ++j)
    length += rod.stretching_share(j) * rest[j];
  return length;
}

}  // namespace

std::vector<double> RodLinkage::segment_rest_lengths() const {
  std::vector<double> lengths;
  lengths.reserve(rods_.size());
  for (const ElasticRod& rod : rods_) lengths.push_back(share_weighted_length(rod));
  return lengths;
}

void RodLinkage::set_segment_rest_lengths(const std::vector<double>& lengths) {
  if (lengths.size() != rods_.size())
    throw ModelError("segment rest lengths: " + std::to_string(lengths.size()) + " given for " +
                     std::to_string(rods_.size()) + " segments");
  for (std::size_t s = 0; s < lengths.size(); ++s)
    if (!std::isfinite(lengths[s]) || lengths[s] <= 0.0)
      throw ModelError("segment rest lengths: segment " + std::to_string(s) + " has rest length " +
                       std::to_string(lengths[s]) + "; each must be positive and finite");
  for (std::size_t s = 0; s < lengths.size(); ++s) {
    ElasticRod& rod = rods_[s];
    const double scale = lengths[s] / share_weighted_length(rod);
    std::vector<double> rest = rod.rest_lengths();
    for (double& l : rest) l *= scale;
    rod.set_rest_lengths(rest);
  }
  options_.segment_rest_lengths = lengths;
}

}  // namespace xshell
