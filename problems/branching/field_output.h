// Writing the results of a relaxed simulation: the field u as CSV, a PNG of
// u_y (two colours, interfaces visible), and the interface counts per column.
#ifndef SHELLSPACE_PROBLEMS_BRANCHING_FIELD_OUTPUT_H_
#define SHELLSPACE_PROBLEMS_BRANCHING_FIELD_OUTPUT_H_

#include <string>
#include <vector>

#include "shellspace/problems/branching/relaxed_grid.h"
#include "shellspace/io/png_writer.h"

namespace shellspace::branching {

// u_y drawn over (0, L) x [0, H) in physical proportions of x (graded grids
// are resampled): x to the right (austenite at the left edge), y upward;
// u_y = +1 orange, -1 blue, blended to white as |u_y| -> 0 so the diffuse
// interfaces show as light lines.
RgbImage RenderSlope(const RelaxedField& field, int width_px, int height_px);

// Writes `text` to `path` atomically (temporary file + rename); InputError
// if it cannot be written.
void WriteTextFile(const std::string& path, const std::string& text);

// "i,j,x,y,u,u_y" per node (u_y: the staggered slope to node j + 1).
std::string FieldCsv(const RelaxedField& field);

// "i,x,interfaces" per node row i >= 1.
std::string InterfaceCsv(const RelaxedField& field,
                         const std::vector<int>& counts);

}  // namespace shellspace::branching

#endif  // SHELLSPACE_PROBLEMS_BRANCHING_FIELD_OUTPUT_H_
