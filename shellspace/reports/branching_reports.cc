#include "shellspace/reports/branching_reports.h"

#include <cmath>
#include <string>
#include <vector>

#include "shellspace/problems/branching/km_family.h"

namespace shellspace {

using namespace branching;

JsonObject BranchingEnergyJson(double elastic, double interfacial) {
  JsonObject e;
  e.Add("elastic", elastic).Add("interfacial", interfacial)
      .Add("total", elastic + interfacial);
  return e;
}

std::vector<std::string> SimulationFailures(
    const SimulationSettings& s, const SimulationResult& result,
    const DeltaExtrapolation* extrapolation,
    const std::string& iterations_label) {
  std::vector<std::string> failures;
  const std::string last =
      result.stages.empty() ? "" : result.stages.back().termination;
  if (last != "CONVERGENCE") {
    failures.push_back(
        "the last stage ended " + last + " after " +
        std::to_string(result.stages.empty() ? 0
                                             : result.stages.back().iterations) +
        " LM iterations (" + iterations_label + " " +
        std::to_string(s.max_iterations) + " per stage)");
  }
  if (extrapolation && !extrapolation->all_converged) {
    failures.push_back("delta extrapolation: not every width converged");
  }
  return failures;
}

JsonObject SimulationJson(const SimulationSettings& s,
                          const SimulationResult& result,
                          const DeltaExtrapolation* extrapolation) {
  const double scale = std::pow(s.epsilon, 2.0 / 3.0) * std::cbrt(s.length);
  JsonObject summary;
  summary.Add("command", "branching simulate")
      .Add("epsilon", s.epsilon).Add("length", s.length)
      .Add("height", s.height).Add("nx", s.nx).Add("ny", s.ny)
      .Add("grading", s.grading).Add("delta", result.delta)
      .Add("init", s.init).Add("periods", result.periods)
      .Add("energy", BranchingEnergyJson(result.energy.elastic,
                                result.energy.interfacial()))
      .Add("energy_over_eps23_L13", result.energy.total() / scale)
      .Add("km_constant", KmClosedFormConstant())
      .Add("iterations", result.iterations).Add("seconds", result.seconds);
  std::vector<JsonObject> stages;
  for (const RelaxedStage& st : result.stages) {
    JsonObject o;
    o.Add("delta", st.delta).Add("iterations", st.iterations)
        .Add("energy", st.energy.total()).Add("seconds", st.seconds)
        .Add("max_slope", st.max_slope).Add("retried", st.retried)
        .Add("termination", st.termination);
    stages.push_back(o);
  }
  summary.Add("stages", stages);
  // Converged: what SimulationFailures judges.
  summary.Add("converged",
              SimulationFailures(s, result, extrapolation, "").empty());
  std::vector<double> x;
  for (size_t k = 0; k < result.interfaces.size(); ++k) {
    x.push_back(result.field.grid.x(static_cast<int>(k) + 1));
  }
  summary.Add("x", x).Add("interfaces", result.interfaces);
  if (extrapolation) {
    summary.Add("extrapolation", DeltaExtrapolationJson(*extrapolation));
  }
  return summary;
}

JsonObject DeltaExtrapolationJson(const DeltaExtrapolation& ex) {
  JsonObject e;
  std::vector<double> deltas, constants;
  std::vector<int> nys, nxs;
  std::vector<JsonObject> widths;
  for (const DeltaWidth& w : ex.widths) {
    deltas.push_back(w.delta);
    nys.push_back(w.ny);
    nxs.push_back(w.nx);
    constants.push_back(w.constant);
    JsonObject o;
    o.Add("delta", w.delta).Add("nx", w.nx).Add("ny", w.ny)
        .Add("constant", w.constant).Add("elastic", w.elastic)
        .Add("interfacial", w.interfacial).Add("iterations", w.iterations)
        .Add("termination", w.termination).Add("converged", w.converged)
        .Add("interfaces_far", w.interfaces_far)
        .Add("interfaces_max", w.interfaces_max).Add("seconds", w.seconds);
    widths.push_back(o);
  }
  e.Add("delta", deltas).Add("ny", nys).Add("nx", nxs)
      .Add("constant", constants);
  e.Add("widths", widths);
  e.Add("all_converged", ex.all_converged).Add("monotone", ex.monotone)
      .Add("linear_c0", ex.c0).Add("linear_c1", ex.c1)
      .Add("linear_rms", ex.linear_rms);
  if (ex.has_quadratic) {
    e.Add("quadratic_q0", ex.q0).Add("quadratic_q1", ex.q1)
        .Add("quadratic_q2", ex.q2).Add("quadratic_rms", ex.quadratic_rms)
        .Add("root_s0", ex.s0).Add("root_s1", ex.s1).Add("root_s2", ex.s2)
        .Add("root_rms", ex.root_rms);
  }
  e.Add("extrapolated_constant", ex.extrapolated)
      .Add("extrapolation_error", ex.error);
  e.Add("x", ex.x).Add("interfaces", ex.interfaces);
  std::vector<JsonObject> steps;
  for (const auto& step : ex.steps) {
    JsonObject o;
    o.Add("x", step.x).Add("outer", step.outer).Add("inner", step.inner);
    steps.push_back(o);
  }
  e.Add("count_steps", steps);
  return e;
}

JsonObject ConstructionJson(const ConstructionResult& result, double epsilon,
                            double length, bool optimized) {
  JsonObject params;
  params.Add("r", result.r).Add("h0", result.h0).Add("theta", result.theta);
  if (result.family == "lens") {
    params.Add("tau", result.shape.tau).Add("a1", result.shape.a1)
        .Add("a2", result.shape.a2);
  }
  // Every generation length free (same cell): C_free = K_r^free / K_r C at
  // the optimal theta.
  const double free_factor =
      FreeLengthSeriesConstant(result.r) /
      SeriesConstant(1.0, 1.0, result.r, OptimalTheta(result.r));
  const double best_geometric =
      SeriesConstant(result.A, result.B, result.r, OptimalTheta(result.r));
  JsonObject summary;
  summary.Add("command", "branching construct").Add("family", result.family)
      .Add("optimized", optimized).Add("epsilon", epsilon)
      .Add("length", length).Add("constant", result.constant)
      .Add("constant_free_lengths", best_geometric * free_factor)
      .Add("parameters", params).Add("A", result.A).Add("B", result.B)
      .Add("energy", BranchingEnergyJson(result.elastic, result.interfacial));
  if (result.family == "km") {
    summary.Add("A_zero_edge", result.A_zero_edge)
        .Add("constant_zero_edge", result.constant_zero_edge);
  }
  summary.Add("km_constant_closed_form", KmClosedFormConstant())
      .Add("km_shifted_constant_closed_form", KmShiftedClosedFormConstant())
      .Add("needle_constant_closed_form", NeedleClosedFormConstant())
      .Add("ratio_to_km", result.constant / KmClosedFormConstant())
      .Add("ratio_to_km_shifted",
           result.constant / KmShiftedClosedFormConstant());
  if (optimized) {
    summary.Add("iterations", result.iterations)
        .Add("seconds", result.seconds)
        .Add("termination", result.termination);
  }
  return summary;
}

JsonObject GeneralConstructionJson(const GeneralResult& best,
                                   const FreeLengthSeries& series,
                                   double epsilon, double length, bool search,
                                   int solves, double seconds) {
  JsonObject params;
  params.Add("topology", best.topology.name).Add("r", best.topology.r)
      .Add("pairs", best.topology.pairs)
      .Add("label_offset", best.topology.label_offset)
      .Add("subintervals", best.topology.subintervals)
      .Add("delta", best.delta).Add("h0", series.h0)
      .Add("x", best.x);
  std::vector<double> taus, pieces, ps;
  for (const NucleationGroup& g : best.topology.groups) {
    for (const NeedleEvent& e : g.needles) {
      taus.push_back(g.tau);
      pieces.push_back(e.piece);
      ps.push_back(e.p);
    }
  }
  params.Add("needle_tau", taus).Add("needle_piece", pieces).Add("needle_p", ps);
  std::vector<double> lengths(series.lengths.begin(),
                              series.lengths.begin() + 12);
  params.Add("lengths_first12", lengths);
  JsonObject summary;
  summary.Add("command", "branching construct").Add("family", "general")
      .Add("search", search).Add("epsilon", epsilon)
      .Add("length", length).Add("constant", best.constant_free)
      .Add("constant_geometric_lengths", best.constant_geometric)
      .Add("parameters", params).Add("A", best.A).Add("B", best.B)
      .Add("AB2", best.AB2)
      .Add("energy", BranchingEnergyJson(series.elastic, series.interfacial))
      .Add("km_constant_closed_form", KmClosedFormConstant())
      .Add("km_shifted_constant_closed_form", KmShiftedClosedFormConstant())
      .Add("ratio_to_km", best.constant_free / KmClosedFormConstant())
      .Add("ratio_to_km_shifted",
           best.constant_free / KmShiftedClosedFormConstant())
      .Add("solves", solves).Add("seconds", seconds);
  return summary;
}

}  // namespace shellspace
