// JsonWriter: a small streaming JSON writer (objects, arrays, strings, numbers, booleans), indented.
#pragma once

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <ostream>
#include <string>
#include <type_traits>
#include <vector>

#include "gpusolve/core/error.hpp"

namespace gpusolve::rbd::io {

// Inside an object every value needs a key (field, begin_object(key), ...), inside
// an array none may have one; misuse throws rather than writing invalid JSON.
// JSON has no NaN or infinity: non-finite numbers are written as null.
class JsonWriter {
 public:
  explicit JsonWriter(std::ostream& os) : os_(os) {}

  JsonWriter& begin_object() { return open('{', nullptr); }
  JsonWriter& begin_object(const std::string& key) { return open('{', &key); }
  JsonWriter& begin_array() { return open('[', nullptr); }
  JsonWriter& begin_array(const std::string& key) { return open('[', &key); }
  JsonWriter& end_object() { return close('{', '}'); }
  JsonWriter& end_array() { return close('[', ']'); }

  template <class V>
  JsonWriter& field(const std::string& key, const V& v) {
    prefix(&key);
    write(v);
    return *this;
  }
  template <class V>
  JsonWriter& value(const V& v) {
    prefix(nullptr);
    write(v);
    return *this;
  }

  // True once the top-level value is complete.
  bool done() const { return stack_.empty() && wrote_top_; }

  static std::string quote(const std::string& s) {
    std::string r = "\"";
    for (unsigned char c : s) {
      switch (c) {
        case '"': r += "\\\""; break;
        case '\\': r += "\\\\"; break;
        case '\n': r += "\\n"; break;
        case '\t': r += "\\t"; break;
        case '\r': r += "\\r"; break;
        default:
          if (c < 0x20) {
            char buf[8];
            std::snprintf(buf, sizeof buf, "\\u%04x", c);
            r += buf;
          } else {
            r += static_cast<char>(c);
          }
      }
    }
    return r + "\"";
  }

 private:
  struct Level {
    char open;
    bool empty;
  };

  void write(const std::string& s) { os_ << quote(s); }
  void write(const char* s) { os_ << quote(s); }
  void write(bool b) { os_ << (b ? "true" : "false"); }
  template <class V, class = std::enable_if_t<std::is_arithmetic_v<V>>>
  void write(V v) {
    if constexpr (std::is_integral_v<V>) {
      os_ << +v;
    } else if (!std::isfinite(static_cast<double>(v))) {
      os_ << "null";
    } else {
      char buf[32];
      std::snprintf(buf, sizeof buf, "%.10g", static_cast<double>(v));
      os_ << buf;
    }
  }

  void prefix(const std::string* key) {
    if (stack_.empty()) {
      if (wrote_top_) throw InvalidArgumentError("JsonWriter: a second top-level value");
      if (key) throw InvalidArgumentError("JsonWriter: key '" + *key + "' outside an object");
      wrote_top_ = true;
      return;
    }
    Level& top = stack_.back();
    if (top.open == '{' && !key) throw InvalidArgumentError("JsonWriter: value without a key in an object");
    if (top.open == '[' && key) throw InvalidArgumentError("JsonWriter: key '" + *key + "' inside an array");
    os_ << (top.empty ? "\n" : ",\n") << std::string(2 * stack_.size(), ' ');
    top.empty = false;
    if (key) os_ << quote(*key) << ": ";
  }

  JsonWriter& open(char c, const std::string* key) {
    prefix(key);
    os_ << c;
    stack_.push_back({c, true});
    return *this;
  }

  JsonWriter& close(char open, char c) {
    if (stack_.empty() || stack_.back().open != open)
      throw InvalidArgumentError(std::string("JsonWriter: '") + c + "' does not match an open '" + open + "'");
    const bool empty = stack_.back().empty;
    stack_.pop_back();
    if (!empty) os_ << '\n' << std::string(2 * stack_.size(), ' ');
    os_ << c;
    if (stack_.empty()) os_ << '\n';
    return *this;
  }

  std::ostream& os_;
  std::vector<Level> stack_;
  bool wrote_top_ = false;
};

}  // namespace gpusolve::rbd::io
