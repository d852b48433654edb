// `branching construct --family general` as both front ends (the CLI verb,
// the Python function) ask for it: the search options from their values,
// checked, and the construction itself -- the multi-start search over
// topologies, or one solve of the lens topology -- timed.
#ifndef SHELLSPACE_PROBLEMS_BRANCHING_GENERAL_CONSTRUCTION_H_
#define SHELLSPACE_PROBLEMS_BRANCHING_GENERAL_CONSTRUCTION_H_

#include <functional>
#include <string>
#include <vector>

#include "shellspace/problems/branching/general_search.h"

namespace shellspace::branching {

// The lens topology in the general model: one group, needles in the middle
// of both lamellae, all interfaces free; `subintervals` linear pieces per
// segment.
GeneralTopology LensTopology(int subintervals);

// The search options of the front ends' values (the other options keep
// their defaults): subintervals in [1, 16], search_pairs (max_pairs) in
// [1, 2], search_starts (starts_per_topology) >= 0, search_threads
// (num_threads) >= 1, then search_ratios, a comma-separated list of 2, 3
// and 4 such as "2,3,4" (ratios), and search_filter (filter). Throws
// InputError for the first value out of range, naming it by these names.
GeneralSearchOptions MakeGeneralSearchOptions(
    const std::string& search_ratios, int search_pairs, int subintervals,
    int search_starts, int search_threads, const std::string& search_filter);

struct GeneralConstruction {
  GeneralResult best;
  int solves = 1;        // LM solves (1 without the search)
  double seconds = 0.0;  // wall-clock time of the search or the solve
};

// With `search`: SearchGeneral(options, progress); without: one solve of
// LensTopology(options.subintervals) from the clean start (progress is not
// called). Throws InputError if no valid pattern was found.
GeneralConstruction ConstructGeneral(
    const GeneralSearchOptions& options, bool search,
    const std::function<void(const GeneralResult&)>& progress = nullptr);

}  // namespace shellspace::branching

#endif  // SHELLSPACE_PROBLEMS_BRANCHING_GENERAL_CONSTRUCTION_H_
