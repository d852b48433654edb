#include "shellspace/workflows/geodesic.h"

#include <algorithm>
#include <utility>

#include "shellspace/geometry/rigid_alignment.h"
#include "shellspace/geometry/validation.h"
#include "shellspace/problems/calculus/exponential_map.h"
#include "shellspace/reports/path_reports.h"

namespace shellspace {
namespace workflows {
namespace {

// What an unconverged geodesic missed, as the front ends word it.
std::string GradientFailure(const shellspace::GeodesicResult& g,
                            const Faces& faces, const std::string& what) {
  return what + ": |grad| " + ShortNumber(g.final_gradient) +
         " above the target " + ShortNumber(g.gradient_target) +
         " (tolerance x max(1, |grad_0|)) after " +
         std::to_string(g.iterations) + " iterations (" +
         (!g.stall.empty()    ? g.stall
          : g.stages.empty() ? std::string("no stages")
                             : g.stages.back().termination) +
         ")" + GradientPeakText(g, faces);
}

std::vector<std::string> PathWarnings(const shellspace::GeodesicResult& g) {
  std::vector<std::string> warnings;
  if (g.uneven_steps) {
    const auto [lo, hi] =
        std::minmax_element(g.step_energies.begin(), g.step_energies.end());
    warnings.push_back(
        "step energies far from equal: max/min " +
        ShortNumber(g.step_energy_ratio) + " (W of step " +
        std::to_string(hi - g.step_energies.begin() + 1) + " = " +
        ShortNumber(*hi) + ", of step " +
        std::to_string(lo - g.step_energies.begin() + 1) + " = " +
        ShortNumber(*lo) + "; a geodesic has equal steps)");
  }
  if (g.collapsing_faces) {
    const FaceAreaRatio& f = g.smallest_face_area;
    warnings.push_back("face " + std::to_string(f.face) + " of shape " +
                       std::to_string(f.shape) + " has " +
                       ShortNumber(f.ratio) +
                       " of its start area: the path passes near a "
                       "degenerate triangle (a sliver of the mesh?)");
  }
  return warnings;
}

// GeodesicResult::sliver_swelling of the solved path.
void MeasureSliverSwelling(GeodesicResult* result) {
  const ShellPath& path = result->path();
  const Faces& faces = result->start.faces;
  for (const int f : result->slivers.faces) {
    const double reference = FaceNormal(faces, path.front(), f).norm();
    if (!(reference > 0)) continue;
    for (size_t k = 1; k < path.size(); ++k) {
      const double ratio = FaceNormal(faces, path[k], f).norm() / reference;
      if (ratio > result->sliver_swelling) {
        result->sliver_swelling = ratio;
        result->sliver_swelling_face = f;
        result->sliver_swelling_shape = static_cast<int>(k);
      }
    }
  }
}

// The slivers and folds of `end` (the start's faces) that are not in
// `before`, those of the start.
SliverFaces NewSliverFaces(const SliverFaces& before, const Mesh& start,
                           const Positions& end) {
  Mesh end_mesh = start;
  end_mesh.positions = end;
  SliverFaces after = FindSliverFaces(end_mesh);
  const auto drop_old = [](auto* items, const auto& old) {
    items->erase(std::remove_if(items->begin(), items->end(),
                                [&](const auto& item) {
                                  return std::binary_search(
                                      old.begin(), old.end(), item);
                                }),
                 items->end());
  };
  drop_old(&after.faces, before.faces);
  drop_old(&after.folds, before.folds);
  return after;
}

// The input's slivers and folds and how the path treats the slivers.
JsonObject SliverJson(const GeodesicResult& result) {
  const SliverFaces& s = result.slivers;
  return JsonObject()
      .Add("faces", s.faces)
      .Add("smallest_area_fraction", s.smallest_area_fraction)
      .Add("smallest_angle_degrees", s.smallest_degrees)
      .Add("folded_edges", static_cast<int>(s.folds.size()))
      .Add("largest_swelling", result.sliver_swelling)
      .Add("largest_swelling_face", result.sliver_swelling_face)
      .Add("largest_swelling_shape", result.sliver_swelling_shape);
}

// Each shape of a path moves on its own without changing the path energy
// (W[a, b] sees only lengths, angles and areas), but the solve's choices
// are made in coordinates: the initial path's checks compare face normals
// of consecutive shapes (a triangle turning over), and those of a blend
// that also turns by k/K of a rigid motion decide differently for the same
// pose placed differently. Without a mask the solve therefore runs to s_K
// rigidly aligned onto s_0 (FitRigidMotion), every shape in one frame, and
// MoveToUserEnd then carries shape k by the fraction k/K of the inverse
// motion (about the centroid of s_0), so the path ends at the user's s_K
// with the same energy and gradient norm. With a mask the fixed vertices
// pin the frame: no motion.
RigidMotion AlignmentOfEnd(const GeodesicOptions& options) {
  if (!options.fixed_vertices.empty()) return RigidMotion();
  return FitRigidMotion(options.end, options.start.positions);
}

void MoveToUserEnd(const RigidMotion& alignment, const Positions& user_end,
                   ShellPath* path) {
  if (path->size() < 2) return;
  const RigidMotion back = alignment.Inverse();
  const Eigen::RowVector3d centre = path->front().colwise().mean();
  const int steps = static_cast<int>(path->size()) - 1;
  for (int k = 1; k < steps; ++k) {
    (*path)[k] = back.Fraction(static_cast<double>(k) / steps, centre)
                     .Apply((*path)[k]);
  }
  path->back() = user_end;
}

GeodesicResult Solve(const GeodesicOptions& options, const std::string& what) {
  if (options.steps < 1) {
    throw InputError("steps must be >= 1, got " +
                     std::to_string(options.steps));
  }
  GeodesicInput input;
  input.start = options.start.positions;
  const RigidMotion alignment = AlignmentOfEnd(options);
  input.end = alignment.Apply(options.end);
  input.steps = options.steps;
  input.fixed_vertices = options.fixed_vertices;
  input.linear_solver = options.linear_solver;
  input.lm = options.lm;
  input.init = options.init;
  const MultiresolutionSettings levels = ResolveMultiresolution(
      options.multires, options.start.num_vertices());

  GeodesicResult result;
  result.start = options.start;
  result.material = options.material;
  // Legal, but a path may crush them: named once, before the solve.
  result.slivers = FindSliverFaces(options.start);
  if (!result.slivers.empty() && options.warn) {
    options.warn("start", result.slivers.Describe());
  }
  result.end_slivers =
      NewSliverFaces(result.slivers, options.start, options.end);
  if (!result.end_slivers.empty() && options.warn) {
    options.warn("end", result.end_slivers.Describe() +
                            ", which the start does not have: the path must "
                            "crush or fold the surface there");
  }
  const ShellSpace space(options.start, options.topology,
                         options.material.material);
  SolverSettings settings = options.settings;
  const StopRecorder stop(&settings);
  result.solve = SolveGeodesicMultiresolution(space, input, settings, levels);
  result.stopped = stop.stopped();
  MoveToUserEnd(alignment, options.end, &result.solve.geodesic.path);
  const shellspace::GeodesicResult& g = result.solve.geodesic;
  if (!g.failure.empty()) {
    result.status = FailedStatus(what, g.failure);
    return result;
  }
  result.energy_split = PathEnergySplit(space, g.path);
  MeasureSliverSwelling(&result);
  result.warnings = PathWarnings(g);
  std::vector<std::string> failures;
  if (!g.converged) {
    failures.push_back(GradientFailure(g, result.start.faces, what));
  }
  result.status = StatusOf(std::move(failures), result.stopped);
  return result;
}

}  // namespace

std::string GradientPeakText(const shellspace::GeodesicResult& geodesic,
                             const Faces& faces) {
  const GradientPeak& peak = geodesic.gradient_peak;
  if (peak.vertex < 0) return "";
  std::string text = ", largest at vertex " + std::to_string(peak.vertex) +
                     " of shape " + std::to_string(peak.shape);
  const FaceAreaRatio& crushed = geodesic.smallest_face_area;
  if (!geodesic.collapsing_faces || crushed.face < 0 ||
      crushed.face >= faces.rows() ||
      (faces.row(crushed.face).array() != peak.vertex).all()) {
    return text;
  }
  return text + ", a vertex of face " + std::to_string(crushed.face) +
         ", which the solve crushed to " + ShortNumber(crushed.ratio) +
         " of its start area while lowering E_K (a sliver or cap of the "
         "mesh: remesh it)";
}

GeodesicResult RunGeodesic(const GeodesicOptions& options) {
  return Solve(options, "geodesic");
}

JsonObject ToJson(const GeodesicResult& result) {
  JsonObject json = GeodesicJson(result.geodesic());
  json.Add("multires_levels", MultiresolutionJson(result.solve))
      .Add("prolongation", ProlongationJson(result.solve.prolongation))
      .Add("energy_split", EnergySplitJson(result.energy_split))
      .Add("input_slivers", SliverJson(result))
      .Add("end_slivers",
           JsonObject()
               .Add("faces", result.end_slivers.faces)
               .Add("folded_edges",
                    static_cast<int>(result.end_slivers.folds.size())));
  return json;
}

LogResult RunLog(const GeodesicOptions& options) {
  LogResult result;
  result.geodesic = Solve(options, "log: the geodesic");
  result.log = LogOfGeodesic(result.geodesic.path());
  result.log_max_norm = result.log.cwiseAbs().maxCoeff();
  return result;
}

JsonObject ToJson(const LogResult& result) {
  JsonObject json = ToJson(result.geodesic);
  json.Add("log_max_norm", result.log_max_norm);
  return json;
}

}  // namespace workflows
}  // namespace shellspace
