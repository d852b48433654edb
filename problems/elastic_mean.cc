#include "problems/elastic_mean.h"

#include <string>

#include "geometry/rigid_alignment.h"
#include "problems/rigid_gauge.h"

namespace shellspace {

void CheckShapeSet(const ShellSpace& space, const std::vector<Positions>& shapes,
                   const char* what) {
  if (shapes.empty()) {
    throw InputError(std::string(what) + ": need at least one shape");
  }
  for (size_t i = 0; i < shapes.size(); ++i) {
    if (shapes[i].rows() != space.num_vertices) {
      throw InputError(std::string(what) + ": shape " + std::to_string(i) +
                       " has " + std::to_string(shapes[i].rows()) +
                       " vertices, expected " +
                       std::to_string(space.num_vertices));
    }
    if (!shapes[i].allFinite()) {
      throw InputError(std::string(what) + ": shape " + std::to_string(i) +
                       " has a non-finite coordinate");
    }
  }
}

Positions AlignedVertexAverage(const std::vector<Positions>& shapes) {
  if (shapes.empty()) throw InputError("vertex average of no shapes");
  Positions sum = shapes[0];
  for (size_t i = 1; i < shapes.size(); ++i) {
    sum += AlignRigidly(shapes[i], shapes[0]);
  }
  return sum / static_cast<double>(shapes.size());
}

ElasticMeanResult ComputeElasticMean(const ShellSpace& space,
                                     const std::vector<Positions>& shapes,
                                     const SolverSettings& settings,
                                     const Positions* initial) {
  CheckShapeSet(space, shapes, "elastic mean");
  ElasticMeanResult result;
  if (initial != nullptr) {
    if (initial->rows() != space.num_vertices || !initial->allFinite()) {
      throw InputError("elastic mean: bad initial guess");
    }
    result.mean = *initial;
  } else {
    result.mean = AlignedVertexAverage(shapes);
  }
  ceres::Problem problem;
  for (const Positions& shape : shapes) {
    AddDeformationEnergy(space, ShellArgument::Fixed(shape),
                         ShellArgument::Variable(&result.mean), 1.0, &problem);
  }
  PinRigidMotions(&result.mean, &problem);
  result.summary = SolveWithSettings(&problem, settings);
  result.mean = AlignRigidly(result.mean, shapes[0]);
  for (const Positions& shape : shapes) {
    result.energies.push_back(
        EvaluateDeformationEnergy(space, shape, result.mean).total);
    result.energy += result.energies.back();
  }
  return result;
}

}  // namespace shellspace
