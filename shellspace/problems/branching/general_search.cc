#include "shellspace/problems/branching/general_search.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <random>
#include <sstream>

#include <ceres/ceres.h>

#include "shellspace/geometry/mesh.h"
#include "shellspace/runtime/parallel_for.h"
#include "shellspace/problems/branching/self_similar_series.h"

namespace shellspace::branching {

namespace {

// Knot s of a layout at given taus (start values).
std::vector<double> KnotS(const GeneralCellLayout& layout,
                          const std::vector<double>& tau) {
  const GeneralTopology& t = layout.topology();
  const int G = static_cast<int>(t.groups.size());
  std::vector<double> s;
  for (int m = 0; m < layout.num_knots(); ++m) {
    const GeneralCellLayout::Knot& k = layout.knot(m);
    const int g0 = layout.segment_start_group(k.segment);
    const double a = g0 < 0 ? 0.0 : tau[g0];
    const double b = g0 + 1 < G ? tau[g0 + 1] : 1.0;
    s.push_back(a + (b - a) * k.step / t.subintervals);
  }
  return s;
}

double SeriesK(int r) { return SeriesConstant(1.0, 1.0, r, OptimalTheta(r)); }

// Sets *x (sized to the layout, zero elsewhere) to the start's pair
// positions, delta, the groups' taus and the needles' p; returns the taus.
std::vector<double> SetStartParameters(const GeneralCellLayout& layout,
                                       double delta, std::vector<double>* x) {
  const GeneralTopology& t = layout.topology();
  const int nc = t.pairs;
  const int G = static_cast<int>(t.groups.size());
  x->assign(layout.size(), 0.0);
  for (int i = 1; i + 1 < 2 * nc; ++i) (*x)[i - 1] = i / (2.0 * nc);
  (*x)[layout.delta_offset()] = delta;
  std::vector<double> tau;
  for (int g = 0; g < G; ++g) {
    tau.push_back(t.first_at_zero && g == 0 ? 0.0 : t.groups[g].tau);
    if (layout.tau_offset(g) >= 0) (*x)[layout.tau_offset(g)] = tau[g];
  }
  int e = 0;
  for (const NucleationGroup& g : t.groups) {
    for (const NeedleEvent& n : g.needles) (*x)[layout.p_offset(e++)] = n.p;
  }
  return tau;
}

// The start's trajectories: trajectory id runs linearly in s from
// birth_pos[id] at birth_s[id] to end[id] at s = 1.
struct StartTrajectories {
  std::vector<double> end, birth_s, birth_pos;
  // Trajectory id's position at s.
  double At(int id, double s) const {
    return birth_pos[id] +
           (end[id] - birth_pos[id]) * (s - birth_s[id]) / (1.0 - birth_s[id]);
  }
};

// The trajectories closed at s = 1 (the final knot's order shifted by the
// label offset, over delta), the initial pairs' 2 nc trajectories born
// evenly spaced at s = 0 (births of later groups are set by PlaceBirths).
StartTrajectories ClosedTrajectories(const GeneralCellLayout& layout,
                                     double delta) {
  const GeneralTopology& t = layout.topology();
  const int nc = t.pairs;
  const int T = layout.num_trajectories();
  const int N = layout.num_knots();
  const std::vector<int>& final_order = layout.knot(N - 1).order;
  StartTrajectories trajectories;
  std::vector<double>& end = trajectories.end;
  std::vector<double>& birth_pos = trajectories.birth_pos;
  end.resize(T);
  trajectories.birth_s.assign(T, 0.0);
  birth_pos.assign(T, 0.0);
  for (size_t j = 0; j < final_order.size(); ++j) {
    const int c = (static_cast<int>(j) + t.label_offset) % (2 * nc);
    const int wrap = (static_cast<int>(j) + t.label_offset) / (2 * nc);
    end[final_order[j]] = delta + (c / (2.0 * nc) + wrap) / t.r;
  }
  for (int i = 0; i < 2 * nc; ++i) birth_pos[i] = i / (2.0 * nc);
  return trajectories;
}

// The needles of `group`, sorted by piece descending = insertion order.
std::vector<int> NeedlesByPiece(const GeneralTopology& t, int group) {
  std::vector<int> by_piece(t.groups[group].needles.size());
  for (size_t q = 0; q < by_piece.size(); ++q) {
    by_piece[q] = static_cast<int>(q);
  }
  std::stable_sort(by_piece.begin(), by_piece.end(), [&](int a, int b) {
    return t.groups[group].needles[a].piece > t.groups[group].needles[b].piece;
  });
  return by_piece;
}

// The births of the knots where a group is born (knot s values `s`): each
// new pair born at its needle's p between its neighbours, its end kept
// within one period of the birth.
void PlaceBirths(const GeneralCellLayout& layout, const std::vector<double>& s,
                 const std::vector<double>& x,
                 StartTrajectories* trajectories) {
  const GeneralTopology& t = layout.topology();
  const int nc = t.pairs;
  const int N = layout.num_knots();
  std::vector<double>& end = trajectories->end;
  for (int m = 0; m < N; ++m) {
    const GeneralCellLayout::Knot& k = layout.knot(m);
    if (k.born_group < 0) continue;
    const int M = static_cast<int>(k.order.size());
    int e0 = 0;
    for (int gg = 0; gg < k.born_group; ++gg) {
      e0 += static_cast<int>(t.groups[gg].needles.size());
    }
    const std::vector<int> by_piece = NeedlesByPiece(t, k.born_group);
    int first_id = 2 * nc;
    for (int gg = 0; gg < k.born_group; ++gg) {
      first_id += 2 * static_cast<int>(t.groups[gg].needles.size());
    }
    for (int j = 0; j < M; ++j) {
      const int id = k.order[j];
      if (layout.birth_group(id) != k.born_group) continue;
      const int prev = k.order[(j + M - 1) % M];
      if (layout.birth_group(prev) == k.born_group) continue;
      const int hi_index = (j + 2) % M;
      const int hi = k.order[hi_index];
      const double lo_pos = trajectories->At(prev, s[m]);
      const double hi_pos =
          trajectories->At(hi, s[m]) + (hi_index == 0 ? 1.0 : 0.0);
      const double p = x[layout.p_offset(e0 + by_piece[(id - first_id) / 2])];
      const double b = lo_pos + p * (hi_pos - lo_pos);
      for (int f : {id, k.order[(j + 1) % M]}) {
        trajectories->birth_s[f] = s[m];
        trajectories->birth_pos[f] = b;
        // Keep the unwrapped end consistent with the birth (within one period).
        while (end[f] - b > 1.0) end[f] -= 1.0;
        while (b - end[f] > 1.0) end[f] += 1.0;
      }
    }
  }
}

// The inner knots' positions in *x: on the trajectories, plus uniform noise
// of amplitude noise / (2 r pairs) from `seed`.
void PlaceKnots(const GeneralCellLayout& layout, const std::vector<double>& s,
                const StartTrajectories& trajectories, double noise,
                unsigned seed, std::vector<double>* x) {
  const GeneralTopology& t = layout.topology();
  const int nc = t.pairs;
  const int N = layout.num_knots();
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  const double scale = noise / (2.0 * t.r * nc);
  for (int m = 1; m + 1 < N; ++m) {
    const GeneralCellLayout::Knot& k = layout.knot(m);
    for (int id : k.order) {
      if (k.param[id] < 0) continue;
      (*x)[k.param[id]] = trajectories.At(id, s[m]) + scale * uniform(rng);
    }
  }
}

}  // namespace

bool GeneralStart(const GeneralCellLayout& layout, double delta, double noise,
                  unsigned seed, std::vector<double>* x) {
  const std::vector<double> tau = SetStartParameters(layout, delta, x);
  // End positions (closure) and birth positions.
  StartTrajectories trajectories = ClosedTrajectories(layout, delta);
  const std::vector<double> s = KnotS(layout, tau);
  PlaceBirths(layout, s, *x, &trajectories);
  PlaceKnots(layout, s, trajectories, noise, seed, x);
  GeneralCellGeometry geometry;
  return EvaluateGeneralGeometry(layout, x->data(), &geometry);
}

GeneralResult OptimizeGeneral(const GeneralTopology& topology,
                              const std::vector<double>& start,
                              int max_iterations) {
  GeneralResult result;
  result.topology = topology;
  auto* cost = new GeneralCellCostFunction(topology);
  const GeneralCellLayout& layout = cost->layout();
  result.x = start;
  if (static_cast<int>(start.size()) != layout.size()) {
    delete cost;
    throw InputError("general cell: start vector of the wrong size");
  }
  ceres::Problem problem;
  problem.AddResidualBlock(cost, nullptr, result.x.data());
  for (int e = 0; e < layout.num_needles(); ++e) {
    problem.SetParameterLowerBound(result.x.data(), layout.p_offset(e), 0.0);
    problem.SetParameterUpperBound(result.x.data(), layout.p_offset(e), 1.0);
  }
  for (size_t g = 0; g < topology.groups.size(); ++g) {
    const int o = layout.tau_offset(static_cast<int>(g));
    if (o < 0) continue;
    problem.SetParameterLowerBound(result.x.data(), o, 0.01);
    problem.SetParameterUpperBound(result.x.data(), o, 0.98);
  }
  ceres::Solver::Options options;
  options.trust_region_strategy_type = ceres::LEVENBERG_MARQUARDT;
  options.linear_solver_type = ceres::DENSE_QR;
  options.max_num_iterations = max_iterations;
  options.function_tolerance = 1e-12;
  options.gradient_tolerance = 1e-14;
  options.parameter_tolerance = 1e-12;
  options.logging_type = ceres::SILENT;
  options.num_threads = 1;
  ceres::Solver::Summary summary;
  ceres::Solve(options, &problem, &summary);
  result.iterations = static_cast<int>(summary.iterations.size()) - 1;
  result.termination = ceres::TerminationTypeToString(summary.termination_type);
  GeneralCellGeometry geometry;
  result.ok = summary.IsSolutionUsable() &&
              EvaluateGeneralGeometry(layout, result.x.data(), &geometry);
  if (!result.ok) return result;
  result.A = geometry.A;
  result.B = geometry.B;
  result.AB2 = geometry.A * geometry.B * geometry.B;
  result.constant_geometric = SeriesK(topology.r) * std::cbrt(result.AB2);
  result.constant_free =
      FreeLengthSeriesConstant(topology.r) * std::cbrt(result.AB2);
  result.delta = result.x[layout.delta_offset()];
  // Optimised tau / p back into the topology (documentation, restarts).
  int e = 0;
  for (size_t g = 0; g < result.topology.groups.size(); ++g) {
    const int o = layout.tau_offset(static_cast<int>(g));
    result.topology.groups[g].tau = o < 0 ? 0.0 : result.x[o];
    for (NeedleEvent& n : result.topology.groups[g].needles) {
      n.p = result.x[layout.p_offset(e++)];
    }
  }
  return result;
}

GeneralResult SolveGeneral(const GeneralTopology& topology, double delta,
                           double noise, unsigned seed, int max_iterations) {
  const GeneralCellLayout layout(topology);
  std::vector<double> x;
  if (!GeneralStart(layout, delta, noise, seed, &x)) {
    GeneralResult bad;
    bad.topology = topology;
    bad.termination = "invalid start";
    return bad;
  }
  return OptimizeGeneral(topology, x, max_iterations);
}

GeneralResult RefineGeneral(const GeneralResult& coarse, int factor,
                            int max_iterations) {
  if (factor < 1) throw InputError("general refine: factor must be >= 1");
  const GeneralCellLayout old_layout(coarse.topology);
  GeneralCellGeometry geo;
  if (!EvaluateGeneralGeometry(old_layout, coarse.x.data(), &geo)) {
    throw InputError("general refine: parameters outside the valid domain");
  }
  GeneralTopology t = coarse.topology;
  t.subintervals *= factor;
  const GeneralCellLayout layout(t);
  std::vector<double> x(layout.size(), 0.0);
  // Shared leading block: q, Delta, taus, p.
  for (int k = 0; k < layout.p_offset(0) + layout.num_needles(); ++k) {
    x[k] = coarse.x[k];
  }
  const int K = coarse.topology.subintervals;
  for (int m = 1; m + 1 < layout.num_knots(); ++m) {
    const GeneralCellLayout::Knot& knot = layout.knot(m);
    // Old knot index of (segment, step / factor) and the fraction between.
    const int seg = knot.segment;
    const int step = knot.step / factor, rest = knot.step % factor;
    const int old = seg * K + step;
    const double f = static_cast<double>(rest) / factor;
    for (int id : knot.order) {
      if (knot.param[id] < 0) continue;
      const double a = geo.position[old][id];
      const double b = rest == 0 ? a : geo.position[old + 1][id];
      x[knot.param[id]] = a + f * (b - a);
    }
  }
  return OptimizeGeneral(t, x, max_iterations);
}

CellPattern GeneralCellPattern(const GeneralResult& result) {
  const GeneralCellLayout layout(result.topology);
  GeneralCellGeometry geo;
  if (!EvaluateGeneralGeometry(layout, result.x.data(), &geo)) {
    throw InputError("general cell: parameters outside the valid domain");
  }
  CellPattern pattern;
  pattern.family = "general";
  pattern.r = result.topology.r;
  const double d = result.delta * result.topology.r;
  pattern.next_offset = d - std::floor(d);
  pattern.swap_variants = result.topology.label_offset % 2 == 1;
  const int N = layout.num_knots();
  for (int id = 0; id < layout.num_trajectories(); ++id) {
    std::vector<double> ks, kg;
    for (int m = 0; m < N; ++m) {
      if (std::isnan(geo.position[m][id])) continue;
      // Knots of zero length (none: ds > 0) and the birth knot included.
      ks.push_back(geo.s[m]);
      kg.push_back(geo.position[m][id]);
    }
    InterfaceCurve c;
    c.jump = layout.jump(id);
    c.s_begin = ks.front();
    c.s_end = 1.0;
    auto locate = [ks](double s) {
      size_t k = std::upper_bound(ks.begin(), ks.end(), s) - ks.begin();
      if (k == 0) k = 1;
      if (k >= ks.size()) k = ks.size() - 1;
      return k;
    };
    c.position = [ks, kg, locate](double s) {
      const size_t k = locate(s);
      const double f = (s - ks[k - 1]) / (ks[k] - ks[k - 1]);
      return kg[k - 1] + f * (kg[k] - kg[k - 1]);
    };
    c.velocity = [ks, kg, locate](double s) {
      const size_t k = locate(s);
      return (kg[k] - kg[k - 1]) / (ks[k] - ks[k - 1]);
    };
    pattern.interfaces.push_back(c);
  }
  for (int m = 1; m + 1 < N; ++m) pattern.breakpoints.push_back(geo.s[m]);
  return pattern;
}

std::string DescribeGeneral(const GeneralResult& result) {
  std::ostringstream out;
  out.precision(8);
  const GeneralTopology& t = result.topology;
  out << "topology " << t.name << ": pairs " << t.pairs << ", r " << t.r
      << ", label offset " << t.label_offset << ", subintervals "
      << t.subintervals << (t.first_at_zero ? ", first group at s = 0" : "")
      << "\n";
  for (size_t g = 0; g < t.groups.size(); ++g) {
    out << "  group " << g << " at tau = " << t.groups[g].tau << ":";
    for (const NeedleEvent& n : t.groups[g].needles) {
      out << " (piece " << n.piece << ", p = " << n.p << ")";
    }
    out << "\n";
  }
  out << "  A = " << result.A << ", B = " << result.B << ", A B^2 = "
      << result.AB2 << ", C (geometric lengths) = " << result.constant_geometric
      << ", C (free lengths) = " << result.constant_free << ", Delta = "
      << result.delta << "; LM " << result.iterations << " iterations, "
      << result.termination << "\n";
  const GeneralCellLayout layout(t);
  GeneralCellGeometry geo;
  if (EvaluateGeneralGeometry(layout, result.x.data(), &geo)) {
    for (int m = 0; m < layout.num_knots(); ++m) {
      out << "  s = " << geo.s[m] << ":";
      for (int id : geo.order[m]) out << " " << id << ":" << geo.position[m][id];
      out << "\n";
    }
  }
  return out.str();
}

}  // namespace shellspace::branching

