// `shellspace energy`: W_mem, W_bend and W of a (reference, deformed) pair.
#include <gflags/gflags.h>

#include <cstdio>
#include <iostream>

#include "shellspace/cost_functions/shell/deformation_energy.h"
#include "shellspace/tools/common_flags.h"
#include "shellspace/reports/shape_reports.h"
#include "shellspace/tools/shell_inputs.h"
#include "shellspace/tools/verb.h"

DEFINE_string(deformed, "", "energy: deformed shell");

namespace shellspace {
namespace {

// The material flags, --bending also accepting "both".
FlagTable EnergyMaterialFlags() {
  FlagTable table = MaterialFlags();
  for (FlagSpec& spec : table) {
    if (spec.name == "bending") {
      spec.meaning =
          "bending model: discrete-shells (default), shape-operator, or both "
          "(W_bend of each model reported; total and membrane from "
          "discrete-shells)";
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
                },
                EnergyMaterialFlags(), JsonFlag()});
}

int RunEnergy() {
  const Shell reference = LoadShell(FLAGS_reference);
  const Mesh deformed = LoadCompatibleShell(FLAGS_deformed, reference);
  const bool both = FLAGS_bending == "both";
  if (both) FLAGS_bending = BendingModelName(BendingModel::kDiscreteShells);
  const ShellSpace space = SpaceFromFlags(reference);
  const DeformationEnergy e = EvaluateDeformationEnergy(
      space, reference.mesh.positions, deformed.positions);
  DeformationEnergy so;
  if (both) {
    ShellMaterial material = space.material;
    material.bending_model = BendingModel::kShapeOperator;
    so = EvaluateDeformationEnergy(
        ShellSpace(reference.mesh, reference.topology, material),
        reference.mesh.positions, deformed.positions);
  }
  if (FLAGS_json) {
    JsonObject json = EnergyJson(e, space.material);
    json.Add("bending_model", both ? "both" : FLAGS_bending);
    if (both) {
      json.Raw("bending_models",
               JsonObject()
                   .Add("discrete-shells", e.bending)
                   .Add("shape-operator", so.bending)
                   .str());
    }
    std::cout << json.str() << "\n";
  } else if (both) {
    std::printf(
        "W_mem  %.12g\nW_bend %.12g (discrete-shells)\nW_bend %.12g "
        "(shape-operator)\nW      %.12g  (eta = %g, discrete-shells)\n",
        e.membrane, e.bending, so.bending, e.total, space.material.eta);
  } else {
    std::printf("W_mem  %.12g\nW_bend %.12g\nW      %.12g  (eta = %g, %s)\n",
                e.membrane, e.bending, e.total, space.material.eta,
                FLAGS_bending.c_str());
  }
  return 0;
}

}  // namespace
}  // namespace shellspace

SHELLSPACE_REGISTER_VERB(
    "energy",
    "energy --reference R.ply --deformed D.ply [--mu 1 --lambda 1 --eta 0.01] "
    "[--bending discrete-shells|shape-operator|both] [--json]",
    shellspace::EnergyFlags(), shellspace::RunEnergy);
