// Writes a second pose of a mesh for the stress corpus:
//   stress_pose INPUT KIND STRENGTH SEED OUTPUT [norigid]
// KIND bend|twist|pull|rigid, STRENGTH degrees (bend, twist, rigid) or a
// fraction of the bounding-box diagonal (pull), SEED the rigid motion's
// (geometry/stress_deformations.h: DeformForCorpus; every kind but rigid is
// followed by a random rigid motion of 30 degrees unless `norigid`).
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>

#include "shellspace/geometry/stress_deformations.h"
#include "shellspace/io/mesh_io.h"

int main(int argc, char** argv) {
  if (argc != 6 && argc != 7) {
    std::fprintf(stderr,
                 "usage: stress_pose INPUT bend|twist|pull|rigid STRENGTH "
                 "SEED OUTPUT [norigid]\n");
    return 2;
  }
  try {
    shellspace::Mesh mesh = shellspace::ReadMesh(argv[1]);
    const bool rigid = argc == 6 || std::string(argv[6]) != "norigid";
    mesh.positions = shellspace::DeformForCorpus(
        mesh.positions, argv[2], std::strtod(argv[3], nullptr), rigid,
        std::strtoull(argv[4], nullptr, 10));
    shellspace::WriteMesh(mesh, argv[5]);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "stress_pose: %s\n", e.what());
    return 1;
  }
  return 0;
}
