#include "shellspace/problems/calculus/shape_comparison.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "shellspace/cost_functions/shell/deformation_energy.h"
#include "shellspace/geometry/rigid_alignment.h"

namespace shellspace {

ShapeComparison CompareShapes(const ShellSpace& space, const ShellPath& a,
                              const ShellPath& b) {
  if (a.empty() || a.size() != b.size()) {
    throw InputError("compare: " + std::to_string(a.size()) + " against " +
                     std::to_string(b.size()) +
                     " frames (the two sides need the same number, at least 1)");
  }
  ShapeComparison out;
  double sum = 0;
  long count = 0;
  for (size_t k = 0; k < a.size(); ++k) {
    if (a[k].rows() != b[k].rows() || a[k].rows() != space.num_vertices) {
      throw InputError("compare: frame " + std::to_string(k) + " has " +
                       std::to_string(a[k].rows()) + " against " +
                       std::to_string(b[k].rows()) + " vertices (the shell space has " +
                       std::to_string(space.num_vertices) + ")");
    }
    // Kabsch's motion, unless the identity fits at least as well in the
    // least-squares sense (it does for equal frames, where Kabsch's
    // rotation is the identity only up to round-off).
    const Positions aligned = AlignRigidly(b[k], a[k]);
    const bool identity =
        (b[k] - a[k]).squaredNorm() <= (aligned - a[k]).squaredNorm();
    const Eigen::VectorXd distance =
        ((identity ? b[k] : aligned) - a[k]).rowwise().norm();
    FrameDifference d;
    d.max_distance = distance.maxCoeff();
    d.mean_distance = distance.mean();
    out.frames.push_back(d);
    out.max_distance = std::max(out.max_distance, d.max_distance);
    sum += distance.sum();
    count += distance.size();
  }
  out.mean_distance = sum / count;
  out.diameter = (a[0].colwise().maxCoeff() - a[0].colwise().minCoeff()).norm();
  out.relative_max_distance = out.max_distance / out.diameter;
  if (a.size() == 1) {
    out.energy_a_to_b = EvaluateDeformationEnergy(space, a[0], b[0]).total;
    return out;
  }
  out.energy_a = PathEnergy(space, a);
  out.energy_b = PathEnergy(space, b);
  const double scale = std::max(out.energy_a, out.energy_b);
  out.relative_energy_difference =
      scale > 0 ? std::abs(out.energy_a - out.energy_b) / scale : 0.0;
  return out;
}

ComparisonVerdict JudgeComparison(const ShapeComparison& comparison,
                                  double tolerance, double energy_tolerance) {
  ComparisonVerdict verdict;
  verdict.shapes_agree = comparison.relative_max_distance <= tolerance;
  verdict.energies_agree = comparison.frames.size() <= 1 ||
                           comparison.relative_energy_difference <= energy_tolerance;
  return verdict;
}

}  // namespace shellspace
