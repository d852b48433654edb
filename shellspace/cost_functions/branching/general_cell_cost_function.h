// The general reduced sharp-interface cell (thesis §8.2; docs/math.md,
// "Branching: the Kohn–Müller model", self-similar constructions): a super-cell
// of n_c lamella pairs whose interfaces are piecewise linear in s, with needle
// nucleation events, refined by r across the cell and closed self-similarly.
// Its energy coefficient product A B^2 as a Ceres cost function whose Jacobian
// comes from forward-mode automatic differentiation (ceres::Jet).
//
// Coordinates: s in [0, 1] from the coarse end (s = 0) to the fine end, eta
// in units of the super-period P (one cell = n_c lamella pairs at s = 0 and
// r n_c pairs at s = 1). Interfaces ("trajectories") are labelled: 0 .. 2n_c-1
// exist from s = 0 (coarse interface i has jump +2 for even i: variant -1
// below, +1 above), the others are born in nucleation groups. Positions are
// unwrapped: with order[0] = trajectory 0, the alive interfaces satisfy
//   g_order[0] < g_order[1] < ... < g_order[M-1] < g_order[0] + 1;
// piece j lies between order[j] and order[j+1] (the last one wraps to
// g_order[0] + 1) and has variant +1 iff jump(order[j]) = +2.
//
// Topology (GeneralTopology): groups g = 0..G-1 nucleate at s = tau_g
// (0 <= tau_0 < tau_1 < ... < 1; tau_0 = 0 fixed if first_at_zero). A needle
// (piece j, relative position p) inserts, right after order[j], two new
// interfaces of opposite jumps (a lamella of the other variant) at
// g_lo + p (g_hi - g_lo) of the piece's bounds: p = 1/2 nucleates in the
// middle of the lamella (needle / lens), p = 0 or 1 on its boundary (the
// psi-junction of Kohn–Müller: one boundary becomes three).
// Knots: every segment [0, tau_0], [tau_0, tau_1], ..., [tau_{G-1}, 1] is cut
// into K equal sub-intervals; the positions of the alive interfaces at the
// interior knots are parameters, except
//   - interfaces born at that knot (determined by p and the host piece),
//   - the volume slave, trajectory S = 2n_c - 1 (jump -2): the +1 fraction
//     V = -sum_i (jump_i / 2) g_i must be 1/2 in every column (u periodic),
//       g_S = 1/2 + sum_{i != S} (jump_i / 2) g_i;
// at s = 0: q_0 = 0 (translation gauge), q_1..q_{2n_c-2} parameters, q_S from
// the volume; at s = 1 the self-similar closure with label offset o:
//   g_order1[j](1) = Delta + (q_{(j+o) mod 2n_c} + floor((j+o) / 2n_c)) / r,
// order1 the final order (the next generation is this cell scaled by 1/r,
// shifted by Delta, variants swapped iff o is odd).
//
// Energy. Between consecutive knots s_a < s_b every interface is linear, so
// the piece widths w_j(t) are linear in t = (s - s_a) / (s_b - s_a) and
// F = -sum_{g_i < eta} jump_i g_i' is constant per piece, F_j = D_j / ds,
//   D_j = -sum_{k <= j} jump(order[k]) (g_order[k](s_b) - g_order[k](s_a)).
// With sum_j w_j = 1, Var F = 1/2 sum_{i,j} w_i w_j (F_i - F_j)^2, so
//   int_{s_a}^{s_b} Var F ds = sum_{i<j} c_ij (D_i - D_j)^2 / ds,
//   c_ij = (2 W0_i W0_j + W0_i W1_j + W1_i W0_j + 2 W1_i W1_j) / 6
// (W0, W1: widths at s_a, s_b), exactly. A = sum over intervals; the
// interfacial coefficient B = 2 sum_i (1 - birth_i) = 2 (2 n_c + 2 sum_g
// n_g (1 - tau_g)). Residuals (one per interval and piece pair):
//   r_ij = B sqrt(c_ij / ds) (D_j - D_i),   sum r^2 = A B^2.
// C = K_r (A B^2)^(1/3) (self_similar_series.h) is the figure of merit.
//
// Parameter block (one, size GeneralCellLayout::size()):
//   [q_1 .. q_{2n_c-2}] [Delta] [tau_g (g >= 1 if first_at_zero)] [p_e]
//   [knot positions: per interior knot, per alive parameter trajectory].
// Evaluation: one template over the scalar type, in the steps above (tau, p
// and the coarse end q; per knot s, then the closure at s = 1 or the carried
// interfaces with the volume slave and the newborn pairs; B; per interval the
// widths W0, W1 and the cumulative jumps D, then r_ij per piece pair).
// Residuals and EvaluateGeneralGeometry evaluate it with double; the
// Jacobian with ceres::Jet<double, 16> in ceil(size / 16) passes, each
// seeding 16 parameters (the chunking of ceres::DynamicAutoDiffCostFunction),
// so the chain rule is the jets' (every knot position is affine in the
// parameters, newborns bilinear in p). Every domain test reads the scalar
// part, so both evaluations take the same branches; with the Jacobian the
// residuals are still those of the double evaluation.
// Evaluate returns false outside the valid domain: a width < 0 at a knot, a
// piece of zero width at both ends of an interval, ds <= 0, p outside [0, 1].
#ifndef SHELLSPACE_COST_FUNCTIONS_BRANCHING_GENERAL_CELL_COST_FUNCTION_H_
#define SHELLSPACE_COST_FUNCTIONS_BRANCHING_GENERAL_CELL_COST_FUNCTION_H_

