// `shellspace example NAME --output DIR`: writes a procedural example set
// (geometry/example_poses.h) -- its poses as PLY files, its mask and its
// variation -- into DIR, whole or not at all, so that every command of the
// docs runs from a bare checkout.
#include <gflags/gflags.h>

#include <iostream>
#include <string>

#include "shellspace/geometry/example_poses.h"
#include "shellspace/io/atomic_file.h"
#include "shellspace/io/mesh_io.h"
#include "shellspace/io/output_directory.h"
#include "tools/run/common_flags.h"
#include "tools/run/run_paths.h"
#include "tools/verbs/verb.h"

namespace shellspace {
namespace {

FlagTable ExampleFlags() {
  return Flags({{
      TextFlag("output",
               "directory of the set's poses (PLY), its variation "
               "(NAME_var.ply, if any) and its mask (NAME_mask.txt)")
          .Required(),
      TextFlag("quiet", "no line on stdout"),
  }});
}

// Flags -> the set -> the directory.
int RunExample(const std::string& name) {
  RunPaths().OutputDirectory("output", FLAGS_output).Check();
  const ExampleSet set = MakeExampleSet(name);
  StagedDirectory output(FLAGS_output);
  std::string written;
  for (const auto& [shape, positions] : set.shapes) {
    WriteMesh(Mesh{positions, set.faces}, output.File(shape + ".ply"));
    written += " " + shape + ".ply";
  }
  if (!set.mask.empty()) {
    std::string mask = "# " + set.description + ": the vertices held\n";
    for (const int vertex : set.mask) mask += std::to_string(vertex) + "\n";
    const std::string file = set.name + "_mask.txt";
    WriteFileAtomically(output.File(file), mask);
    written += " " + file;
  }
  output.Commit();
  if (!FLAGS_quiet) {
    std::cout << "wrote " << FLAGS_output << "/:" << written << " ("
              << set.description << ", " << set.shapes[0].second.rows()
              << " vertices)\n";
  }
  return 0;
}

// One sub-command per set: `shellspace example finger`, ...
const bool kRegistered = [] {
  for (const auto& [name, description] : ExampleSetNames()) {
    VerbRegistrar("example " + name,
                  "example " + name + " --output DIR: " + description +
                      " (PLY poses, mask, variation)",
                  ExampleFlags(), [name = name] { return RunExample(name); });
  }
  return true;
}();

}  // namespace
}  // namespace shellspace
