#include "shellspace/geometry/memory_limits.h"

#include <unistd.h>

#include <cstdio>

#include "shellspace/geometry/mesh.h"

namespace shellspace {
namespace {

std::string Gigabytes(double bytes) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.3g GB", bytes / 1e9);
  return text;
}

}  // namespace

double MemoryLimitBytes() {
  const long pages = ::sysconf(_SC_PHYS_PAGES);
  const long page = ::sysconf(_SC_PAGE_SIZE);
  if (pages <= 0 || page <= 0) return 4e9;  // unknown: 4 GB
  return 0.5 * static_cast<double>(pages) * static_cast<double>(page);
}

double GeodesicBytes(int vertices, int steps) {
  const double v = vertices, k = steps;
  return 64e6 + 1500.0 * v * k * k;
}

double PathBytes(int vertices, int frames) {
  return 64e6 + 200.0 * static_cast<double>(vertices) * frames;
}

double SplineBytes(int vertices, int steps) {
  const double v = vertices, shapes = static_cast<double>(steps) + 1;
  return 64e6 + 24.0 * shapes * shapes + 20e3 * v * shapes;
}

double BranchingBytes(double nodes) { return 16e6 + 3000.0 * nodes; }

void CheckMemory(double estimate, const std::string& what,
                 const std::string& model) {
  const double limit = MemoryLimitBytes();
  if (estimate <= limit) return;
  throw InputError(what + " needs about " + Gigabytes(estimate) + " (" +
                   model + "), above the limit " + Gigabytes(limit) +
                   " (half the physical memory)");
}

std::string FilmStripBoundText() {
  return std::string("; the strip's estimated memory, ") + kFilmStripModel +
         ", within half the physical memory (" +
         Gigabytes(MemoryLimitBytes()) + " here)";
}

std::string StepsBoundText(const std::string& model) {
  return "; at most " + std::to_string(kMaxSteps) +
         " and an estimated memory of " + model +
         " within half the physical memory (" + Gigabytes(MemoryLimitBytes()) +
         " here)";
}

}  // namespace shellspace
