// A minimal JSON writer for reports (--report=FILE.json) and benchmark lines: keys in
// insertion order, numbers printed round-trip exact, non-finite numbers as null (JSON
// has no NaN).
#ifndef MOCAPSOLVE_IO_JSON_WRITER_H_
#define MOCAPSOLVE_IO_JSON_WRITER_H_

#include <string>
#include <utility>
#include <vector>

namespace mocapsolve {

class JsonValue {
 public:
  JsonValue() : text_("null") {}
  JsonValue(double number);  // NOLINT: implicit by design, as for the other scalars.
  JsonValue(int number) : JsonValue(static_cast<double>(number)) {}
  JsonValue(long number) : JsonValue(static_cast<double>(number)) {}
  JsonValue(bool value) : text_(value ? "true" : "false") {}
  JsonValue(const char* text);
  JsonValue(const std::string& text) : JsonValue(text.c_str()) {}

  static JsonValue Raw(std::string json) {
    JsonValue v;
    v.text_ = std::move(json);
    return v;
  }
  const std::string& text() const { return text_; }

 private:
  std::string text_;
};

class JsonObject {
 public:
  JsonObject& Add(const std::string& key, const JsonValue& value);
  JsonObject& Add(const std::string& key, const JsonObject& object);
  JsonObject& Add(const std::string& key, const std::vector<JsonValue>& array);
  JsonObject& Add(const std::string& key, const std::vector<JsonObject>& array);
  bool Has(const std::string& key) const;
  // Appends the members of `other` whose keys this object lacks.
  JsonObject& Merge(const JsonObject& other);
  // Compact, one line (for benchmark JSON lines) or indented.
  std::string ToString(bool indent = true) const;

 private:
  std::vector<std::pair<std::string, std::string>> members_;  // key, JSON text
};

std::string JsonQuote(const std::string& text);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_IO_JSON_WRITER_H_
