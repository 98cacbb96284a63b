#include "render_camera.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>

#include "linkage/bounding_box.hpp"

namespace xshell {

namespace {

struct Direction {
  Eigen::Vector3d back;  // from the focal point to the eye, unit
  Eigen::Vector3d up;
};

Direction preset(RenderView view) {
  switch (view) {
    case RenderView::Top:
      return {Eigen::Vector3d::UnitZ(), Eigen::Vector3d::UnitY()};
    case RenderView::Front:
      return {-Eigen::Vector3d::UnitY(), Eigen::Vector3d::UnitZ()};
    case RenderView::Side:
      return {Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitZ()};
    case RenderView::Iso:
      break;
  }
  return {Eigen::Vector3d(1.0, -1.0, 0.8).normalized(), Eigen::Vector3d::UnitZ()};
}

template <class F>
void for_each_point(const std::vector<vtkPolyData*>& shown, F&& f) {
  for (vtkPolyData* data : shown)
    for (vtkIdType p = 0; p < data->GetNumberOfPoints(); ++p) {
      Eigen::Vector3d x;
      data->GetPoint(p, x.data());
      f(x);
    }
}

// The unit normal of the points' best-fit plane when they lie nearly in it,
// else zero.
Eigen::Vector3d flat_normal(const std::vector<vtkPolyData*>& shown) {
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  double n = 0.0;
  for_each_point(shown, [&](const Eigen::Vector3d& x) { mean += x, n += 1.0; });
  if (n < 3.0) return Eigen::Vector3d::Zero();
  mean /= n;
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  for_each_point(
      shown, [&](const Eigen::Vector3d& x) { covariance += (x - mean) * (x - mean).transpose(); });
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(covariance);
  const Eigen::Vector3d normal = solver.eigenvectors().col(0), along = solver.eigenvectors().col(2);
  double lo[2] = {std::numeric_limits<double>::max(), std::numeric_limits<double>::max()};
  double hi[2] = {std::numeric_limits<double>::lowest(), std::numeric_limits<double>::lowest()};
  for_each_point(shown, [&](const Eigen::Vector3d& x) {
    const double t[2] = {(x - mean).dot(normal), (x - mean).dot(along)};
    for (int i = 0; i < 2; ++i) lo[i] = std::min(lo[i], t[i]), hi[i] = std::max(hi[i], t[i]);
  });
  const bool flat = hi[1] - lo[1] > 0.0 && hi[0] - lo[0] < 0.05 * (hi[1] - lo[1]);
  return flat ? normal : Eigen::Vector3d::Zero();
}

// `back` turned towards `normal` until it makes `degrees` with the plane.
Eigen::Vector3d raised(const Eigen::Vector3d& back, Eigen::Vector3d normal, double degrees) {
  const double s = std::sin(degrees * M_PI / 180.0);
  if (normal.isZero() || std::abs(back.dot(normal)) >= s) return back;
  if (back.dot(normal) < 0.0 || (back.dot(normal) == 0.0 && normal.z() < 0.0)) normal = -normal;
  const Eigen::Vector3d in_plane = (back - back.dot(normal) * normal).normalized();
  return std::sqrt(1.0 - s * s) * in_plane + s * normal;
}

}  // namespace

void place_camera(vtkCamera& camera, const std::vector<vtkPolyData*>& shown, RenderView view,
                  double aspect) {
  BoundingBox box;
  for_each_point(shown, [&](const Eigen::Vector3d& x) { box.extend(x); });
  const Eigen::Vector3d centre = box.centre();
  Direction d = preset(view);
  d.back = raised(d.back, flat_normal(shown), view == RenderView::Iso ? 30.0 : 20.0);
  if (std::abs(d.back.dot(d.up)) > 0.99) d.up = Eigen::Vector3d::UnitY();
  const Eigen::Vector3d up = (d.up - d.back.dot(d.up) * d.back).normalized();
  const Eigen::Vector3d right = up.cross(d.back);
  const double tan_half = std::tan(0.5 * camera.GetViewAngle() * M_PI / 180.0);
  const double margin = 1.05;
  double distance = 0.0;
  for_each_point(shown, [&](const Eigen::Vector3d& x) {
    const Eigen::Vector3d r = x - centre;
    distance = std::max({distance, r.dot(d.back) + margin * std::abs(r.dot(up)) / tan_half,
                         r.dot(d.back) + margin * std::abs(r.dot(right)) / (tan_half * aspect)});
  });
  if (!(distance > 0.0)) distance = 1.0;  // a single point
  const Eigen::Vector3d eye = centre + distance * d.back;
  camera.SetFocalPoint(centre.data());
  camera.SetPosition(eye.data());
  camera.SetViewUp(up.data());
}

}  // namespace xshell
