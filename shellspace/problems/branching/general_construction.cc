#include "shellspace/problems/branching/general_construction.h"

#include <chrono>
#include <sstream>

#include "shellspace/geometry/mesh.h"

namespace shellspace::branching {

GeneralTopology LensTopology(int subintervals) {
  GeneralTopology t;
  t.pairs = 1;
  t.r = 3;
  t.subintervals = subintervals;
  t.name = "lens";
  NucleationGroup group;
  group.tau = 0.5;
  group.needles = {{0, 0.5}, {1, 0.5}};
  t.groups = {group};
  return t;
}

namespace {

// The ratios r of a comma-separated list such as "2,3,4" (each 2, 3 or 4).
// Throws InputError naming `name` if an entry is anything else or the list
// is empty.
std::vector<int> ParseRefinementRatios(const std::string& list,
                                       const std::string& name) {
  std::vector<int> ratios;
  std::stringstream in(list);
  std::string item;
  while (std::getline(in, item, ',')) {
    if (item != "2" && item != "3" && item != "4") {
      throw InputError(name + " must be a list of 2, 3, 4");
    }
    ratios.push_back(std::stoi(item));
  }
  if (ratios.empty()) throw InputError(name + " is empty");
  return ratios;
}

}  // namespace

GeneralSearchOptions MakeGeneralSearchOptions(
    const std::string& search_ratios, int search_pairs, int subintervals,
    int search_starts, int search_threads, const std::string& search_filter) {
  if (subintervals < 1 || subintervals > 16) {
    throw InputError("subintervals must lie in [1, 16]");
  }
  if (search_pairs < 1 || search_pairs > 2) {
    throw InputError("search_pairs must be 1 or 2");
  }
  if (search_starts < 0 || search_threads < 1) {
    throw InputError("search_starts must be >= 0, search_threads >= 1");
  }
  GeneralSearchOptions options;
  options.ratios =
      ParseRefinementRatios(search_ratios, "search_ratios");
  options.max_pairs = search_pairs;
  options.subintervals = subintervals;
  options.starts_per_topology = search_starts;
  options.num_threads = search_threads;
  options.filter = search_filter;
  return options;
}

GeneralConstruction ConstructGeneral(
    const GeneralSearchOptions& options, bool search,
    const std::function<void(const GeneralResult&)>& progress) {
  GeneralConstruction out;
  const auto start = std::chrono::steady_clock::now();
  if (search) {
    const GeneralSearchResult r = SearchGeneral(options, progress);
    out.best = r.best;
    out.solves = r.solves;
  } else {
    out.best = SolveGeneral(LensTopology(options.subintervals), 0.0, 0.0, 1);
  }
  out.seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start)
          .count();
  if (!out.best.ok) {
    throw InputError("general construct: no valid pattern found");
  }
  return out;
}

}  // namespace shellspace::branching