namespace shellspace::branching {

namespace {

void AddCombinations(int n, int k, int first, std::vector<int>* current,
                     std::vector<std::vector<int>>* out) {
  if (static_cast<int>(current->size()) == k) {
    out->push_back(*current);
    return;
  }
  for (int i = first; i < n; ++i) {
    current->push_back(i);
    AddCombinations(n, k, i + 1, current, out);
    current->pop_back();
  }
}

// Ordered sequences of groups: each group a nonempty set of distinct
// pieces of the order before it (pieces ascending), until `remaining`
// needles are placed.
void AddGroupings(int alive, int remaining, std::vector<std::vector<int>>* current,
                  std::vector<std::vector<std::vector<int>>>* out) {
  if (remaining == 0) {
    out->push_back(*current);
    return;
  }
  for (int k = 1; k <= std::min(remaining, alive); ++k) {
    std::vector<std::vector<int>> subsets;
    std::vector<int> cur;
    AddCombinations(alive, k, 0, &cur, &subsets);
    for (const std::vector<int>& s : subsets) {
      current->push_back(s);
      AddGroupings(alive + 2 * k, remaining - k, current, out);
      current->pop_back();
    }
  }
}

}  // namespace

// For each r and n_c (n_c > 1 only for r <= 3): every ordered grouping of
// the n_c (r - 1) needles (AddGroupings; for n_c = 2 only one group, or for
// r = 3 two groups of one needle per coarse lamella). Start values: the
// needles' p = 1/2 (and for r = 2 also all 0 / all 1, the psi-junction),
// taus evenly in [0.3, 0.7] (one group: 1/2), for one group also the variant
// nucleating at s = 0; every label offset.
std::vector<GeneralTopology> SearchTopologies(
    const GeneralSearchOptions& options) {
  std::vector<GeneralTopology> out;
  for (int r : options.ratios) {
    for (int nc = 1; nc <= options.max_pairs; ++nc) {
      if (nc > 1 && r > 3) continue;
      const int needles = nc * (r - 1);
      std::vector<std::vector<std::vector<int>>> groupings;
      if (nc == 1) {
        std::vector<std::vector<int>> cur;
        AddGroupings(2 * nc, needles, &cur, &groupings);
      } else {
        if (needles <= 2 * nc) {
          std::vector<std::vector<int>> combos;
          std::vector<int> cur;
          AddCombinations(2 * nc, needles, 0, &cur, &combos);
          for (const auto& combo : combos) groupings.push_back({combo});
        }
        if (needles == 4 && 2 * nc == 4) {
          for (int mask = 1; mask < 15; ++mask) {
            std::vector<int> a, b;
            for (int piece = 0, shift = 0; piece < 4; ++piece) {
              if (mask & (1 << piece)) {
                a.push_back(piece);
                shift += 2;
              } else {
                b.push_back(piece + shift);
              }
            }
            groupings.push_back({a, b});
          }
        }
      }
      int index = 0;
      for (const auto& grouping : groupings) {
        const int G = static_cast<int>(grouping.size());
        std::vector<double> ps = {0.5};
        if (r == 2) ps = {0.5, 0.0, 1.0};
        for (double p : ps) {
          for (bool at_zero : {false, true}) {
            if (at_zero && G > 1) continue;
            for (int o = 0; o < 2 * nc; ++o) {
              GeneralTopology t;
              t.pairs = nc;
              t.r = r;
              t.label_offset = o;
              t.subintervals = options.subintervals;
              t.first_at_zero = at_zero;
              for (int g = 0; g < G; ++g) {
                NucleationGroup group;
                group.tau = G == 1 ? 0.5 : 0.3 + 0.4 * g / (G - 1.0);
                for (int piece : grouping[g]) group.needles.push_back({piece, p});
                t.groups.push_back(group);
              }
              std::ostringstream name;
              name << "r" << r << "-n" << nc << "-g" << index << "-p" << p
                   << (at_zero ? "-z" : "") << "-o" << o << "-";
              for (int g = 0; g < G; ++g) {
                name << (g ? "|" : "");
                for (size_t k = 0; k < grouping[g].size(); ++k) {
                  name << (k ? "," : "") << grouping[g][k];
                }
              }
              t.name = name.str();
              out.push_back(t);
            }
          }
        }
        ++index;
      }
    }
  }
  return out;
}

GeneralSearchResult SearchGeneral(
    const GeneralSearchOptions& options,
    const std::function<void(const GeneralResult&)>& progress) {
  std::vector<GeneralTopology> topologies;
  for (const GeneralTopology& t : SearchTopologies(options)) {
    if (options.filter.empty() || t.name.find(options.filter) != std::string::npos) {
      topologies.push_back(t);
    }
  }
  GeneralSearchResult out;
  out.per_topology.resize(topologies.size());
  std::vector<int> solves(topologies.size(), 0);
  auto run = [&](size_t i) {
    const GeneralTopology& t = topologies[i];
    GeneralResult best;
    const double unit = 1.0 / (4.0 * t.r * t.pairs);
    const double base = -static_cast<double>(t.label_offset) / (2.0 * t.pairs * t.r);
    int count = 0;
    for (double shift : {0.0, unit, -unit}) {
      for (int k = 0; k <= options.starts_per_topology; ++k) {
        const double noise = k == 0 ? 0.0 : 0.3;
        const unsigned seed = options.seed + 7919u * static_cast<unsigned>(i) +
                              104729u * static_cast<unsigned>(k);
        GeneralResult r = SolveGeneral(t, base + shift, noise, seed,
                                       options.max_iterations);
        ++count;
        if (r.ok && (!best.ok || r.AB2 < best.AB2)) best = r;
      }
    }
    solves[i] = count;
    out.per_topology[i] = best;
  };
  const int threads = std::max(1, options.num_threads);
  if (threads == 1) {
    for (size_t i = 0; i < topologies.size(); ++i) {
      run(i);
      if (progress) progress(out.per_topology[i]);
    }
  } else {
    // Work items are independent; each writes only its own slot.
    ParallelFor(static_cast<int>(topologies.size()), threads,
                [&](int i) { run(static_cast<size_t>(i)); });
    if (progress) {
      for (const GeneralResult& r : out.per_topology) progress(r);
    }
  }
  // Deterministic: the best by (A B^2, topology index), independent of the
  // order the threads finished in.
  std::vector<size_t> ranked;
  for (size_t i = 0; i < topologies.size(); ++i) {
    out.solves += solves[i];
    if (out.per_topology[i].ok) ranked.push_back(i);
  }
  // By C (free lengths): A B^2 alone does not compare different r.
  std::stable_sort(ranked.begin(), ranked.end(), [&](size_t a, size_t b) {
    return out.per_topology[a].constant_free < out.per_topology[b].constant_free;
  });
  // The best few refined (knots doubled, same geometry as the start, then
  // LM): the refined optimum is never worse than the coarse one.
  const size_t refine = std::min<size_t>(ranked.size(), options.refine_best);
  std::vector<GeneralResult> refined(refine);
  auto refine_one = [&](size_t k) {
    refined[k] = out.per_topology[ranked[k]];
    if (options.refine_factor > 1) {
      GeneralResult r = RefineGeneral(refined[k], options.refine_factor,
                                      options.refine_iterations);
      if (r.ok && r.AB2 <= refined[k].AB2) refined[k] = r;
    }
  };
  ParallelFor(static_cast<int>(refine), threads,
              [&](int k) { refine_one(static_cast<size_t>(k)); });
  out.solves += static_cast<int>(refine);
  for (const GeneralResult& r : refined) {
    if (r.ok && (!out.best.ok || r.constant_free < out.best.constant_free)) {
      out.best = r;
    }
  }
  if (!out.best.ok && !ranked.empty()) out.best = out.per_topology[ranked[0]];
  return out;
}

}  // namespace shellspace::branching
