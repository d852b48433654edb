#include "tests/testing/cli_output.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>

#include "tests/testing/test_support.h"

namespace shellspace::testing {

double Number(const std::string& json, const std::string& key) {
  const std::string needle = "\"" + key + "\": ";
  const auto at = json.find(needle);
  if (at == std::string::npos) return std::nan("");
  return std::strtod(json.c_str() + at + needle.size(), nullptr);
}

std::vector<double> EveryNumber(const std::string& json,
                                const std::string& key) {
  const std::string needle = "\"" + key + "\": ";
  std::vector<double> values;
  for (auto at = json.find(needle); at != std::string::npos;
       at = json.find(needle, at + 1)) {
    values.push_back(std::strtod(json.c_str() + at + needle.size(), nullptr));
  }
  return values;
}

bool Bool(const std::string& json, const std::string& key) {
  return json.find("\"" + key + "\": true") != std::string::npos;
}

std::vector<double> Numbers(const std::string& json, const std::string& key) {
  const std::string needle = "\"" + key + "\": [";
  const auto at = json.find(needle);
  std::vector<double> values;
  if (at == std::string::npos) return values;
  const auto end = json.find(']', at);
  std::string body = json.substr(at + needle.size(), end - at - needle.size());
  for (char& c : body) {
    if (c == ',') c = ' ';
  }
  std::istringstream in(body);
  for (double v; in >> v;) values.push_back(v);
  return values;
}

std::vector<std::string> Frames(int count) {
  std::vector<std::string> names;
  for (int k = 0; k < count; ++k) {
    char name[32];
    std::snprintf(name, sizeof(name), "shape_%03d.ply", k);
    names.push_back(name);
  }
  return names;
}

std::vector<std::string> FramesAndSummary(int count) {
  std::vector<std::string> names = Frames(count);
  names.push_back("summary.json");
  return names;
}

std::string Slurp(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string Square4() { return DataPath("simple/square4.ply"); }
std::string Square4Bent() { return DataPath("simple/square4_bent.ply"); }

std::string RunOk(const std::string& args) {
  std::string out, err;
  EXPECT_EQ(RunCli(args, &out, &err), 0) << args << "\n" << err;
  return out;
}

}  // namespace shellspace::testing
