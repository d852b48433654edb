#include "shellspace/problems/calculus/vertex_relaxation.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <array>
#include <cmath>
#include <utility>

#include "shellspace/cost_functions/shell/element_hessian.h"
#include "shellspace/geometry/vertex_flags.h"
#include "shellspace/problems/calculus/path_energy.h"
#include "shellspace/runtime/parallel_for.h"

namespace shellspace {
namespace {

// Where vertex v sits in the element set: per group (in ForEachGroup's
// order), per vertex, the (element, position in its stencil) pairs.
using Incidence = std::vector<std::vector<std::vector<std::pair<int, int>>>>;

Incidence BuildIncidence(const ShellSpace& space) {
  Incidence incidence;
  space.elements().ForEachGroup([&](const auto& group) {
    std::vector<std::vector<std::pair<int, int>>> at(space.num_vertices);
    for (int e = 0; e < group.size(); ++e) {
      for (int a = 0; a < static_cast<int>(group.stencils[e].size()); ++a) {
        at[group.stencils[e][a]].emplace_back(e, a);
      }
    }
    incidence.push_back(std::move(at));
  });
  return incidence;
}

template <int kCount>
void Gather(const Positions& x, const std::array<int, kCount>& stencil,
            double* out) {
  for (int a = 0; a < kCount; ++a) {
    for (int c = 0; c < 3; ++c) out[3 * a + c] = x(stencil[a], c);
  }
}

// The local energy K (W[s_{k-1}, s_k] + W[s_k, s_{k+1}]) over the elements
// at vertex v, with its gradient and Hessian in x_k(v) if `gradient` is not
// null. False if an element is degenerate.
class LocalEnergy {
 public:
  LocalEnergy(const ShellSpace& space, const Incidence& incidence,
              const std::vector<Positions>& path)
      : space_(space), incidence_(incidence), path_(path) {}

  bool Evaluate(int k, int v, double* energy, Eigen::Vector3d* gradient,
                Eigen::Matrix3d* hessian) const {
    const double K = static_cast<double>(path_.size()) - 1;
    *energy = 0;
    if (gradient) {
      gradient->setZero();
      hessian->setZero();
    }
    bool ok = true;
    int group_index = 0;
    space_.elements().ForEachGroup([&](const auto& group) {
      const auto& at = incidence_[group_index++][v];
      if (!ok) return;
      constexpr int count = std::decay_t<decltype(group)>::kVertices;
      using D = ElementSecondDerivatives<count>;
      for (const auto& [e, a] : at) {
        double prev[3 * count], own[3 * count], next[3 * count];
        Gather<count>(path_[k - 1], group.stencils[e], prev);
        Gather<count>(path_[k], group.stencils[e], own);
        Gather<count>(path_[k + 1], group.stencils[e], next);
        if (gradient) {
          D before, after;
          if (!before.ComputeModel(HessianModel::kExact, group.element, prev,
                                   own, ShellSide::kDeformed, K,
                                   D::Rows::kDeformed) ||
              !after.ComputeModel(HessianModel::kExact, group.element, own,
                                  next, ShellSide::kReference, K,
                                  D::Rows::kReference)) {
            ok = false;
            return;
          }
          *energy += before.energy + after.energy;
          *gradient += before.grad_deformed.template segment<3>(3 * a) +
                       after.grad_reference.template segment<3>(3 * a);
          *hessian +=
              before.d_grad_deformed.template block<3, 3>(3 * a, 3 * a) +
              after.d_grad_reference.template block<3, 3>(3 * a, 3 * a);
        } else {
          for (const auto* pair : {&prev, &next}) {
            const bool is_before = pair == &prev;
            const StencilPositions<count> x(is_before ? *pair : own,
                                            is_before ? own : *pair);
            constexpr int m = std::decay_t<decltype(group.element)>::kNumResiduals;
            double r[m];
            if (!group.element.template Evaluate<double>(x.ref, x.def, r, nullptr,
                                                       nullptr)) {
              ok = false;
              return;
            }
            double sum = 0;
            for (int i = 0; i < m; ++i) sum += r[i] * r[i];
            *energy += 0.5 * K * sum;
          }
        }
      }
    });
    return ok;
  }

