// Reading what the CLI printed and wrote, for the CLI tests: values of its
// --json object (flat key lookup, the first occurrence of a key), frame
// names of an output directory, file contents, snapshots of a directory
// tree (a refused run changes nothing).
#ifndef SHELLSPACE_TESTS_TESTING_CLI_OUTPUT_H_
#define SHELLSPACE_TESTS_TESTING_CLI_OUTPUT_H_

#include <map>
#include <string>
#include <vector>

namespace shellspace::testing {

// The number after "KEY": in `json`; NaN if absent.
double Number(const std::string& json, const std::string& key);
// The numbers after every "KEY": in `json`, in order (e.g. one field of
// each object of an array).
std::vector<double> EveryNumber(const std::string& json,
                                const std::string& key);
// True if `json` holds "KEY": true.
bool Bool(const std::string& json, const std::string& key);
// The numbers of the array "KEY": [...] (empty if absent).
std::vector<double> Numbers(const std::string& json, const std::string& key);

// shape_000.ply ... shape_{count-1}.ply.
std::vector<std::string> Frames(int count);
// Frames(count) and summary.json: the listing of a path verb's output
// directory.
std::vector<std::string> FramesAndSummary(int count);

// The whole content of a file ("" if it cannot be read).
std::string Slurp(const std::string& path);

// The two meshes most CLI tests run on: simple/square4.ply (a flat 3 x 3
// vertex square) and simple/square4_bent.ply (the same square bent).
std::string Square4();
std::string Square4Bent();

// `geodesic --quiet --steps STEPS --start Square4() --end Square4Bent()
// --output OUTPUT`, for the caller to append further flags.
std::string Square4Geodesic(int steps, const std::string& output);

// Runs `shellspace ARGS` (RunCli), expects exit 0 (a failed expectation
// prints the arguments and stderr) and returns its stdout.
std::string RunOk(const std::string& args);

// Every file and directory under `dir` (recursively, `dir` included):
// type, size, modification time (ns) and, for a file, a hash of its
// content (FNV-1a, 64 bits) and the content itself; a symbolic link by its
// target.
std::map<std::string, std::string> FileTreeSnapshot(const std::string& dir);

// Runs `shellspace ARGS` (RunCli); expects a non-zero exit, one stderr line
// containing `name`, and `dir` unchanged (FileTreeSnapshot before and
// after).
void ExpectRejected(const std::string& args, const std::string& name,
                    const std::string& dir);

}  // namespace shellspace::testing

#endif  // SHELLSPACE_TESTS_TESTING_CLI_OUTPUT_H_
