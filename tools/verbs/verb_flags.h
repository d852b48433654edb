// The flags of one verb: each verb's table lists the gflags it reads, with
// their meaning in that verb (one flag name may mean different things in two
// verbs: `--epsilon` is the transport step of `transport` and the
// twin-boundary energy of `branching`), the verb's default if it differs
// from the gflags one, and the valid range of a numeric flag. main.cc
// rejects any flag set on the command line that is not in the verb's table,
// applies the verb's defaults, checks the required flags and the ranges,
// and prints the table for `shellspace VERB --help`.
#ifndef SHELLSPACE_TOOLS_VERBS_VERB_FLAGS_H_
#define SHELLSPACE_TOOLS_VERBS_VERB_FLAGS_H_

#include <functional>
#include <initializer_list>
#include <limits>
#include <string>
#include <utility>
#include <vector>

namespace shellspace {

struct FlagSpec {
  std::string name;     // the gflags name, without "--"
  std::string meaning;  // what the flag does in this verb
  std::string range;    // numeric flags: the valid values, e.g. ">= 1"
  // Numeric flags: true if a finite value is valid (`range` in words).
  std::function<bool(double)> valid;
  std::string verb_default;  // this verb's default; "" keeps the gflags one
  bool required = false;     // a string flag that must be non-empty
  // String flags: throws InputError with a one-line message (without the
  // flag's name) if the value is not valid; main runs it on the flag's value
  // before the verb runs, so a bad value fails before any work.
  std::function<void(const std::string&)> check;

  FlagSpec& Required() {
    required = true;
    return *this;
  }
  FlagSpec& Default(const std::string& value) {
    verb_default = value;
    return *this;
  }
  // What --help prints as the default, for a flag whose gflags default is a
  // "not given" sentinel (e.g. --eta: -1, "relative_eta x area").
  std::string shown_default;
  FlagSpec& ShownDefault(const std::string& text) {
    shown_default = text;
    return *this;
  }
  FlagSpec& Check(std::function<void(const std::string&)> test) {
    check = std::move(test);
    return *this;
  }
};

using FlagTable = std::vector<FlagSpec>;

// A library default as a flag's verb_default (FlagSpec::Default), so that a
// flag's default is taken from the library's Options or settings struct
// rather than written twice: an integer in decimal, a real as the shortest
// "%g" text that reads back to the same double (1e-08, 0.0001, 1), a word
// as it is.
std::string FlagDefault(int value);
std::string FlagDefault(double value);
std::string FlagDefault(const std::string& value);
// "true" or "false" (a name of its own: a string literal would convert to
// bool before std::string).
std::string BoolFlagDefault(bool value);

// A string or boolean flag (no range).
FlagSpec TextFlag(const std::string& name, const std::string& meaning);

// An integer flag in [min, max].
FlagSpec IntegerFlag(const std::string& name, const std::string& meaning,
                     long min, long max = std::numeric_limits<int>::max());

// A real flag in the interval from min to max, each end open or closed
// (infinite ends are open).
enum class End { kOpen, kClosed };
FlagSpec RealFlag(const std::string& name, const std::string& meaning,
                  double min, End min_end,
                  double max = std::numeric_limits<double>::infinity(),
                  End max_end = End::kOpen);

// A numeric flag with a validity test of its own, described by `range`.
FlagSpec CheckedFlag(const std::string& name, const std::string& meaning,
                     const std::string& range,
                     std::function<bool(double)> valid);

// Tables concatenated (a verb's own flags plus shared groups).
FlagTable Flags(std::initializer_list<FlagTable> parts);

// Shared groups, each flag with the same meaning in every verb using it.
FlagTable MaterialFlags();  // --mu, --lambda, --eta, --bending
// --tolerance, --max_iterations, --threads, --quiet, --time_limit
FlagTable SolverFlags();
FlagSpec TimeLimitFlag();  // --time_limit (tools/run/stop_request.h)
FlagTable JsonFlag();       // --json
// --allow_unconverged (and --allow_unsolved for the EXP-step verbs); the
// flags themselves and what they change are tools/run/run_status.h's.
FlagSpec AllowUnconvergedFlag();
FlagSpec AllowUnsolvedFlag();

// The flag of `table` called `name`, or nullptr.
const FlagSpec* FindFlag(const FlagTable& table, const std::string& name);

}  // namespace shellspace

#endif  // SHELLSPACE_TOOLS_VERBS_VERB_FLAGS_H_