 private:
  const ShellSpace& space_;
  const Incidence& incidence_;
  const std::vector<Positions>& path_;
};

// Damped Newton on x_k(v); returns the accepted steps.
int RelaxVertex(const LocalEnergy& local, int k, int v, int max_steps,
                Positions* shape) {
  int accepted = 0;
  for (int step = 0; step < max_steps; ++step) {
    double energy;
    Eigen::Vector3d g;
    Eigen::Matrix3d h;
    if (!local.Evaluate(k, v, &energy, &g, &h) || !(g.squaredNorm() > 0)) {
      break;
    }
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(
        0.5 * (h + h.transpose()));
    Eigen::Vector3d lambda = eigen.eigenvalues();
    const double scale = lambda.cwiseAbs().maxCoeff();
    if (!(scale > 0)) break;
    lambda = lambda.cwiseMax(1e-8 * scale);
    const Eigen::Vector3d p =
        -eigen.eigenvectors() *
        (eigen.eigenvectors().transpose() * g).cwiseQuotient(lambda);
    const double slope = g.dot(p);  // < 0
    const Eigen::RowVector3d x0 = shape->row(v);
    bool moved = false;
    for (double alpha = 1; alpha > 1e-10; alpha *= 0.5) {
      shape->row(v) = x0 + alpha * p.transpose();
      double trial;
      if (local.Evaluate(k, v, &trial, nullptr, nullptr) &&
          trial <= energy + 1e-4 * alpha * slope) {
        moved = true;
        break;
      }
    }
    if (!moved) {
      shape->row(v) = x0;
      break;
    }
    ++accepted;
  }
  return accepted;
}

}  // namespace

VertexRelaxationReport RelaxPeakVertices(const ShellSpace& space,
                                         const std::vector<int>& fixed_vertices,
                                         double fraction, int max_steps,
                                         int threads,
                                         std::vector<Positions>* path) {
  VertexRelaxationReport report;
  const int K = static_cast<int>(path->size()) - 1;
  if (K < 2) return report;
  // The gradient max norm per vertex of each inner shape.
  std::vector<Eigen::VectorXd> peak(K - 1);
  const bool ok = ForEachInnerShapeGradient(
      space, *path, threads, [&](int i, const Eigen::VectorXd& g) {
        peak[i] = Eigen::Map<const Eigen::MatrixXd>(g.data(), 3,
                                                    space.num_vertices)
                      .cwiseAbs()
                      .colwise()
                      .maxCoeff()
                      .transpose();
      });
  if (!ok) return report;
  const std::vector<char> is_fixed =
      VertexFlags(space.num_vertices, fixed_vertices);
  double largest = 0;
  for (const Eigen::VectorXd& p : peak) {
    for (int v = 0; v < space.num_vertices; ++v) {
      if (!is_fixed[v]) largest = std::max(largest, p(v));
    }
  }
  if (!(largest > 0)) return report;
  std::vector<std::vector<int>> chosen(K + 1);
  for (int k = 1; k < K; ++k) {
    for (int v = 0; v < space.num_vertices; ++v) {
      if (!is_fixed[v] && peak[k - 1](v) >= fraction * largest) {
        chosen[k].push_back(v);
      }
    }
  }
  return RelaxVertices(space, chosen, max_steps, threads, path);
}

VertexRelaxationReport RelaxVertices(
    const ShellSpace& space, const std::vector<std::vector<int>>& vertices,
    int max_steps, int threads, std::vector<Positions>* path) {
  VertexRelaxationReport report;
  const int K = static_cast<int>(path->size()) - 1;
  if (K < 2) return report;
  report.energy_before = TryPathEnergy(space, *path).value_or(0);
  const Incidence incidence = BuildIncidence(space);
  const LocalEnergy local(space, incidence, *path);
  std::vector<int> steps(K - 1, 0), count(K - 1, 0);
  for (int parity : {0, 1}) {
    std::vector<int> shapes;
    for (int k = 1; k < K; ++k) {
      if (k % 2 == parity && k < static_cast<int>(vertices.size()) &&
          !vertices[k].empty()) {
        shapes.push_back(k);
      }
    }
    if (shapes.empty()) continue;
    ParallelFor(static_cast<int>(shapes.size()), threads, [&](int j) {
      const int k = shapes[j];
      for (int v : vertices[k]) {
        ++count[k - 1];
        steps[k - 1] += RelaxVertex(local, k, v, max_steps, &(*path)[k]);
      }
    });
  }
  for (int i = 0; i < K - 1; ++i) {
    report.vertices += count[i];
    report.newton_steps += steps[i];
  }
  report.energy_after = TryPathEnergy(space, *path).value_or(0);
  return report;
}

}  // namespace shellspace
