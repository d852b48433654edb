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

// A linear form value + gradient over the parameter block (dense; the
// gradient is empty when derivatives are not requested).
struct Lin {
  double v = 0.0;
  std::vector<double> d;
};

class Forms {
 public:
  Forms(int n, bool grad) : n_(n), grad_(grad) {}
  Lin Constant(double v) const {
    Lin l;
    l.v = v;
    if (grad_) l.d.assign(n_, 0.0);
    return l;
  }
  Lin Param(const double* x, int index) const {
    Lin l = Constant(x[index]);
    if (grad_) l.d[index] = 1.0;
    return l;
  }
  // a += f b
  void Axpy(double f, const Lin& b, Lin* a) const {
    a->v += f * b.v;
    if (grad_) {
      for (int k = 0; k < n_; ++k) a->d[k] += f * b.d[k];
    }
  }
  bool grad() const { return grad_; }
  int n() const { return n_; }

 private:
  int n_;
  bool grad_;
};

// The whole evaluation; residuals / jacobian / geometry optional.
bool Compute(const GeneralCellLayout& layout, const double* x,
             double* residuals, double* jacobian,
             GeneralCellGeometry* geometry) {
  const GeneralTopology& t = layout.topology();
  const int n = layout.size();
  const Forms forms(n, jacobian != nullptr);
  const int nc = t.pairs;
  const int G = static_cast<int>(t.groups.size());
  const int K = t.subintervals;
  const int T = layout.num_trajectories();
  const int slave = 2 * nc - 1;
  // Nucleation positions tau_g as forms; tau_{-1} = 0, tau_G = 1.
  std::vector<Lin> tau;
  for (int g = 0; g < G; ++g) {
    const int o = layout.tau_offset(g);
    tau.push_back(o < 0 ? forms.Constant(0.0) : forms.Param(x, o));
  }
  for (int g = 0; g < G; ++g) {
    const double lower = g == 0 ? 0.0 : tau[g - 1].v;
    if (!(tau[g].v >= lower) || !(tau[g].v < 1.0)) return false;
    if (g > 0 && !(tau[g].v > tau[g - 1].v)) return false;
  }
  std::vector<Lin> p;
  for (int e = 0; e < layout.num_needles(); ++e) {
    p.push_back(forms.Param(x, layout.p_offset(e)));
    if (!(p.back().v >= 0.0 && p.back().v <= 1.0)) return false;
  }
  // Needle index of the first needle of each group.
  std::vector<int> first_needle(G + 1, 0);
  for (int g = 0; g < G; ++g) {
    first_needle[g + 1] =
        first_needle[g] + static_cast<int>(t.groups[g].needles.size());
  }
  // q at s = 0.
  std::vector<Lin> q;
  q.push_back(forms.Constant(0.0));
  for (int i = 1; i + 1 < 2 * nc; ++i) q.push_back(forms.Param(x, i - 1));
  {
    Lin qs = forms.Constant(0.5);
    for (int i = 0; i < slave; ++i) forms.Axpy(layout.jump(i) / 2.0, q[i], &qs);
    q.push_back(qs);
  }
  for (int i = 0; i + 1 < 2 * nc; ++i) {
    if (!(q[i + 1].v > q[i].v)) return false;
  }
  if (!(q[2 * nc - 1].v < 1.0)) return false;
  const Lin delta = forms.Param(x, layout.delta_offset());

  const int N = layout.num_knots();
  std::vector<Lin> s(N);
  std::vector<std::vector<Lin>> g(N, std::vector<Lin>(T));
  for (int m = 0; m < N; ++m) {
    const GeneralCellLayout::Knot& knot = layout.knot(m);
    const int g0 = layout.segment_start_group(knot.segment);
    const Lin start = g0 < 0 ? forms.Constant(0.0) : tau[g0];
    const Lin end = g0 + 1 < G ? tau[g0 + 1] : forms.Constant(1.0);
    Lin sm = start;
    const double f = static_cast<double>(knot.step) / K;
    forms.Axpy(f, end, &sm);
    forms.Axpy(-f, start, &sm);
    s[m] = sm;
    std::vector<Lin>& pos = g[m];
    if (m + 1 == N) {
      // Self-similar closure.
      const int M = static_cast<int>(knot.order.size());
      for (int j = 0; j < M; ++j) {
        const int c = (j + t.label_offset) % (2 * nc);
        const int wrap = (j + t.label_offset) / (2 * nc);
        Lin v = delta;
        forms.Axpy(1.0 / t.r, q[c], &v);
        v.v += static_cast<double>(wrap) / t.r;
        pos[knot.order[j]] = v;
      }
      continue;
    }
    // Pre-existing interfaces.
    for (int id : knot.order) {
      if (knot.born_group >= 0 && layout.birth_group(id) == knot.born_group) {
        continue;
      }
      if (m == 0) {
        pos[id] = q[id];
      } else if (id != slave) {
        pos[id] = forms.Param(x, knot.param[id]);
      }
    }
    if (m > 0) {
      Lin v = forms.Constant(0.5);
      for (int id : knot.order) {
        if (id == slave) continue;
        if (knot.born_group >= 0 && layout.birth_group(id) == knot.born_group) {
          continue;
        }
        forms.Axpy(layout.jump(id) / 2.0, pos[id], &v);
      }
      pos[slave] = v;
    }
    // Births: the order before the group is knot.order without the group's
    // trajectories; each new pair follows its host's lower bound.
    if (knot.born_group >= 0) {
      const int bg = knot.born_group;
      const int M = static_cast<int>(knot.order.size());
      // The host bounds are the nearest pre-existing neighbours.
      for (int j = 0; j < M; ++j) {
        const int id = knot.order[j];
        if (layout.birth_group(id) != bg) continue;
        // Lower flank of a pair: its predecessor is pre-existing.
        const int prev = knot.order[(j + M - 1) % M];
        if (layout.birth_group(prev) == bg) continue;  // upper flank
        const int hi_index = (j + 2) % M;
        const int hi = knot.order[hi_index];
        Lin lo_pos = pos[prev];
        Lin hi_pos = pos[hi];
        if (hi_index == 0) hi_pos.v += 1.0;  // the wrap piece
        // Which needle: trajectories of group bg are numbered in insertion
        // order (highest piece first); recover the needle by its id.
        int first_id = 2 * nc;
        for (int gg = 0; gg < bg; ++gg) {
          first_id += 2 * static_cast<int>(t.groups[gg].needles.size());
        }
        // Insertion order: pieces sorted descending.
        std::vector<int> by_piece(t.groups[bg].needles.size());
        for (size_t e = 0; e < by_piece.size(); ++e) by_piece[e] = static_cast<int>(e);
        std::stable_sort(by_piece.begin(), by_piece.end(), [&](int a, int b) {
          return t.groups[bg].needles[a].piece > t.groups[bg].needles[b].piece;
        });
        const int needle = first_needle[bg] + by_piece[(id - first_id) / 2];
        Lin born = lo_pos;
        const double width = hi_pos.v - lo_pos.v;
        // born = lo + p (hi - lo): bilinear.
        born.v += p[needle].v * width;
        if (forms.grad()) {
          for (int k = 0; k < n; ++k) {
            born.d[k] += p[needle].v * (hi_pos.d[k] - lo_pos.d[k]) +
                         width * p[needle].d[k];
          }
        }
        pos[id] = born;
        pos[knot.order[(j + 1) % M]] = born;
      }
    }
  }

  // Interfacial coefficient.
  Lin B = forms.Constant(2.0 * 2 * nc);
  for (int gg = 0; gg < G; ++gg) {
    const double count = static_cast<double>(t.groups[gg].needles.size());
    B.v += 4.0 * count;
    forms.Axpy(-4.0 * count, tau[gg], &B);
  }

  if (geometry != nullptr) {
    geometry->s.assign(N, 0.0);
    geometry->position.assign(
        N, std::vector<double>(T, std::numeric_limits<double>::quiet_NaN()));
    geometry->order.assign(N, {});
    for (int m = 0; m < N; ++m) {
      geometry->s[m] = s[m].v;
      geometry->order[m] = layout.knot(m).order;
      for (int id : layout.knot(m).order) geometry->position[m][id] = g[m][id].v;
    }
    geometry->B = B.v;
    geometry->A = 0.0;
  }

  int row = 0;
  double A = 0.0;
  for (int m = 0; m + 1 < N; ++m) {
    const std::vector<int>& order = layout.knot(m).order;
    const int M = static_cast<int>(order.size());
    Lin ds = s[m + 1];
    forms.Axpy(-1.0, s[m], &ds);
    if (!(ds.v > 0.0)) return false;
    std::vector<Lin> W0(M), W1(M), D(M);
    Lin cumulative = forms.Constant(0.0);
    for (int j = 0; j < M; ++j) {
      const int lo = order[j];
      const int hi = order[(j + 1) % M];
      const double wrap = j + 1 == M ? 1.0 : 0.0;
      W0[j] = g[m][hi];
      W0[j].v += wrap;
      forms.Axpy(-1.0, g[m][lo], &W0[j]);
      W1[j] = g[m + 1][hi];
      W1[j].v += wrap;
      forms.Axpy(-1.0, g[m + 1][lo], &W1[j]);
      if (!(W0[j].v >= 0.0) || !(W1[j].v >= 0.0) ||
          !(W0[j].v + W1[j].v > 0.0)) {
        return false;
      }
      forms.Axpy(-layout.jump(lo), g[m + 1][lo], &cumulative);
      forms.Axpy(layout.jump(lo), g[m][lo], &cumulative);
      D[j] = cumulative;
    }
    for (int i = 0; i < M; ++i) {
      for (int j = i + 1; j < M; ++j) {
        const double c = (2.0 * W0[i].v * W0[j].v + W0[i].v * W1[j].v +
                          W1[i].v * W0[j].v + 2.0 * W1[i].v * W1[j].v) /
                         6.0;
        if (!(c > 0.0)) return false;
        const double R = std::sqrt(c / ds.v);
        const double Dij = D[j].v - D[i].v;
        A += c * Dij * Dij / ds.v;
        if (residuals != nullptr) residuals[row] = B.v * R * Dij;
        if (jacobian != nullptr) {
          double* J = jacobian + static_cast<size_t>(row) * n;
          const double a0i = (2.0 * W0[j].v + W1[j].v) / 6.0;
          const double a0j = (2.0 * W0[i].v + W1[i].v) / 6.0;
          const double a1i = (W0[j].v + 2.0 * W1[j].v) / 6.0;
          const double a1j = (W0[i].v + 2.0 * W1[i].v) / 6.0;
          const double base = B.v * R * Dij;
          const double fc = base / (2.0 * c);
          const double fds = -base / (2.0 * ds.v);
          const double fB = R * Dij;
          const double fD = B.v * R;
          for (int k = 0; k < n; ++k) {
            const double dc = a0i * W0[i].d[k] + a0j * W0[j].d[k] +
                              a1i * W1[i].d[k] + a1j * W1[j].d[k];
            J[k] = fB * B.d[k] + fc * dc + fds * ds.d[k] +
                   fD * (D[j].d[k] - D[i].d[k]);
          }
        }
        ++row;
      }
    }
  }
  if (geometry != nullptr) geometry->A = A;
  return true;
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
