#include "tests/testing/cli_output.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <system_error>

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

std::string Square4Geodesic(int steps, const std::string& output) {
  return "geodesic --quiet --steps " + std::to_string(steps) + " --start " +
         Square4() + " --end " + Square4Bent() + " --output " + output;
}

std::string RunOk(const std::string& args) {
  std::string out, err;
  EXPECT_EQ(RunCli(args, &out, &err), 0) << args << "\n" << err;
  return out;
}

std::map<std::string, std::string> FileTreeSnapshot(const std::string& dir) {
  namespace fs = std::filesystem;
  std::map<std::string, std::string> files;
  const auto describe = [](const fs::path& path) {
    std::error_code error;
    const fs::file_status status = fs::symlink_status(path, error);
    std::ostringstream text;
    if (fs::is_symlink(status)) {
      text << "link -> " << fs::read_symlink(path, error).string();
      return text.str();
    }
    text << "mtime "
         << fs::last_write_time(path, error).time_since_epoch().count();
    if (fs::is_regular_file(status)) {
      std::ifstream in(path, std::ios::binary);
      std::ostringstream bytes;
      bytes << in.rdbuf();
      const std::string content = bytes.str();
      uint64_t hash = 1469598103934665603ull;
      for (unsigned char c : content) hash = (hash ^ c) * 1099511628211ull;
      text << " size " << content.size() << " fnv " << hash << " " << content;
    } else {
      text << " <dir>";
    }
    return text.str();
  };
  files[dir] = describe(dir);
  for (const auto& entry : fs::recursive_directory_iterator(dir)) {
    files[entry.path().string()] = describe(entry.path());
  }
  return files;
}

void ExpectRejected(const std::string& args, const std::string& name,
                    const std::string& dir) {
  SCOPED_TRACE(args);
  const auto before = FileTreeSnapshot(dir);
  std::string err;
  const int code = RunCli(args, nullptr, &err);
  EXPECT_NE(code, 0);
  EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1) << err;
  EXPECT_NE(err.find(name), std::string::npos) << err;
  EXPECT_EQ(FileTreeSnapshot(dir), before) << "files created or changed";
}

}  // namespace shellspace::testing
