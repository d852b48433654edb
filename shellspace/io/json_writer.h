// A minimal JSON object writer for the verbs' --json summaries.
#ifndef SHELLSPACE_IO_JSON_WRITER_H_
#define SHELLSPACE_IO_JSON_WRITER_H_

#include <cmath>
#include <cstdio>
#include <sstream>
#include <string>
#include <vector>

namespace shellspace {

// Builds one JSON object with keys in insertion order. Numbers are printed
// with 17 significant digits; non-finite numbers as null.
class JsonObject {
 public:
  JsonObject& Add(const std::string& key, double value) {
    return Raw(key, Number(value));
  }
  JsonObject& Add(const std::string& key, int value) {
    return Raw(key, std::to_string(value));
  }
  JsonObject& Add(const std::string& key, bool value) {
    return Raw(key, value ? "true" : "false");
  }
  JsonObject& Add(const std::string& key, const std::string& value) {
    return Raw(key, Quote(value));
  }
  JsonObject& Add(const std::string& key, const char* value) {
    return Raw(key, Quote(value));
  }
  JsonObject& Add(const std::string& key, const std::vector<double>& values) {
    std::string s = "[";
    for (size_t i = 0; i < values.size(); ++i) {
      s += (i ? ", " : "") + Number(values[i]);
    }
    return Raw(key, s + "]");
  }
  JsonObject& Add(const std::string& key,
                  const std::vector<std::string>& values) {
    std::string s = "[";
    for (size_t i = 0; i < values.size(); ++i) {
      s += (i ? ", " : "") + Quote(values[i]);
    }
    return Raw(key, s + "]");
  }
  JsonObject& Add(const std::string& key, const JsonObject& object) {
    return Raw(key, object.str());
  }
  // `value` must already be valid JSON.
  JsonObject& Raw(const std::string& key, const std::string& value) {
    body_ += (body_.empty() ? "" : ", ") + Quote(key) + ": " + value;
    return *this;
  }
  std::string str() const { return "{" + body_ + "}"; }

  static std::string Number(double value) {
    if (!std::isfinite(value)) return "null";
    char buffer[64];
    std::snprintf(buffer, sizeof(buffer), "%.17g", value);
    return buffer;
  }
  static std::string Quote(const std::string& s) {
    std::string out = "\"";
    for (char c : s) {
      if (c == '"' || c == '\\') out += '\\';
      if (c == '\n') {
        out += "\\n";
        continue;
      }
      out += c;
    }
    return out + "\"";
  }

 private:
  std::string body_;
};

}  // namespace shellspace

#endif  // SHELLSPACE_IO_JSON_WRITER_H_
