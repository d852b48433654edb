#include "shellspace/problems/branching/km_family.h"

#include <cmath>

namespace shellspace::branching {

namespace {
InterfaceCurve Line(double start, double slope, int jump) {
  InterfaceCurve c;
  c.jump = jump;
  c.position = [start, slope](double s) { return start + slope * s; };
  c.velocity = [slope](double) { return slope; };
  return c;
}
}  // namespace

CellPattern NeedleCellPattern() {
  CellPattern pattern;
  pattern.family = "needle";
  pattern.r = 2;
  pattern.next_offset = 0.0;
  pattern.interfaces = {Line(0.25, -0.125, 2), Line(0.5, -0.125, -2),
                        Line(0.5, 0.125, 2), Line(0.75, 0.125, -2)};
  return pattern;
}

CellPattern KmCellPattern() {
  CellPattern pattern;
  pattern.family = "km";
  pattern.r = 2;
  pattern.next_offset = 0.25;
  pattern.interfaces = {Line(0.25, 0.0, 2), Line(0.75, -0.25, -2),
                        Line(0.75, 0.0, 2), Line(0.75, 0.25, -2)};
  return pattern;
}

double KmOptimalTheta() { return 0.5 - std::sin(M_PI / 18.0); }

double R2ConstantAt(double AB2, double theta) {
  const double f = 4.0 * theta * (1.0 - theta) /
                   ((4.0 * theta - 1.0) * (1.0 - 2.0 * theta) *
                    (1.0 - 2.0 * theta));
  return 3.0 * std::pow(2.0, -2.0 / 3.0) * std::cbrt(AB2 * f);
}

double KmClosedFormConstant() { return 3.0 * (1.0 + 2.0 * std::cos(M_PI / 9.0)); }

double KmShiftedClosedFormConstant() {
  return std::cbrt(2.0 / 3.0) * KmClosedFormConstant();
}

double NeedleClosedFormConstant() {
  return KmClosedFormConstant() / std::cbrt(2.0);
}

}  // namespace shellspace::branching
