// JSON values for the verbs' --json summaries: a tree (JsonValue) that the
// CLI prints (JsonObject::str) and the Python module converts to dicts and
// lists directly (python/module_common.h ToDict), without printing and
// parsing text.
#ifndef SHELLSPACE_IO_JSON_WRITER_H_
#define SHELLSPACE_IO_JSON_WRITER_H_

#include <cmath>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

namespace shellspace {

class JsonObject;

// One JSON value: null, a boolean, an integer, a number (non-finite numbers
// print as null), a string, an array, an object, or raw text (already valid
// JSON, printed as it is: for records a front end keeps as text; a reader of
// the tree parses it).
class JsonValue {
 public:
  enum class Kind {
    kNull,
    kBool,
    kInt,
    kNumber,
    kString,
    kArray,
    kObject,
    kRaw
  };

  JsonValue() = default;
  static JsonValue Bool(bool value) {
    JsonValue v(Kind::kBool);
    v.boolean_ = value;
    return v;
  }
  static JsonValue Int(long long value) {
    JsonValue v(Kind::kInt);
    v.integer_ = value;
    return v;
  }
  static JsonValue Number(double value) {
    JsonValue v(Kind::kNumber);
    v.number_ = value;
    return v;
  }
  static JsonValue String(std::string value) {
    JsonValue v(Kind::kString);
    v.text_ = std::move(value);
    return v;
  }
  static JsonValue Raw(std::string json) {
    JsonValue v(Kind::kRaw);
    v.text_ = std::move(json);
    return v;
  }
  static JsonValue Array(std::vector<JsonValue> items) {
    JsonValue v(Kind::kArray);
    v.items_ = std::move(items);
    return v;
  }
  static JsonValue Object(const JsonObject& object);

  Kind kind() const { return kind_; }
  bool boolean() const { return boolean_; }
  long long integer() const { return integer_; }
  double number() const { return number_; }
  // kString: the string; kRaw: the JSON text.
  const std::string& text() const { return text_; }
  const std::vector<JsonValue>& items() const { return items_; }
  // kObject: the members in insertion order.
  const std::vector<std::pair<std::string, JsonValue>>& members() const {
    return members_;
  }

  // The JSON text: numbers with 17 significant digits, ", " between items.
  std::string str() const;
  // Whether a kRaw value is in this tree.
  bool ContainsRaw() const {
    if (kind_ == Kind::kRaw) return true;
    for (const JsonValue& item : items_)
      if (item.ContainsRaw()) return true;
    for (const auto& member : members_)
      if (member.second.ContainsRaw()) return true;
    return false;
  }

 private:
  friend class JsonObject;
  explicit JsonValue(Kind kind) : kind_(kind) {}

  Kind kind_ = Kind::kNull;
  bool boolean_ = false;
  long long integer_ = 0;
  double number_ = 0;
  std::string text_;
  std::vector<JsonValue> items_;
  std::vector<std::pair<std::string, JsonValue>> members_;
};

// Builds one JSON object with keys in insertion order. Numbers are printed
// with 17 significant digits; non-finite numbers as null.
class JsonObject {
 public:
  JsonObject& Add(const std::string& key, JsonValue value) {
    value_.members_.emplace_back(key, std::move(value));
    return *this;
  }
  JsonObject& Add(const std::string& key, double value) {
    return Add(key, JsonValue::Number(value));
  }
  JsonObject& Add(const std::string& key, int value) {
    return Add(key, JsonValue::Int(value));
  }
  JsonObject& Add(const std::string& key, bool value) {
    return Add(key, JsonValue::Bool(value));
  }
  JsonObject& Add(const std::string& key, const std::string& value) {
    return Add(key, JsonValue::String(value));
  }
  JsonObject& Add(const std::string& key, const char* value) {
    return Add(key, JsonValue::String(value));
  }
  JsonObject& Add(const std::string& key, const std::vector<double>& values) {
    std::vector<JsonValue> items;
    for (double value : values) items.push_back(JsonValue::Number(value));
    return Add(key, JsonValue::Array(std::move(items)));
  }
  JsonObject& Add(const std::string& key, const std::vector<int>& values) {
    std::vector<JsonValue> items;
    for (int value : values) items.push_back(JsonValue::Int(value));
    return Add(key, JsonValue::Array(std::move(items)));
  }
  JsonObject& Add(const std::string& key,
                  const std::vector<std::string>& values) {
    std::vector<JsonValue> items;
    for (const std::string& value : values)
      items.push_back(JsonValue::String(value));
    return Add(key, JsonValue::Array(std::move(items)));
  }
  JsonObject& Add(const std::string& key, const JsonObject& object) {
    return Add(key, JsonValue::Object(object));
  }
  JsonObject& Add(const std::string& key,
                  const std::vector<JsonObject>& objects) {
    std::vector<JsonValue> items;
    for (const JsonObject& object : objects)
      items.push_back(JsonValue::Object(object));
    return Add(key, JsonValue::Array(std::move(items)));
  }
  // `value` must already be valid JSON (kept as text: JsonValue::Raw).
  JsonObject& Raw(const std::string& key, const std::string& value) {
    return Add(key, JsonValue::Raw(value));
  }

  // The object as a value of the tree (kObject).
  const JsonValue& value() const { return value_; }
  std::string str() const { return value_.str(); }

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
  JsonValue value_{JsonValue::Kind::kObject};
};

inline JsonValue JsonValue::Object(const JsonObject& object) {
  return object.value();
}

inline std::string JsonValue::str() const {
  switch (kind_) {
    case Kind::kNull:
      return "null";
    case Kind::kBool:
      return boolean_ ? "true" : "false";
    case Kind::kInt:
      return std::to_string(integer_);
    case Kind::kNumber:
      return JsonObject::Number(number_);
    case Kind::kString:
      return JsonObject::Quote(text_);
    case Kind::kRaw:
      return text_;
    case Kind::kArray: {
      std::string out = "[";
      for (size_t i = 0; i < items_.size(); ++i)
        out += (i ? ", " : "") + items_[i].str();
      return out + "]";
    }
    case Kind::kObject: {
      std::string out = "{";
      for (size_t i = 0; i < members_.size(); ++i) {
        out += (i ? ", " : "") + JsonObject::Quote(members_[i].first) + ": " +
               members_[i].second.str();
      }
      return out + "}";
    }
  }
  return "null";
}

}  // namespace shellspace

#endif  // SHELLSPACE_IO_JSON_WRITER_H_
