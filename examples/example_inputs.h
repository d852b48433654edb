// What the examples share: reading two poses of one shell from files, with
// the checks the CLI makes (geometry/validation.h), and main's error
// handling. Header-only, so each
// example stays one translation unit.
#ifndef SHELLSPACE_EXAMPLES_EXAMPLE_INPUTS_H_
#define SHELLSPACE_EXAMPLES_EXAMPLE_INPUTS_H_

#include <shellspace/geometry/topology.h>
#include <shellspace/geometry/validation.h>
#include <shellspace/io/mesh_io.h>

#include <cstdio>
#include <exception>

namespace examples {

// The first shell (validated), the second one's positions (the first's
// connectivity, validated), and the topology they share.
struct TwoPoses {
  shellspace::Mesh first;
  shellspace::Positions second;
  shellspace::Topology topology;
};

inline TwoPoses ReadTwoPoses(const char* first_path, const char* second_path) {
  TwoPoses poses;
  poses.first = shellspace::ReadMesh(first_path);
  poses.topology = shellspace::ValidateShell(poses.first, first_path);
  const shellspace::Mesh second = shellspace::ReadMesh(second_path);
  shellspace::CheckCompatible(poses.first, first_path, second, second_path);
  shellspace::ValidateShellPositions(second, poses.topology, second_path);
  poses.second = second.positions;
  return poses;
}

// The command line of an example: from min_args to max_args arguments
// (the program's name not counted), described by `text`.
struct Usage {
  int min_args;
  int max_args;
  const char* text;
};

// main's body for every example: "usage: PROGRAM text" and exit 2 for a
// wrong argument count, else Run(argc, argv), with a library error
// (shellspace::InputError, one line naming the input) printed as that line
// and exit 1.
template <typename RunFunction>
int Main(RunFunction run, const Usage& usage, int argc, char** argv) {
  if (argc - 1 < usage.min_args || argc - 1 > usage.max_args) {
    std::fprintf(stderr, "usage: %s %s\n", argv[0], usage.text);
    return 2;
  }
  try {
    return run(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 1;
  }
}

}  // namespace examples

#endif  // SHELLSPACE_EXAMPLES_EXAMPLE_INPUTS_H_
