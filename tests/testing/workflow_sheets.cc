#include "tests/testing/workflow_sheets.h"

#include "shellspace/cost_functions/shell/relative_bending_weight.h"
#include "shellspace/geometry/procedural_shapes.h"
#include "shellspace/geometry/topology.h"
#include "shellspace/problems/statistics/shell_pca.h"

namespace shellspace::testing {

workflows::MaterialChoice DefaultMaterial(const Mesh& reference) {
  workflows::MaterialChoice choice;
  choice.material.eta = EtaFromRelative(kDefaultRelativeEta, reference);
  return choice;
}

SolverSettings DefaultSettings() {
  return UserSolverSettings(1e-8, 200, 2, /*quiet=*/true, "test");
}

Mesh Sheet() { return MakeEquilateralSheet(6, 4, 0.25); }

workflows::GeodesicOptions BentSheetGeodesic() {
  workflows::GeodesicOptions options;
  options.start = Sheet();
  options.topology = Topology::Build(options.start);
  options.end = RollOntoCylinder(options.start.positions, 0.6);
  options.steps = 4;
  options.material = DefaultMaterial(options.start);
  options.settings = DefaultSettings();
  return options;
}

workflows::PcaOptions FourSheets() {
  workflows::PcaOptions options;
  options.reference = Sheet();
  options.topology = Topology::Build(options.reference);
  options.shapes = {options.reference.positions};
  for (const double radius : {0.6, 1.0, 2.0}) {
    options.shapes.push_back(
        RollOntoCylinder(options.reference.positions, radius));
  }
  options.material = DefaultMaterial(options.reference);
  options.modes = 1;
  // The CLI's --log_steps 2 --exp_steps 4 --max_exp_steps 16.
  options.pca = MakeShellPcaOptions(2, 4, 16, DisplacementKind::kLog);
  options.settings = DefaultSettings();
  return options;
}

workflows::MeanOptions MeanOfFourSheets() {
  const workflows::PcaOptions sheets = FourSheets();
  workflows::MeanOptions options;
  options.reference = sheets.reference;
  options.topology = sheets.topology;
  options.shapes = sheets.shapes;
  options.material = sheets.material;
  options.settings = sheets.settings;
  return options;
}

}  // namespace shellspace::testing
