#include "shellspace/cost_functions/deformation_energy.h"

#include <cmath>
#include <sstream>
#include <string>

#include "shellspace/cost_functions/bending_cost_function.h"
#include "shellspace/cost_functions/membrane_cost_function.h"
#include "shellspace/geometry/element_geometry.h"

namespace shellspace {

void ShellMaterial::Validate() const {
  const auto fail = [](const std::string& what, double value) {
    std::ostringstream message;
    message << "shell material: " << what << ", got " << value;
    throw InputError(message.str());
  };
  if (!(mu > 0) || !std::isfinite(mu)) {
    fail("the membrane weight mu must be a positive number", mu);
  }
  if (!(lambda > 0) || !std::isfinite(lambda)) {
    fail("the membrane weight lambda must be a positive number", lambda);
  }
  if (!(eta >= 0) || !std::isfinite(eta)) {
    fail("the bending weight eta must be a non-negative number", eta);
  }
}

namespace {

// Gathers the coordinates of `vertices` of a fixed shell (nullptr if variable)
// and the parameter blocks of a variable one.
template <int kVertices>
const double* Gather(const ShellArgument& arg, const int* vertices,
                     double* buffer, std::vector<double*>* blocks) {
  for (int v = 0; v < kVertices; ++v) {
    double* p = arg.positions + 3 * vertices[v];
    if (arg.variable) {
      blocks->push_back(p);
    } else {
      for (int c = 0; c < 3; ++c) buffer[3 * v + c] = p[c];
    }
  }
  return arg.variable ? nullptr : buffer;
}

}  // namespace

void AddDeformationEnergy(const ShellSpace& space, ShellArgument reference,
                          ShellArgument deformed, double weight,
                          ceres::Problem* problem,
                          std::vector<ceres::ResidualBlockId>* ids) {
  const MembraneElement membrane = space.material.membrane();
  const BendingElement bending = space.material.bending();
  std::vector<double*> blocks;
  for (int f = 0; f < space.faces.rows(); ++f) {
    const int vertices[3] = {space.faces(f, 0), space.faces(f, 1),
                             space.faces(f, 2)};
    double ref_buffer[9], def_buffer[9];
    blocks.clear();
    const double* ref = Gather<3>(reference, vertices, ref_buffer, &blocks);
    const double* def = Gather<3>(deformed, vertices, def_buffer, &blocks);
    auto* cost = new MembraneCostFunction(membrane, ref, def, weight);
    const auto id = problem->AddResidualBlock(cost, nullptr, blocks);
    if (ids) ids->push_back(id);
  }
  if (space.material.eta <= 0) return;
  for (const EdgeFlap& flap : space.topology.interior_edges) {
    const int vertices[4] = {flap.i, flap.j, flap.k, flap.l};
    double ref_buffer[12], def_buffer[12];
    blocks.clear();
    const double* ref = Gather<4>(reference, vertices, ref_buffer, &blocks);
    const double* def = Gather<4>(deformed, vertices, def_buffer, &blocks);
    auto* cost = new BendingCostFunction(bending, ref, def, weight);
    const auto id = problem->AddResidualBlock(cost, nullptr, blocks);
    if (ids) ids->push_back(id);
  }
}

DeformationEnergy EvaluateDeformationEnergy(const ShellSpace& space,
                                            const Positions& reference,
                                            const Positions& deformed) {
  DeformationEnergy energy;
  const ShellMaterial& m = space.material;
  auto vertex = [](const Positions& p, int i) -> Vec3<double> {
    return p.row(i).transpose();
  };
  for (int f = 0; f < space.faces.rows(); ++f) {
    const int i = space.faces(f, 0), j = space.faces(f, 1),
              k = space.faces(f, 2);
    const FirstFundamentalForm<double> gbar(
        vertex(reference, i), vertex(reference, j), vertex(reference, k));
    const FirstFundamentalForm<double> g(
        vertex(deformed, i), vertex(deformed, j), vertex(deformed, k));
    const double det_gbar = gbar.g11 * gbar.g22 - gbar.g12 * gbar.g12;
    const double det_g = g.g11 * g.g22 - g.g12 * g.g12;
    if (!(det_gbar > 0) || !(det_g > 0)) {
      throw InputError("triangle " + std::to_string(f) + " is degenerate");
    }
    // tr(gbar^-1 g) with gbar^-1 = adj(gbar) / det gbar.
    const double tr =
        (gbar.g22 * g.g11 - 2 * gbar.g12 * g.g12 + gbar.g11 * g.g22) / det_gbar;
    const double det = det_g / det_gbar;
    const double area = 0.5 * std::sqrt(det_gbar);
    energy.membrane += area * (m.mu / 2 * tr + m.lambda / 4 * det -
                               (m.mu / 2 + m.lambda / 4) * std::log(det) -
                               m.mu - m.lambda / 4);
  }
  for (const EdgeFlap& flap : space.topology.interior_edges) {
    const DihedralAngle<double> theta(
        vertex(deformed, flap.i), vertex(deformed, flap.j),
        vertex(deformed, flap.k), vertex(deformed, flap.l));
    const DihedralAngle<double> theta_bar(
        vertex(reference, flap.i), vertex(reference, flap.j),
        vertex(reference, flap.k), vertex(reference, flap.l));
    const TriangleArea<double> a0(vertex(reference, flap.i),
                                  vertex(reference, flap.j),
                                  vertex(reference, flap.k));
    const TriangleArea<double> a1(vertex(reference, flap.j),
                                  vertex(reference, flap.i),
                                  vertex(reference, flap.l));
    const double edge_sq =
        (vertex(reference, flap.j) - vertex(reference, flap.i)).squaredNorm();
    const double delta = theta.theta - theta_bar.theta;
    energy.bending += delta * delta * edge_sq / ((a0.area + a1.area) / 3);
  }
  energy.total = energy.membrane + m.eta * energy.bending;
  return energy;
}

}  // namespace shellspace
