#include "shellspace/problems/branching/km_family.h"

#include <cmath>

namespace shellspace::branching {

CellPattern KmCellPattern() {
  CellPattern pattern;
  pattern.family = "km";
  pattern.r = 2;
  pattern.next_offset = 0.0;
  auto line = [](double start, double slope, int jump) {
    InterfaceCurve c;
    c.jump = jump;
    c.position = [start, slope](double s) { return start + slope * s; };
    c.velocity = [slope](double) { return slope; };
    return c;
  };
  pattern.interfaces = {line(0.25, -0.125, 2), line(0.5, -0.125, -2),
                        line(0.5, 0.125, 2), line(0.75, 0.125, -2)};
  return pattern;
}

double KmOptimalTheta() { return 0.5 - std::sin(M_PI / 18.0); }

double KmConstantAt(double theta) {
  const double f = 4.0 * theta * (1.0 - theta) /
                   ((4.0 * theta - 1.0) * (1.0 - 2.0 * theta) *
                    (1.0 - 2.0 * theta));
  return 3.0 * std::pow(2.0, -1.0 / 3.0) * std::cbrt(f);
}

double KmClosedFormConstant() { return KmConstantAt(KmOptimalTheta()); }

}  // namespace shellspace::branching
