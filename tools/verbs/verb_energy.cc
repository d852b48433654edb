// `shellspace energy`: W_mem, W_bend and W of a (reference, deformed) pair.
#include <gflags/gflags.h>

#include <cstdio>
#include <iostream>
#include <string>

#include "shellspace/cost_functions/edge_angle_bending.h"
#include "shellspace/cost_functions/shell/deformation_energy.h"
#include "shellspace/reports/shape_reports.h"
#include "tools/run/common_flags.h"
#include "tools/run/run_status.h"
#include "tools/run/shell_inputs.h"
#include "tools/verbs/verb.h"

DEFINE_string(deformed, "", "energy: deformed shell");

namespace shellspace {
namespace {

// The --bending values of `energy` beyond the models of every verb: the
// edge-angle variant of the shape operator (cost_functions/
// edge_angle_bending.h; only here and in bench/curvature_study) and "both".
constexpr char kEdgeAngles[] = "shape-operator-edge-angles";
constexpr char kBoth[] = "both";

// The material flags, --bending also accepting the variant and "both".
FlagTable EnergyMaterialFlags() {
  FlagTable table = MaterialFlags();
  for (FlagSpec& spec : table) {
    if (spec.name == "bending") {
      spec.meaning =
          "bending model: discrete-shells (default), shape-operator, "
          "shape-operator-edge-angles (the shape operator with one angle per "
          "interior edge fitted to each shell, docs/math.md, \"Bending "
          "energy: two models\"; energy only), or both (W_bend of all three "
          "reported; total and membrane from discrete-shells)";
    }
  }
  return table;
}

FlagTable EnergyFlags() {
  return Flags({{
                    TextFlag("reference",
                             "reference (undeformed) shell: PLY, OBJ or OFF")
                        .Required(),
                    TextFlag("deformed",
                             "deformed shell with the reference's "
                             "connectivity")
                        .Required(),
                    AllowUnconvergedFlag(),
                },
                EnergyMaterialFlags(), JsonFlag()});
}

// W of the pair with `model` (a model of the element set).
DeformationEnergy EnergyWith(const Shell& reference, const Mesh& deformed,
                             ShellMaterial material, BendingModel model) {
  material.bending_model = model;
  return EvaluateDeformationEnergy(
      ShellSpace(reference.mesh, reference.topology, material),
      reference.mesh.positions, deformed.positions);
}

int RunEnergy() {
  const auto [reference, deformed] =
      LoadShellPair(FLAGS_reference, FLAGS_deformed);
  const std::string requested = FLAGS_bending;
  const bool both = requested == kBoth;
  const bool edge_angles = requested == kEdgeAngles;
  BendingModel model;
  if (!both && !edge_angles && !ParseBendingModel(requested, &model)) {
    throw InputError("--bending: unknown bending model '" + requested +
                     "' (discrete-shells, shape-operator, " + kEdgeAngles +
                     " or both)");
  }
  // The element-set model behind the report: discrete-shells for "both",
  // shape-operator (its alpha, beta and membrane) for the variant.
  if (both) FLAGS_bending = BendingModelName(BendingModel::kDiscreteShells);
  if (edge_angles) FLAGS_bending = BendingModelName(BendingModel::kShapeOperator);
  const workflows::MaterialChoice material =
      MaterialChoiceFromFlags(reference.mesh);
  const ShellSpace space(reference.mesh, reference.topology, material.material);
  FLAGS_bending = requested;
  DeformationEnergy e = EvaluateDeformationEnergy(
      space, reference.mesh.positions, deformed.positions);
  DeformationEnergy so;
  EdgeAngleBending variant;
  RunStatus status("energy");
  if (both || edge_angles) {
    if (both) {
      so = EnergyWith(reference, deformed, space.material,
                      BendingModel::kShapeOperator);
    }
    EdgeAngleFitOptions options;
    options.alpha = space.material.shape_operator_alpha;
    options.beta = space.material.shape_operator_beta;
    variant = EvaluateEdgeAngleBending(reference.mesh, reference.topology,
                                       reference.mesh.positions,
                                       deformed.positions, options);
    status.Require(variant.reference.converged,
                   "edge angles of the reference: " + variant.reference.message);
    status.Require(variant.deformed.converged,
                   "edge angles of the deformed shell: " +
                       variant.deformed.message);
    if (edge_angles) {
      e.bending = variant.energy;
      e.total = e.membrane + space.material.eta * e.bending;
    }
  }
  if (FLAGS_json) {
    JsonObject json = EnergyJson(e, space.material);
    json.Add("bending_model", requested)
        .Add("material",
             workflows::MaterialChoiceJson(material, reference.mesh));
    if (both) {
      json.Add("bending_models", JsonObject()
                                     .Add("discrete-shells", e.bending)
                                     .Add("shape-operator", so.bending)
                                     .Add(kEdgeAngles, variant.energy));
    }
    if (both || edge_angles) {
      json.Add("edge_angles", EdgeAngleBendingJson(variant));
    }
    std::cout << json.str() << "\n";
  } else if (both) {
    std::printf(
        "W_mem  %.12g\nW_bend %.12g (discrete-shells)\nW_bend %.12g "
        "(shape-operator)\nW_bend %.12g (%s, %d + %d iterations)\n"
        "W      %.12g  (eta = %g, discrete-shells)\n",
        e.membrane, e.bending, so.bending, variant.energy, kEdgeAngles,
        variant.reference.iterations, variant.deformed.iterations, e.total,
        space.material.eta);
  } else {
    std::printf("W_mem  %.12g\nW_bend %.12g\nW      %.12g  (eta = %g, %s)\n",
                e.membrane, e.bending, e.total, space.material.eta,
                requested.c_str());
  }
  return status.Finish();
}

}  // namespace
}  // namespace shellspace

SHELLSPACE_REGISTER_VERB(
    "energy",
    "energy --reference R.ply --deformed D.ply [--mu 1 --lambda 1 --eta 0.01] "
    "[--bending discrete-shells|shape-operator|shape-operator-edge-angles|both] "
    "[--json]",
    shellspace::EnergyFlags(), shellspace::RunEnergy);
