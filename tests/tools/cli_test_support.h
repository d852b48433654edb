// The preamble of the CLI tests (tests/tools/): the helpers of tests/testing/
// they call unqualified, and the two meshes most of them run on. A test-only
// header: it declares these names in namespace shellspace.
#ifndef SHELLSPACE_TESTS_TOOLS_CLI_TEST_SUPPORT_H_
#define SHELLSPACE_TESTS_TOOLS_CLI_TEST_SUPPORT_H_

#include <string>

#include "tests/testing/cli_output.h"
#include "tests/testing/test_support.h"

namespace shellspace {

using testing::Bool;
using testing::DataPath;
using testing::DirectoryListing;
using testing::Frames;
using testing::FramesAndSummary;
using testing::Number;
using testing::Numbers;
using testing::RunCli;
using testing::RunOk;
using testing::Slurp;
using testing::TempDir;

// simple/square4.ply and simple/square4_bent.ply (testing::Square4,
// testing::Square4Bent) as paths for the command line.
inline const std::string kSquare = testing::Square4();
inline const std::string kBent = testing::Square4Bent();

}  // namespace shellspace

#endif  // SHELLSPACE_TESTS_TOOLS_CLI_TEST_SUPPORT_H_
