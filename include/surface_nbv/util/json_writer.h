// A small streaming JSON writer for reports: objects, arrays, numbers,
// strings (escaped) and booleans. Non-finite numbers are written as null.
#pragma once

#include <sstream>
#include <string>
#include <vector>

namespace surface_nbv {

class JsonWriter {
 public:
  JsonWriter& beginObject(const std::string& key = "");
  JsonWriter& endObject();
  JsonWriter& beginArray(const std::string& key = "");
  JsonWriter& endArray();
  JsonWriter& value(const std::string& key, double v);
  JsonWriter& value(const std::string& key, long long v);
  JsonWriter& value(const std::string& key, int v) { return value(key, static_cast<long long>(v)); }
  JsonWriter& value(const std::string& key, size_t v) { return value(key, static_cast<long long>(v)); }
  JsonWriter& value(const std::string& key, bool v);
  JsonWriter& value(const std::string& key, const std::string& v);
  JsonWriter& value(const std::string& key, const char* v) { return value(key, std::string(v)); }

  std::string str() const { return out_.str() + "\n"; }

 private:
  void prefix(const std::string& key);
  static std::string quote(const std::string& s);

  std::ostringstream out_;
  std::vector<bool> first_{true};
};

}  // namespace surface_nbv
