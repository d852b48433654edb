// The procedural inputs of the workflow tests (tests/workflows/): a 6 x 4
// equilateral sheet of side 0.25 and the same sheet rolled onto cylinders,
// as the options of a geodesic, a PCA and a mean with the CLI's default
// material and settings.
#ifndef SHELLSPACE_TESTS_TESTING_WORKFLOW_SHEETS_H_
#define SHELLSPACE_TESTS_TESTING_WORKFLOW_SHEETS_H_

#include "shellspace/geometry/mesh.h"
#include "shellspace/solvers/solver_settings.h"
#include "shellspace/workflows/geodesic.h"
#include "shellspace/workflows/mean.h"
#include "shellspace/workflows/pca.h"

namespace shellspace::testing {

// The CLI's defaults: mu = lambda = 1, eta = 1e-4 x the reference's area,
// tolerance 1e-8, 200 iterations, 2 threads.
workflows::MaterialChoice DefaultMaterial(const Mesh& reference);
SolverSettings DefaultSettings();

// The bent sheet: a 6 x 4 equilateral sheet of side 0.25 and the same
// sheet rolled onto a cylinder of radius 0.6.
Mesh Sheet();
workflows::GeodesicOptions BentSheetGeodesic();

// Four shapes of the sheet: flat and rolled onto radii 0.6, 1.0 and 2.0.
workflows::PcaOptions FourSheets();

// The mean of the same four sheets, material and settings.
workflows::MeanOptions MeanOfFourSheets();

}  // namespace shellspace::testing

#endif  // SHELLSPACE_TESTS_TESTING_WORKFLOW_SHEETS_H_
