#include "tests/testing/newton_problems.h"

#include <Eigen/Dense>

namespace shellspace::testing {

EvaluationStatus FunctionProblem::Merit(NewtonPoint point, double* merit) {
  const Eigen::VectorXd& x = At(point);
  if (point == NewtonPoint::kTrial) trial_merits.push_back(NAN);
  if (!f_.feasible(x)) {
    ++infeasible_evaluations;
    return EvaluationStatus::kInfeasible;
  }
  *merit = f_.merit(x);
  if (point == NewtonPoint::kTrial) trial_merits.back() = *merit;
  return EvaluationStatus::kOk;
}

EvaluationStatus FunctionProblem::Residual(NewtonPoint point,
                                           NewtonResidual* r) {
  const Eigen::VectorXd& x = At(point);
  if (!f_.feasible(x)) {
    ++infeasible_evaluations;
    return EvaluationStatus::kInfeasible;
  }
  *r = NewtonResidual::OfReduced(f_.residual(x));
  return EvaluationStatus::kOk;
}

EvaluationStatus FunctionProblem::Assemble(LinearSystem* system) {
  Eigen::MatrixXd j = f_.jacobian(x_);
  if (lower_only_) j = j.triangularView<Eigen::Lower>();
  system->matrix = j.sparseView();
  system->vertex_of.resize(j.rows());
  for (int i = 0; i < j.rows(); ++i) system->vertex_of[i] = i;
  system->num_vertices = static_cast<int>(j.rows());
  return EvaluationStatus::kOk;
}

ConvexExample::ConvexExample(int n)
    : m(Eigen::MatrixXd::Identity(n, n)), a(n) {
  for (int i = 0; i + 1 < n; ++i) m(i, i + 1) = 0.3;
  for (int i = 0; i < n; ++i) a(i) = std::sin(1.0 + i);  // in [-1, 1]
}

Eigen::VectorXd ConvexExample::Minimiser() const {
  return m.partialPivLu().solve(a);
}

Callbacks ConvexExample::MakeCallbacks() const {
  Callbacks c;
  c.merit = [this](const Eigen::VectorXd& x) {
    const Eigen::VectorXd u = m * x - a;
    return (u.array().exp() - u.array()).sum();
  };
  c.residual = [this](const Eigen::VectorXd& x) {
    const Eigen::VectorXd u = m * x - a;
    return Eigen::VectorXd(m.transpose() *
                           (u.array().exp() - 1.0).matrix());
  };
  c.jacobian = [this](const Eigen::VectorXd& x) {
    const Eigen::VectorXd u = m * x - a;
    return Eigen::MatrixXd(m.transpose() *
                           u.array().exp().matrix().asDiagonal() * m);
  };
  return c;
}

::testing::AssertionResult QuadraticRate(
    const std::vector<Eigen::VectorXd>& iterates, const Eigen::VectorXd& x_star,
    double bound) {
  int observed = 0;
  for (size_t k = 0; k + 1 < iterates.size(); ++k) {
    const double e = (iterates[k] - x_star).norm();
    const double e_next = (iterates[k + 1] - x_star).norm();
    if (e < 1e-6) break;
    if (!(e_next <= bound * e * e)) {
      return ::testing::AssertionFailure()
             << "step " << k << ": e = " << e << ", next " << e_next;
    }
    ++observed;
  }
  if (observed < 3) {
    return ::testing::AssertionFailure() << "only " << observed << " steps";
  }
  return ::testing::AssertionSuccess();
}

NewtonSettings Minimize(double tolerance, int max_steps) {
  NewtonSettings s;
  s.mode = NewtonMode::kMinimize;
  s.tolerance = tolerance;
  s.max_steps = max_steps;
  s.forcing = 1e-14;
  return s;
}

Callbacks WithDoubledHessian(const ConvexExample& example) {
  Callbacks wrong = example.MakeCallbacks();
  const auto exact = wrong.jacobian;
  wrong.jacobian = [exact](const Eigen::VectorXd& x) {
    return Eigen::MatrixXd(2.0 * exact(x));
  };
  return wrong;
}

Callbacks Hyperbolas() {
  Callbacks c;
  c.merit = [](const Eigen::VectorXd& x) {
    return (1 + x.array().square()).sqrt().sum();
  };
  c.residual = [](const Eigen::VectorXd& x) {
    return Eigen::VectorXd(x.array() / (1 + x.array().square()).sqrt());
  };
  c.jacobian = [](const Eigen::VectorXd& x) {
    return Eigen::MatrixXd(
        (1 + x.array().square()).pow(-1.5).matrix().asDiagonal());
  };
  return c;
}

::testing::AssertionResult MonotoneMerits(
    const Callbacks& c, const std::vector<Eigen::VectorXd>& iterates) {
  for (size_t k = 0; k + 1 < iterates.size(); ++k) {
    const double before = c.merit(iterates[k]);
    const double after = c.merit(iterates[k + 1]);
    if (!(after <= before)) {
      return ::testing::AssertionFailure()
             << "step " << k << ": " << before << " -> " << after;
    }
  }
  return ::testing::AssertionSuccess();
}

Callbacks ScaledSaddle(double scale) {
  Callbacks c;
  c.merit = [scale](const Eigen::VectorXd& x) {
    return 1 +
           scale * (0.5 * x[0] * x[0] + 0.25 * std::pow(x[1] * x[1] - 1, 2));
  };
  c.residual = [scale](const Eigen::VectorXd& x) {
    return Eigen::VectorXd(
        scale *
        (Eigen::VectorXd(2) << x[0], x[1] * (x[1] * x[1] - 1)).finished());
  };
  c.jacobian = [scale](const Eigen::VectorXd& x) {
    Eigen::MatrixXd h = Eigen::MatrixXd::Zero(2, 2);
    h(0, 0) = scale;
    h(1, 1) = scale * (3 * x[1] * x[1] - 1);
    return h;
  };
  return c;
}

}  // namespace shellspace::testing
