#include "io/json_writer.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace mocapsolve {

JsonValue::JsonValue(double number) {
  if (!std::isfinite(number)) {
    text_ = "null";
    return;
  }
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.17g", number);
  // Prefer the shortest form that reads back exactly.
  for (int precision = 6; precision < 17; ++precision) {
    char shorter[32];
    std::snprintf(shorter, sizeof shorter, "%.*g", precision, number);
    if (std::strtod(shorter, nullptr) == number) {
      text_ = shorter;
      return;
    }
  }
  text_ = buffer;
}

JsonValue::JsonValue(const char* text) : text_(JsonQuote(text)) {}

std::string JsonQuote(const std::string& text) {
  std::string out = "\"";
  for (unsigned char c : text) {
    switch (c) {
      case '"': out += "\\\""; break;
      case '\\': out += "\\\\"; break;
      case '\n': out += "\\n"; break;
      case '\r': out += "\\r"; break;
      case '\t': out += "\\t"; break;
      default:
        if (c < 0x20) {
          char buffer[8];
          std::snprintf(buffer, sizeof buffer, "\\u%04x", c);
          out += buffer;
        } else {
          out += static_cast<char>(c);
        }
    }
  }
  return out + "\"";
}

JsonObject& JsonObject::Add(const std::string& key, const JsonValue& value) {
  members_.emplace_back(key, value.text());
  return *this;
}

bool JsonObject::Has(const std::string& key) const {
  for (const auto& member : members_) {
    if (member.first == key) return true;
  }
  return false;
}

JsonObject& JsonObject::Merge(const JsonObject& other) {
  for (const auto& member : other.members_) {
    if (!Has(member.first)) members_.push_back(member);
  }
  return *this;
}

JsonObject& JsonObject::Add(const std::string& key, const JsonObject& object) {
  members_.emplace_back(key, object.ToString(false));
  return *this;
}

JsonObject& JsonObject::Add(const std::string& key, const std::vector<JsonValue>& array) {
  std::string text = "[";
  for (size_t i = 0; i < array.size(); ++i) text += (i ? ", " : "") + array[i].text();
  members_.emplace_back(key, text + "]");
  return *this;
}

JsonObject& JsonObject::Add(const std::string& key, const std::vector<JsonObject>& array) {
  std::string text = "[";
  for (size_t i = 0; i < array.size(); ++i) text += (i ? ", " : "") + array[i].ToString(false);
  members_.emplace_back(key, text + "]");
  return *this;
}

std::string JsonObject::ToString(bool indent) const {
  std::string out = "{";
  for (size_t i = 0; i < members_.size(); ++i) {
    out += i ? "," : "";
    out += indent ? "\n  " : (i ? " " : "");
    out += JsonQuote(members_[i].first) + ": " + members_[i].second;
  }
  out += indent && !members_.empty() ? "\n}" : "}";
  return out;
}

}  // namespace mocapsolve
