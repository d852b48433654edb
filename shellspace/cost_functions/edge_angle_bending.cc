#include "shellspace/cost_functions/edge_angle_bending.h"

#include <ceres/ceres.h>

#include <array>
#include <cmath>
#include <string>

#include "shellspace/runtime/blas_threads.h"

namespace shellspace {
namespace {

double FaceEnergy(const EdgeAngleBendingCostFunction& cost, const double* phi) {
  double r[3];
  cost.Residuals(phi, r);
  return 0.5 * (r[0] * r[0] + r[1] * r[1] + r[2] * r[2]);
}

}  // namespace

std::vector<EdgeAngleReferenceFace> EdgeAngleReferenceFaces(
    const Mesh& mesh, const Positions& metric,
    const std::vector<SecondForm2>& target) {
  std::vector<EdgeAngleReferenceFace> out(mesh.num_faces());
  for (int f = 0; f < mesh.num_faces(); ++f) {
    const Eigen::Vector3d x0 = metric.row(mesh.faces(f, 0)).transpose(),
                          x1 = metric.row(mesh.faces(f, 1)).transpose(),
                          x2 = metric.row(mesh.faces(f, 2)).transpose();
    const Eigen::Vector3d e1 = x1 - x0, e2 = x2 - x0;
    const double g11 = e1.dot(e1), g12 = e1.dot(e2), g22 = e2.dot(e2);
    const double l11 = std::sqrt(g11), l21 = g12 / l11;
    const double l22_sq = g22 - l21 * l21;
    EdgeAngleReferenceFace& face = out[f];
    face.area = 0.5 * e1.cross(e2).norm();
    if (!(face.area > 0) || !(l22_sq > 0)) {
      throw InputError("reference face " + std::to_string(f) +
                       " is degenerate (zero area): no metric");
    }
    const double l22 = std::sqrt(l22_sq);
    face.p = 1 / l11;
    face.q = -l21 / (l11 * l22);
    face.s = 1 / l22;
    if (!target.empty()) face.second_form = target[f];
  }
  return out;
}

std::vector<SecondForm2> EdgeAngleSecondForms(
    const std::vector<EdgeAngleFace>& faces, const std::vector<double>& angles) {
  std::vector<SecondForm2> out(faces.size());
  for (size_t f = 0; f < faces.size(); ++f) {
    double phi[3];
    FaceEdgeAngles(faces[f], angles, phi);
    out[f] = EdgeAngleSecondForm(faces[f], phi);
  }
  return out;
}

EdgeAngleFit FitEdgeAngles(const std::vector<EdgeAngleFace>& shape,
                           const std::vector<EdgeAngleReferenceFace>& reference,
                           int num_interior_edges,
                           const EdgeAngleFitOptions& options) {
  EdgeAngleFit fit;
  fit.angles.assign(num_interior_edges, 0.0);
  fit.face_energy.assign(shape.size(), 0.0);
  // The cost functions are owned by the problem; `costs` keeps them for the
  // face energies after the solve.
  std::vector<const EdgeAngleBendingCostFunction*> costs(shape.size());
  ceres::Problem problem;
  // Each boundary slot is bound to its own constant block (Ceres rejects a
  // block repeated in one residual block); its Jacobian column is zero.
  std::vector<std::array<double, 3>> boundary_angles(shape.size(), {0, 0, 0});
  for (size_t f = 0; f < shape.size(); ++f) {
    auto* cost = EdgeAngleBendingCostFunction::Create(shape[f], reference[f],
                                                      options.alpha, options.beta);
    costs[f] = cost;
    double* blocks[3];
    for (int i = 0; i < 3; ++i) {
      blocks[i] = shape[f].interior(i) ? &fit.angles[shape[f].edge[i]]
                                       : &boundary_angles[f][i];
    }
    problem.AddResidualBlock(cost, nullptr, blocks[0], blocks[1], blocks[2]);
    for (int i = 0; i < 3; ++i) {
      if (!shape[f].interior(i)) problem.SetParameterBlockConstant(blocks[i]);
    }
  }
  auto total = [&](const std::vector<double>& angles) {
    double sum = 0;
    for (size_t f = 0; f < shape.size(); ++f) {
      double phi[3];
      FaceEdgeAngles(shape[f], angles, phi);
      fit.face_energy[f] = FaceEnergy(*costs[f], phi);
      sum += fit.face_energy[f];
    }
    return sum;
  };
  fit.energy_at_zero = total(fit.angles);
  fit.face_energy_at_zero = fit.face_energy;
  if (num_interior_edges > 0) {
    // One BLAS thread: the fit's factorisations are small and many
    // (runtime/blas_threads.h has the measurement).
    const ScopedBlasThreads blas(1);
    ceres::Solver::Options solver;
    solver.linear_solver_type = ceres::SPARSE_NORMAL_CHOLESKY;
    solver.max_num_iterations = options.max_iterations;
    solver.function_tolerance = options.function_tolerance;
    solver.gradient_tolerance = options.gradient_tolerance;
    solver.parameter_tolerance = options.parameter_tolerance;
    solver.num_threads = 1;
    solver.logging_type = ceres::SILENT;
    ceres::Solver::Summary summary;
    ceres::Solve(solver, &problem, &summary);
    fit.iterations = static_cast<int>(summary.iterations.size()) - 1;
    fit.converged = summary.termination_type == ceres::CONVERGENCE;
    if (!fit.converged) fit.message = summary.BriefReport();
  } else {
    fit.converged = true;
  }
  fit.energy = total(fit.angles);
  return fit;
}

EdgeAngleBending EvaluateEdgeAngleBending(const Mesh& mesh,
                                          const Topology& topology,
                                          const Positions& reference,
                                          const Positions& deformed,
                                          const EdgeAngleFitOptions& options) {
  const int num_edges = static_cast<int>(topology.interior_edges.size());
  const std::vector<EdgeAngleFace> reference_faces =
      EdgeAngleFaces(mesh, topology, reference);
  EdgeAngleBending out;
  out.reference = FitEdgeAngles(reference_faces,
                                EdgeAngleReferenceFaces(mesh, reference),
                                num_edges, options);
  const std::vector<SecondForm2> hbar =
      EdgeAngleSecondForms(reference_faces, out.reference.angles);
  out.deformed = FitEdgeAngles(EdgeAngleFaces(mesh, topology, deformed),
                               EdgeAngleReferenceFaces(mesh, reference, hbar),
                               num_edges, options);
  out.energy = out.deformed.energy;
  out.converged = out.reference.converged && out.deformed.converged;
  return out;
}

}  // namespace shellspace