#include <string>
#include <vector>

#include <ceres/ceres.h>

namespace shellspace::branching {

struct NeedleEvent {
  int piece = 0;   // index of the host piece in the order before the group
  double p = 0.5;  // start value of the relative position across the piece
};

struct NucleationGroup {
  std::vector<NeedleEvent> needles;
  double tau = 0.5;  // start value of the nucleation position
};

struct GeneralTopology {
  int pairs = 1;         // n_c
  int r = 3;             // refinement, in {2, 3, 4}
  int label_offset = 0;  // o in [0, 2 n_c)
  int subintervals = 3;  // K per segment, >= 1
  bool first_at_zero = false;
  std::vector<NucleationGroup> groups;
  std::string name;      // label for reports
};

// Throws InputError (naming the field) unless the topology is consistent:
// n_c >= 1, r in {2,3,4}, sum of needles = n_c (r - 1), valid piece indices.
void CheckGeneralTopology(const GeneralTopology& topology);

// The parameter layout and the knot structure of a topology.
class GeneralCellLayout {
 public:
  explicit GeneralCellLayout(const GeneralTopology& topology);

  const GeneralTopology& topology() const { return topology_; }
  int size() const { return size_; }
  int num_trajectories() const { return static_cast<int>(jump_.size()); }
  int jump(int trajectory) const { return jump_[trajectory]; }
  int birth_group(int trajectory) const { return birth_group_[trajectory]; }
  int num_knots() const { return static_cast<int>(knots_.size()); }
  int num_residuals() const { return num_residuals_; }

  // Offsets into the parameter block.
  int q_offset() const { return 0; }
  int delta_offset() const { return 2 * topology_.pairs - 2; }
  // -1 if tau_g is fixed at 0.
  int tau_offset(int group) const;
  int p_offset(int needle) const { return p_offset_ + needle; }
  int num_needles() const { return num_needles_; }

  struct Knot {
    int segment = 0;      // segment index
    int step = 0;         // k in [0, K] within the segment
    int born_group = -1;  // group born at this knot (its first knot)
    // Alive interfaces leaving the knot (for the interval to the next knot),
    // in cyclic order starting with trajectory 0.
    std::vector<int> order;
    // Parameter index of each trajectory's position at this knot (-1: not a
    // parameter or not alive).
    std::vector<int> param;
  };
  const Knot& knot(int n) const { return knots_[n]; }
  int num_segments() const { return num_segments_; }
  // The group whose tau starts / ends segment `segment` (-1: s = 0, G: s = 1).
  int segment_start_group(int segment) const;

 private:
  GeneralTopology topology_;
  std::vector<int> jump_, birth_group_;
  std::vector<Knot> knots_;
  int size_ = 0, p_offset_ = 0, num_needles_ = 0, num_segments_ = 0;
  int num_residuals_ = 0;
};

// The geometry at the knots for a parameter vector (no derivatives): s of
// every knot and the position of every trajectory alive at it (NaN if not
// alive; born trajectories at their birth knot sit at the birth point). At
// s = 1 `order` is the final order. Returns false outside the valid domain.
struct GeneralCellGeometry {
  std::vector<double> s;                       // per knot
  std::vector<std::vector<double>> position;   // [knot][trajectory]
  std::vector<std::vector<int>> order;         // [knot] (leaving the knot)
  double A = 0.0, B = 0.0;
};
bool EvaluateGeneralGeometry(const GeneralCellLayout& layout, const double* x,
                             GeneralCellGeometry* geometry);

class GeneralCellCostFunction : public ceres::CostFunction {
 public:
  explicit GeneralCellCostFunction(const GeneralTopology& topology);

  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override;

  const GeneralCellLayout& layout() const { return layout_; }

 private:
  GeneralCellLayout layout_;
};

}  // namespace shellspace::branching

#endif  // SHELLSPACE_COST_FUNCTIONS_BRANCHING_GENERAL_CELL_COST_FUNCTION_H_
