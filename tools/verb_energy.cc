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
                MaterialFlags(), JsonFlag()});
}

int RunEnergy() {
  const Shell reference = LoadShell(FLAGS_reference);
  const Mesh deformed = LoadCompatibleShell(FLAGS_deformed, reference);
  const ShellSpace space = SpaceFromFlags(reference);
  const DeformationEnergy e = EvaluateDeformationEnergy(
      space, reference.mesh.positions, deformed.positions);
  if (FLAGS_json) {
    std::cout << EnergyJson(e, space.material).str() << "\n";
  } else {
    std::printf("W_mem  %.12g\nW_bend %.12g\nW      %.12g  (eta = %g)\n",
                e.membrane, e.bending, e.total, space.material.eta);
  }
  return 0;
}

}  // namespace
}  // namespace shellspace

SHELLSPACE_REGISTER_VERB(
    "energy",
    "energy --reference R.ply --deformed D.ply [--mu 1 --lambda 1 --eta 0.01] "
    "[--json]",
    shellspace::EnergyFlags(), shellspace::RunEnergy);
