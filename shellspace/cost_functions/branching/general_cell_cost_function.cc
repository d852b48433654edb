#include "shellspace/cost_functions/branching/general_cell_cost_function.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <string>

#include "shellspace/geometry/mesh.h"

namespace shellspace::branching {

void CheckGeneralTopology(const GeneralTopology& t) {
  if (t.pairs < 1 || t.pairs > 4) {
    throw InputError("general topology: pairs must lie in [1, 4]");
  }
  if (t.r < 2 || t.r > 4) throw InputError("general topology: r must be 2, 3 or 4");
  if (t.label_offset < 0 || t.label_offset >= 2 * t.pairs) {
    throw InputError("general topology: label_offset must lie in [0, 2 pairs)");
  }
  if (t.subintervals < 1 || t.subintervals > 16) {
    throw InputError("general topology: subintervals must lie in [1, 16]");
  }
  int needles = 0;
  int alive = 2 * t.pairs;
  for (size_t g = 0; g < t.groups.size(); ++g) {
    const NucleationGroup& group = t.groups[g];
    if (group.needles.empty()) {
      throw InputError("general topology: a nucleation group without needles");
    }
    std::set<int> pieces;
    for (const NeedleEvent& e : group.needles) {
      if (e.piece < 0 || e.piece >= alive) {
        throw InputError("general topology: needle piece index out of range");
      }
      if (!pieces.insert(e.piece).second) {
        throw InputError("general topology: two needles of one group in one piece");
      }
      if (!(e.p >= 0.0 && e.p <= 1.0)) {
        throw InputError("general topology: needle p must lie in [0, 1]");
      }
    }
    if (!(group.tau >= 0.0 && group.tau < 1.0)) {
      throw InputError("general topology: group tau must lie in [0, 1)");
    }
    needles += static_cast<int>(group.needles.size());
    alive += 2 * static_cast<int>(group.needles.size());
  }
  if (needles != t.pairs * (t.r - 1)) {
    throw InputError("general topology: the needles must number pairs (r - 1)");
  }
  if (t.first_at_zero && t.groups.empty()) {
    throw InputError("general topology: first_at_zero without groups");
  }
}

GeneralCellLayout::GeneralCellLayout(const GeneralTopology& topology)
    : topology_(topology) {
  CheckGeneralTopology(topology_);
  const int nc = topology_.pairs;
  const int G = static_cast<int>(topology_.groups.size());
  const int K = topology_.subintervals;
  for (int i = 0; i < 2 * nc; ++i) {
    jump_.push_back(i % 2 == 0 ? 2 : -2);
    birth_group_.push_back(-1);
  }
  int next = delta_offset() + 1;
  next += topology_.first_at_zero ? G - 1 : G;
  p_offset_ = next;
  for (const NucleationGroup& g : topology_.groups) {
    num_needles_ += static_cast<int>(g.needles.size());
  }
  next += num_needles_;
  num_segments_ = topology_.first_at_zero ? G : G + 1;
  std::vector<int> order;
  for (int i = 0; i < 2 * nc; ++i) order.push_back(i);
  const int slave = 2 * nc - 1;
  for (int seg = 0; seg < num_segments_; ++seg) {
    for (int k = 0; k < K; ++k) {
      Knot knot;
      knot.segment = seg;
      knot.step = k;
      if (k == 0) {
        const int g = segment_start_group(seg);
        if (g >= 0) {
          knot.born_group = g;
          // Insert from the highest piece down so indices stay valid.
          std::vector<NeedleEvent> needles = topology_.groups[g].needles;
          std::sort(needles.begin(), needles.end(),
                    [](const NeedleEvent& a, const NeedleEvent& b) {
                      return a.piece > b.piece;
                    });
          for (const NeedleEvent& e : needles) {
            const int host = order[e.piece];
            const int lo = static_cast<int>(jump_.size());
            jump_.push_back(-jump_[host]);
            birth_group_.push_back(g);
            jump_.push_back(jump_[host]);
            birth_group_.push_back(g);
            order.insert(order.begin() + e.piece + 1, {lo, lo + 1});
          }
        }
      }
      knot.order = order;
      knots_.push_back(knot);
    }
  }
  Knot last;
  last.segment = num_segments_ - 1;
  last.step = K;
  last.order = order;
  knots_.push_back(last);
  const int T = num_trajectories();
  for (int n = 0; n < num_knots(); ++n) {
    Knot& knot = knots_[n];
    knot.param.assign(T, -1);
    if (n == 0 || n + 1 == num_knots()) continue;
    for (int id : knot.order) {
      if (id == slave) continue;
      if (knot.born_group >= 0 && birth_group_[id] == knot.born_group) continue;
      knot.param[id] = next++;
    }
  }
  size_ = next;
  for (int n = 0; n + 1 < num_knots(); ++n) {
    const int M = static_cast<int>(knots_[n].order.size());
    num_residuals_ += M * (M - 1) / 2;
  }
}

int GeneralCellLayout::tau_offset(int group) const {
  if (topology_.first_at_zero) {
    return group == 0 ? -1 : delta_offset() + group;
  }
  return delta_offset() + 1 + group;
}

int GeneralCellLayout::segment_start_group(int segment) const {
  return topology_.first_at_zero ? segment : segment - 1;
}

namespace {

// The residuals are one template, evaluated with T = double (residuals,
// geometry) and with T = ceres::Jet<double, kStride> (the Jacobian, kStride
// columns per pass). Every decision on the domain reads the scalar part.
inline double Value(double v) { return v; }
template <int N>
double Value(const ceres::Jet<double, N>& v) {
  return v.a;
}

// Nucleation positions tau_g per group (tau_0 = 0 if first_at_zero); false
// unless 0 <= tau_0 < tau_1 < ... < tau_{G-1} < 1.
template <typename T>
bool NucleationPositions(const GeneralCellLayout& layout, const T* x,
                         std::vector<T>* tau) {
  const int G = static_cast<int>(layout.topology().groups.size());
  tau->clear();
  for (int g = 0; g < G; ++g) {
    const int o = layout.tau_offset(g);
    tau->push_back(o < 0 ? T(0.0) : x[o]);
  }
  for (int g = 0; g < G; ++g) {
    const double value = Value((*tau)[g]);
    const double lower = g == 0 ? 0.0 : Value((*tau)[g - 1]);
    if (!(value >= lower) || !(value < 1.0)) return false;
    if (g > 0 && !(value > Value((*tau)[g - 1]))) return false;
  }
  return true;
}

// Relative positions p_e per needle (all groups in order); false unless
// every p lies in [0, 1].
template <typename T>
bool NeedlePositions(const GeneralCellLayout& layout, const T* x,
                     std::vector<T>* p) {
  p->clear();
  for (int e = 0; e < layout.num_needles(); ++e) {
    p->push_back(x[layout.p_offset(e)]);
    if (!(Value(p->back()) >= 0.0 && Value(p->back()) <= 1.0)) return false;
  }
  return true;
}

// The coarse end s = 0: q_0 = 0 (gauge), q_1 .. q_{S-1} parameters, q_S from
// the volume constraint; false unless q_0 < q_1 < ... < q_S < 1.
template <typename T>
bool CoarseEnd(const GeneralCellLayout& layout, const T* x,
               std::vector<T>* q) {
  const int slave = 2 * layout.topology().pairs - 1;
  q->assign(1, T(0.0));
  for (int i = 1; i < slave; ++i) q->push_back(x[i - 1]);
  T qs(0.5);
  for (int i = 0; i < slave; ++i) qs += (layout.jump(i) / 2.0) * (*q)[i];
  q->push_back(qs);
  for (int i = 0; i < slave; ++i) {
    if (!(Value((*q)[i + 1]) > Value((*q)[i]))) return false;
  }
  return Value((*q)[slave]) < 1.0;
}

// s of knot m: step / K of the way through its segment [tau_{g0}, tau_{g0+1}]
// (tau_{-1} = 0, tau_G = 1).
template <typename T>
T KnotS(const GeneralCellLayout& layout, const std::vector<T>& tau, int m) {
  const GeneralCellLayout::Knot& knot = layout.knot(m);
  const int G = static_cast<int>(tau.size());
  const int g0 = layout.segment_start_group(knot.segment);
  const T start = g0 < 0 ? T(0.0) : tau[g0];
  const T end = g0 + 1 < G ? tau[g0 + 1] : T(1.0);
  const double f = static_cast<double>(knot.step) / layout.topology().subintervals;
  T s = start;
  s += f * end;
  s += (-f) * start;
  return s;
}

// The fine end s = 1, closed self-similarly: the j-th interface of the final
// order sits at Delta + (q_{(j+o) mod 2n_c} + floor((j+o) / 2n_c)) / r.
template <typename T>
void ClosurePositions(const GeneralCellLayout& layout, const std::vector<T>& q,
                      const T& delta, std::vector<T>* pos) {
  const GeneralTopology& t = layout.topology();
  const std::vector<int>& order = layout.knot(layout.num_knots() - 1).order;
  const int nc = t.pairs;
  for (int j = 0; j < static_cast<int>(order.size()); ++j) {
    const int c = (j + t.label_offset) % (2 * nc);
    const int wrap = (j + t.label_offset) / (2 * nc);
    T v = delta;
    v += (1.0 / t.r) * q[c];
    v += static_cast<double>(wrap) / t.r;
    (*pos)[order[j]] = v;
  }
}

bool BornAtKnot(const GeneralCellLayout& layout,
                const GeneralCellLayout::Knot& knot, int id) {
  return knot.born_group >= 0 && layout.birth_group(id) == knot.born_group;
}

// The interfaces alive before knot m (< N - 1): the coarse end at m = 0;
// further on the parameters, and the volume slave from the +1 fraction 1/2.
template <typename T>
void CarriedPositions(const GeneralCellLayout& layout, const T* x,
                      const std::vector<T>& q, int m, std::vector<T>* pos) {
  const GeneralCellLayout::Knot& knot = layout.knot(m);
  const int slave = 2 * layout.topology().pairs - 1;
  for (int id : knot.order) {
    if (BornAtKnot(layout, knot, id)) continue;
    if (m == 0) {
      (*pos)[id] = q[id];
    } else if (id != slave) {
      (*pos)[id] = x[knot.param[id]];
    }
  }
  if (m == 0) return;
  T v(0.5);
  for (int id : knot.order) {
    if (id == slave || BornAtKnot(layout, knot, id)) continue;
    v += (layout.jump(id) / 2.0) * (*pos)[id];
  }
  (*pos)[slave] = v;
}

// The needle (numbered over all groups) that trajectory `id` of group
// `group` belongs to: a group's trajectories are numbered in insertion
// order, its needles sorted by piece, highest first.
int NeedleOfTrajectory(const GeneralTopology& t, int group, int id) {
  int first_id = 2 * t.pairs, first_needle = 0;
  for (int g = 0; g < group; ++g) {
    const int count = static_cast<int>(t.groups[g].needles.size());
    first_id += 2 * count;
    first_needle += count;
  }
  const std::vector<NeedleEvent>& needles = t.groups[group].needles;
  std::vector<int> by_piece(needles.size());
  for (size_t e = 0; e < by_piece.size(); ++e) by_piece[e] = static_cast<int>(e);
  std::stable_sort(by_piece.begin(), by_piece.end(), [&](int a, int b) {
    return needles[a].piece > needles[b].piece;
  });
  return first_needle + by_piece[(id - first_id) / 2];
}

// The pairs born at knot m: both flanks at lo + p (hi - lo), lo and hi the
// host piece's bounds (its nearest carried neighbours; hi + 1 on the wrap
// piece).
template <typename T>
void NewbornPositions(const GeneralCellLayout& layout, const std::vector<T>& p,
                      int m, std::vector<T>* pos) {
  const GeneralCellLayout::Knot& knot = layout.knot(m);
  const int M = static_cast<int>(knot.order.size());
  for (int j = 0; j < M; ++j) {
    const int id = knot.order[j];
    // The lower flank of a pair: its predecessor is carried.
    if (!BornAtKnot(layout, knot, id)) continue;
    const int prev = knot.order[(j + M - 1) % M];
    if (BornAtKnot(layout, knot, prev)) continue;
    const int hi_index = (j + 2) % M;
    const T& lo = (*pos)[prev];
    T hi = (*pos)[knot.order[hi_index]];
    if (hi_index == 0) hi += 1.0;
    const int needle = NeedleOfTrajectory(layout.topology(), knot.born_group, id);
    const T born = lo + p[needle] * (hi - lo);
    (*pos)[id] = born;
    (*pos)[knot.order[(j + 1) % M]] = born;
  }
}

// B = 2 sum_i (1 - birth_i) = 4 n_c + 4 sum_g n_g (1 - tau_g).
template <typename T>
T InterfacialCoefficient(const GeneralCellLayout& layout,
                         const std::vector<T>& tau) {
  const GeneralTopology& t = layout.topology();
  T B(2.0 * 2 * t.pairs);
  for (size_t g = 0; g < tau.size(); ++g) {
    const double count = static_cast<double>(t.groups[g].needles.size());
    B += 4.0 * count;
    B += (-4.0 * count) * tau[g];
  }
  return B;
}

// The cell at its knots: s and the positions of the alive interfaces (the
// others are left at zero), B, and the parameters read on the way. The
// Jacobian's passes reuse one, so its storage is allocated once.
template <typename T>
struct CellKnots {
  std::vector<T> tau, p, q;       // per group, per needle, at s = 0
  std::vector<T> s;               // [knot]
  std::vector<std::vector<T>> g;  // [knot][trajectory]
  T B;
};

// False outside the domain of tau, p and the coarse end.
template <typename T>
bool EvaluateKnots(const GeneralCellLayout& layout, const T* x,
                   CellKnots<T>* cell) {
  if (!NucleationPositions(layout, x, &cell->tau) ||
      !NeedlePositions(layout, x, &cell->p) || !CoarseEnd(layout, x, &cell->q)) {
    return false;
  }
  const T& delta = x[layout.delta_offset()];
  const int N = layout.num_knots();
  cell->s.resize(N);
  cell->g.resize(N);
  for (int m = 0; m < N; ++m) {
    std::vector<T>& pos = cell->g[m];
    pos.assign(layout.num_trajectories(), T(0.0));
    cell->s[m] = KnotS(layout, cell->tau, m);
    if (m + 1 == N) {
      ClosurePositions(layout, cell->q, delta, &pos);
    } else {
      CarriedPositions(layout, x, cell->q, m, &pos);
      NewbornPositions(layout, cell->p, m, &pos);
    }
  }
  cell->B = InterfacialCoefficient(layout, cell->tau);
  return true;
}

// The pieces of one interval: widths W0 (at s_a), W1 (at s_b) and the
// cumulative jumps D_j (storage reused from interval to interval).
template <typename T>
struct Pieces {
  std::vector<T> W0, W1, D;
};

// The pieces of the interval from knot m to m + 1. False if ds <= 0 or a
// width is negative or zero at both ends.
template <typename T>
bool IntervalPieces(const GeneralCellLayout& layout, const CellKnots<T>& cell,
                    int m, Pieces<T>* pieces) {
  const std::vector<int>& order = layout.knot(m).order;
  const std::vector<T>& g0 = cell.g[m];
  const std::vector<T>& g1 = cell.g[m + 1];
  const int M = static_cast<int>(order.size());
  if (!(Value(cell.s[m + 1]) - Value(cell.s[m]) > 0.0)) return false;
  std::vector<T>& W0 = pieces->W0;
  std::vector<T>& W1 = pieces->W1;
  std::vector<T>& D = pieces->D;
  W0.resize(M);
  W1.resize(M);
  D.resize(M);
  T cumulative(0.0);
  for (int j = 0; j < M; ++j) {
    const int lo = order[j];
    const int hi = order[(j + 1) % M];
    const double wrap = j + 1 == M ? 1.0 : 0.0;
    W0[j] = g0[hi] + wrap - g0[lo];
    W1[j] = g1[hi] + wrap - g1[lo];
    const double w0 = Value(W0[j]), w1 = Value(W1[j]);
    if (!(w0 >= 0.0) || !(w1 >= 0.0) || !(w0 + w1 > 0.0)) return false;
    cumulative += static_cast<double>(-layout.jump(lo)) * g1[lo];
    cumulative += static_cast<double>(layout.jump(lo)) * g0[lo];
    D[j] = cumulative;
  }
  return true;
}

// The residuals of interval m, one per piece pair i < j:
//   r_ij = B sqrt(c_ij / ds) (D_j - D_i),
// written from `residuals` on (if not null); adds the interval's share of A
// to *A (if not null). False outside the domain.
template <typename T>
bool IntervalResiduals(const GeneralCellLayout& layout,
                       const CellKnots<T>& cell, int m, T* residuals,
                       double* A, Pieces<T>* pieces) {
  if (!IntervalPieces(layout, cell, m, pieces)) return false;
  const std::vector<T>& W0 = pieces->W0;
  const std::vector<T>& W1 = pieces->W1;
  const std::vector<T>& D = pieces->D;
  const T ds = cell.s[m + 1] - cell.s[m];
  const int M = static_cast<int>(D.size());
  int row = 0;
  for (int i = 0; i < M; ++i) {
    for (int j = i + 1; j < M; ++j) {
      const T c = (2.0 * W0[i] * W0[j] + W0[i] * W1[j] + W1[i] * W0[j] +
                   2.0 * W1[i] * W1[j]) /
                  6.0;
      if (!(Value(c) > 0.0)) return false;
      using std::sqrt;
      const T R = sqrt(c / ds);
      const T Dij = D[j] - D[i];
      if (A != nullptr) {
        *A += Value(c) * Value(Dij) * Value(Dij) / Value(ds);
      }
      if (residuals != nullptr) residuals[row] = cell.B * R * Dij;
      ++row;
    }
  }
  return true;
}

// The residuals of all intervals in order; A (if not null) summed.
template <typename T>
bool CellEnergy(const GeneralCellLayout& layout, const CellKnots<T>& cell,
                T* residuals, double* A, Pieces<T>* pieces) {
  int row = 0;
  for (int m = 0; m + 1 < layout.num_knots(); ++m) {
    if (!IntervalResiduals(layout, cell, m,
                           residuals == nullptr ? nullptr : residuals + row, A,
                           pieces)) {
      return false;
    }
    const int M = static_cast<int>(layout.knot(m).order.size());
    row += M * (M - 1) / 2;
  }
  return true;
}

// The storage of one residual evaluation, reusable by the next.
template <typename T>
struct CellWorkspace {
  CellKnots<T> cell;
  Pieces<T> pieces;
};

// The templated residual evaluation: the knots, then the energy (storage
// from `work` if given).
template <typename T>
bool CellResiduals(const GeneralCellLayout& layout, const T* x, T* residuals,
                   CellWorkspace<T>* work = nullptr) {
  CellWorkspace<T> local;
  if (work == nullptr) work = &local;
  return EvaluateKnots(layout, x, &work->cell) &&
         CellEnergy(layout, work->cell, residuals, nullptr, &work->pieces);
}

// The Jacobian (row-major, num_residuals x size) by forward-mode automatic
// differentiation in chunks, as ceres::DynamicAutoDiffCostFunction does:
// pass k seeds parameters [k kStride, (k + 1) kStride) and reads those
// columns off the residual jets.
constexpr int kStride = 16;
bool CellJacobian(const GeneralCellLayout& layout, const double* x,
                  double* jacobian) {
  using Jet = ceres::Jet<double, kStride>;
  const int n = layout.size();
  const int rows = layout.num_residuals();
  std::vector<Jet> x_jet(n), r_jet(rows);
  for (int k = 0; k < n; ++k) x_jet[k] = Jet(x[k]);
  CellWorkspace<Jet> work;
  for (int first = 0; first < n; first += kStride) {
    const int width = std::min(kStride, n - first);
    for (int k = 0; k < width; ++k) x_jet[first + k].v[k] = 1.0;
    if (!CellResiduals(layout, x_jet.data(), r_jet.data(), &work)) return false;
    for (int row = 0; row < rows; ++row) {
      double* J = jacobian + static_cast<size_t>(row) * n + first;
      for (int k = 0; k < width; ++k) J[k] = r_jet[row].v[k];
    }
    for (int k = 0; k < width; ++k) x_jet[first + k].v[k] = 0.0;
  }
  return true;
}

// The knots' s, positions (NaN where not alive) and orders, and B, into
// `geometry`; A = 0 until the energy is summed.
void KnotGeometry(const GeneralCellLayout& layout, const CellKnots<double>& cell,
                  GeneralCellGeometry* geometry) {
  const int N = layout.num_knots();
  geometry->s = cell.s;
  geometry->position.assign(
      N, std::vector<double>(layout.num_trajectories(),
                             std::numeric_limits<double>::quiet_NaN()));
  geometry->order.assign(N, {});
  for (int m = 0; m < N; ++m) {
    geometry->order[m] = layout.knot(m).order;
    for (int id : layout.knot(m).order) {
      geometry->position[m][id] = cell.g[m][id];
    }
  }
  geometry->B = cell.B;
  geometry->A = 0.0;
}

// The whole evaluation; residuals / jacobian / geometry optional. The
// residuals and the geometry come from the double evaluation, the Jacobian
// from the jets.
bool Compute(const GeneralCellLayout& layout, const double* x,
             double* residuals, double* jacobian,
             GeneralCellGeometry* geometry) {
  CellKnots<double> cell;
  if (!EvaluateKnots(layout, x, &cell)) return false;
  if (geometry != nullptr) KnotGeometry(layout, cell, geometry);
  double A = 0.0;
  Pieces<double> pieces;
  if (!CellEnergy(layout, cell, residuals, &A, &pieces)) return false;
  if (geometry != nullptr) geometry->A = A;
  return jacobian == nullptr || CellJacobian(layout, x, jacobian);
}

}  // namespace

bool EvaluateGeneralGeometry(const GeneralCellLayout& layout, const double* x,
                             GeneralCellGeometry* geometry) {
  return Compute(layout, x, nullptr, nullptr, geometry);
}

GeneralCellCostFunction::GeneralCellCostFunction(const GeneralTopology& topology)
    : layout_(topology) {
  set_num_residuals(layout_.num_residuals());
  mutable_parameter_block_sizes()->push_back(layout_.size());
}

bool GeneralCellCostFunction::Evaluate(double const* const* parameters,
                                       double* residuals,
                                       double** jacobians) const {
  double* J = (jacobians != nullptr) ? jacobians[0] : nullptr;
  return Compute(layout_, parameters[0], residuals, J, nullptr);
}

}  // namespace shellspace::branching
