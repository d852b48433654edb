#include "shellspace/problems/branching/general_search.h"

#include <algorithm>
#include <atomic>
#include <thread>
#include <cmath>
#include <limits>
#include <memory>
#include <random>
#include <sstream>

#include <ceres/ceres.h>

#include "shellspace/geometry/mesh.h"
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

}  // namespace

bool GeneralStart(const GeneralCellLayout& layout, double delta, double noise,
                  unsigned seed, std::vector<double>* x) {
  const GeneralTopology& t = layout.topology();
  const int nc = t.pairs;
  const int T = layout.num_trajectories();
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
  // End positions (closure) and birth positions.
  const int N = layout.num_knots();
  const std::vector<int>& final_order = layout.knot(N - 1).order;
  std::vector<double> end(T), birth_s(T, 0.0), birth_pos(T, 0.0);
  for (size_t j = 0; j < final_order.size(); ++j) {
    const int c = (static_cast<int>(j) + t.label_offset) % (2 * nc);
    const int wrap = (static_cast<int>(j) + t.label_offset) / (2 * nc);
    end[final_order[j]] = delta + (c / (2.0 * nc) + wrap) / t.r;
  }
  for (int i = 0; i < 2 * nc; ++i) birth_pos[i] = i / (2.0 * nc);
  auto at = [&](int id, double s) {
    return birth_pos[id] + (end[id] - birth_pos[id]) * (s - birth_s[id]) /
                               (1.0 - birth_s[id]);
  };
  const std::vector<double> s = KnotS(layout, tau);
  for (int m = 0; m < N; ++m) {
    const GeneralCellLayout::Knot& k = layout.knot(m);
    if (k.born_group < 0) continue;
    const int M = static_cast<int>(k.order.size());
    int e0 = 0;
    for (int gg = 0; gg < k.born_group; ++gg) {
      e0 += static_cast<int>(t.groups[gg].needles.size());
    }
    // Needles of the group sorted by piece descending = insertion order.
    std::vector<int> by_piece(t.groups[k.born_group].needles.size());
    for (size_t q = 0; q < by_piece.size(); ++q) by_piece[q] = static_cast<int>(q);
    std::stable_sort(by_piece.begin(), by_piece.end(), [&](int a, int b) {
      return t.groups[k.born_group].needles[a].piece >
             t.groups[k.born_group].needles[b].piece;
    });
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
      const double lo_pos = at(prev, s[m]);
      const double hi_pos = at(hi, s[m]) + (hi_index == 0 ? 1.0 : 0.0);
      const double p =
          (*x)[layout.p_offset(e0 + by_piece[(id - first_id) / 2])];
      const double b = lo_pos + p * (hi_pos - lo_pos);
      for (int f : {id, k.order[(j + 1) % M]}) {
        birth_s[f] = s[m];
        birth_pos[f] = b;
        // Keep the unwrapped end consistent with the birth (within one period).
        while (end[f] - b > 1.0) end[f] -= 1.0;
        while (b - end[f] > 1.0) end[f] += 1.0;
      }
    }
  }
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  const double scale = noise / (2.0 * t.r * nc);
  for (int m = 1; m + 1 < N; ++m) {
    const GeneralCellLayout::Knot& k = layout.knot(m);
    for (int id : k.order) {
      if (k.param[id] < 0) continue;
      (*x)[k.param[id]] = at(id, s[m]) + scale * uniform(rng);
    }
  }
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
      << result.delta << "\n";
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

// Sequences of single-needle groups: piece choices in the growing order.
void AddSequences(int alive, int remaining, std::vector<int>* current,
                  std::vector<std::vector<int>>* out) {
  if (remaining == 0) {
    out->push_back(*current);
    return;
  }
  for (int piece = 0; piece < alive; ++piece) {
    current->push_back(piece);
    AddSequences(alive + 2, remaining - 1, current, out);
    current->pop_back();
  }
}

}  // namespace

// For each r and n_c: (a) one group with all needles in distinct coarse
// pieces (every combination), (b) for at most 3 needles, one needle per
// group in every sequence of pieces; each with the needles' start p all 1/2,
// all 0 or all 1, and with the first group free or at s = 0; every label
// offset. Start taus: one group 1/2; staggered groups evenly in (0.2, 0.8).
std::vector<GeneralTopology> SearchTopologies(
    const GeneralSearchOptions& options) {
  std::vector<GeneralTopology> out;
  for (int r : options.ratios) {
    for (int nc = 1; nc <= options.max_pairs; ++nc) {
      const int needles = nc * (r - 1);
      std::vector<std::vector<NucleationGroup>> shapes;
      if (needles <= 2 * nc) {
        std::vector<std::vector<int>> combos;
        std::vector<int> cur;
        AddCombinations(2 * nc, needles, 0, &cur, &combos);
        for (const auto& c : combos) {
          NucleationGroup g;
          g.tau = 0.5;
          for (int piece : c) g.needles.push_back({piece, 0.5});
          shapes.push_back({g});
        }
      }
      if (needles <= 3 && needles >= 2) {
        std::vector<std::vector<int>> seqs;
        std::vector<int> cur;
        AddSequences(2 * nc, needles, &cur, &seqs);
        for (const auto& seq : seqs) {
          std::vector<NucleationGroup> groups;
          for (size_t k = 0; k < seq.size(); ++k) {
            NucleationGroup g;
            g.tau = 0.2 + 0.6 * k / (seq.size() - 1.0);
            g.needles.push_back({seq[k], 0.5});
            groups.push_back(g);
          }
          shapes.push_back(groups);
        }
      }
      int index = 0;
      for (const auto& shape : shapes) {
        for (double p : {0.5, 0.0, 1.0}) {
          for (bool at_zero : {false, true}) {
            for (int o = 0; o < 2 * nc; ++o) {
              GeneralTopology t;
              t.pairs = nc;
              t.r = r;
              t.label_offset = o;
              t.subintervals = options.subintervals;
              t.first_at_zero = at_zero;
              t.groups = shape;
              for (NucleationGroup& g : t.groups) {
                for (NeedleEvent& e : g.needles) e.p = p;
              }
              if (at_zero && t.groups.size() > 1) {
                // Shift the later groups' start taus up.
                for (size_t k = 1; k < t.groups.size(); ++k) {
                  t.groups[k].tau = 0.6 * k / (t.groups.size() - 1.0) + 0.2;
                }
              }
              std::ostringstream name;
              name << "r" << r << "-n" << nc << "-s" << index << "-p" << p
                   << (at_zero ? "-z" : "") << "-o" << o;
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
  const std::vector<GeneralTopology> topologies = SearchTopologies(options);
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
    std::atomic<size_t> next{0};
    std::vector<std::thread> pool;
    for (int k = 0; k < threads; ++k) {
      pool.emplace_back([&]() {
        for (size_t i = next++; i < topologies.size(); i = next++) run(i);
      });
    }
    for (std::thread& th : pool) th.join();
    if (progress) {
      for (const GeneralResult& r : out.per_topology) progress(r);
    }
  }
  // Deterministic: the best by (A B^2, topology index), independent of the
  // order the threads finished in.
  for (size_t i = 0; i < topologies.size(); ++i) {
    out.solves += solves[i];
    const GeneralResult& r = out.per_topology[i];
    if (r.ok && (!out.best.ok || r.AB2 < out.best.AB2)) out.best = r;
  }
  return out;
}

}  // namespace shellspace::branching
