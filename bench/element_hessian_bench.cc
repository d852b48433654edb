// Per-element second derivatives on W[cactus0, cactus1] (5,261 vertices,
// 10,518 membrane elements, 15,777 bending elements, default material): the
// hand-derived ones (ElementSecondDerivatives::Compute) against the
// dual-number differentiation of the gradient (ComputeWithDualNumbers), one
// thread, in the pattern of the path Hessian assembler: per element one
// deformed-active call (D_2^2 and the mixed block) and one reference-active
// call with Rows::kReference (D_1^2). Counter ns_per_element. And the
// projected model's term (ElementTermSecondDerivatives, both shapes free:
// the exact 2n x 2n term Hessian, its positive-semidefiniteness test and,
// where that fails, its eigen-decomposition), with the fraction of the
// elements whose term was projected (counter projected).
//
//   build/bench/element_hessian_bench
//   arguments: element (0 membrane, 1 bending), method (0 dual, 1 analytic)
#include <benchmark/benchmark.h>

#include <type_traits>
#include <vector>

#include "shellspace/cost_functions/shell/element_hessian.h"
#include "shellspace/cost_functions/shell/element_set.h"
#include "shellspace/geometry/topology.h"
#include "shellspace/io/mesh_io.h"

namespace shellspace {
namespace {

void BM_ElementSecondDerivatives(benchmark::State& state) {
  const std::string dir = std::string(SHELLSPACE_DATA_DIR) + "/cactus/";
  const Mesh a = ReadMesh(dir + "cactus0.ply");
  const Mesh b = ReadMesh(dir + "cactus1.ply");
  const ShellSpace space(a, Topology::Build(a), ShellMaterial{});
  const int which = static_cast<int>(state.range(0));
  const bool analytic = state.range(1) == 1;
  int count = 0, group_index = 0;
  double checksum = 0;
  space.elements().ForEachGroup([&](const auto& group) {
    if (group_index++ != which) return;
    constexpr int kV = std::decay_t<decltype(group)>::kVertices;
    using D = ElementSecondDerivatives<kV>;
    std::vector<double> ref(3 * kV * group.size()), def(ref.size());
    for (int e = 0; e < group.size(); ++e) {
      GatherCoordinates(a.positions, group.stencils[e], &ref[3 * kV * e]);
      GatherCoordinates(b.positions, group.stencils[e], &def[3 * kV * e]);
    }
    count = group.size();
    D d;
    for (auto _ : state) {
      for (int e = 0; e < group.size(); ++e) {
        const double* r = &ref[3 * kV * e];
        const double* x = &def[3 * kV * e];
        bool ok;
        if (analytic) {
          ok = d.Compute(group.element, r, x, ShellSide::kDeformed, 1.0) &&
               d.Compute(group.element, r, x, ShellSide::kReference, 1.0,
                         D::Rows::kReference);
        } else {
          ok = d.ComputeWithDualNumbers(group.element, r, x,
                                        ShellSide::kDeformed, 1.0) &&
               d.ComputeWithDualNumbers(group.element, r, x,
                                        ShellSide::kReference, 1.0,
                                        D::Rows::kReference);
        }
        if (!ok) state.SkipWithError("degenerate element");
        benchmark::DoNotOptimize(d.d_grad_deformed.data());
        benchmark::DoNotOptimize(d.d_grad_reference.data());
      }
      checksum += d.d_grad_deformed(0, 0) + d.d_grad_reference(0, 0);
    }
  });
  state.counters["elements"] = count;
  // Inverted rate: seconds per (count * 1e-9) = ns per element.
  state.counters["ns_per_element"] = benchmark::Counter(
      count * 1e-9, benchmark::Counter::kIsIterationInvariantRate |
                        benchmark::Counter::kInvert);
  benchmark::DoNotOptimize(checksum);
}
void BM_ProjectedTermSecondDerivatives(benchmark::State& state) {
  const std::string dir = std::string(SHELLSPACE_DATA_DIR) + "/cactus/";
  const Mesh a = ReadMesh(dir + "cactus0.ply");
  const Mesh b = ReadMesh(dir + "cactus1.ply");
  const ShellSpace space(a, Topology::Build(a), ShellMaterial{});
  const int which = static_cast<int>(state.range(0));
  int count = 0, group_index = 0, projected = 0;
  double checksum = 0;
  space.elements().ForEachGroup([&](const auto& group) {
    if (group_index++ != which) return;
    constexpr int kV = std::decay_t<decltype(group)>::kVertices;
    std::vector<double> ref(3 * kV * group.size()), def(ref.size());
    for (int e = 0; e < group.size(); ++e) {
      GatherCoordinates(a.positions, group.stencils[e], &ref[3 * kV * e]);
      GatherCoordinates(b.positions, group.stencils[e], &def[3 * kV * e]);
    }
    count = group.size();
    ElementTermSecondDerivatives<kV> d;
    for (auto _ : state) {
      projected = 0;
      for (int e = 0; e < group.size(); ++e) {
        if (!d.Compute(group.element, &ref[3 * kV * e], &def[3 * kV * e],
                       1.0, true, true)) {
          state.SkipWithError("degenerate element");
        }
        projected += d.projected;
        benchmark::DoNotOptimize(d.bb.data());
      }
      checksum += d.bb(0, 0);
    }
  });
  state.counters["elements"] = count;
  state.counters["projected"] = count > 0 ? double(projected) / count : 0;
  state.counters["ns_per_element"] = benchmark::Counter(
      count * 1e-9, benchmark::Counter::kIsIterationInvariantRate |
                        benchmark::Counter::kInvert);
  benchmark::DoNotOptimize(checksum);
}
BENCHMARK(BM_ProjectedTermSecondDerivatives)
    ->ArgNames({"element"})
    ->DenseRange(0, 1)
    ->Unit(benchmark::kMillisecond);

BENCHMARK(BM_ElementSecondDerivatives)
    ->ArgNames({"element", "analytic"})
    ->ArgsProduct({{0, 1}, {0, 1}})
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace shellspace

