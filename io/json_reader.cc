#include "io/json_reader.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <unordered_set>

#include "io/atomic_file.h"
#include "kinematics/quote_token.h"

namespace mocapsolve {
namespace {

class Parser {
 public:
  Parser(std::string_view text, const std::string& file_name, const JsonReadOptions& options)
      : text_(text), file_name_(file_name), options_(options) {}

  Status ParseDocument(JsonNode* root) {
    if (text_.substr(0, 3) == "\xEF\xBB\xBF") pos_ = line_start_ = 3;  // UTF-8 BOM.
    SkipWhitespace();
    Status status = ParseValue(0, root);
    if (!status.ok()) return status;
    SkipWhitespace();
    if (pos_ != text_.size()) return Expected("end of file");
    return Status::Ok();
  }

 private:
  bool AtEnd() const { return pos_ >= text_.size(); }
  char Peek() const { return text_[pos_]; }
  int Column() const { return static_cast<int>(pos_ - line_start_) + 1; }

  void SkipWhitespace() {
    while (!AtEnd()) {
      const char c = Peek();
      if (c == '\n') {
        ++pos_;
        ++line_;
        line_start_ = pos_;
      } else if (c == ' ' || c == '\t' || c == '\r') {
        ++pos_;
      } else {
        break;
      }
    }
  }

  std::string Here() const {
    return file_name_ + ":" + std::to_string(line_) + ":" + std::to_string(Column());
  }

  // The offending text at pos_, for "got 'Y'": a word or number, a string, or one byte.
  std::string Got() const {
    if (AtEnd()) return "end of file";
    const auto is_word = [](char c) {
      return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
             c == '_' || c == '-' || c == '+' || c == '.';
    };
    size_t end = pos_ + 1;
    if (Peek() == '"') {
      while (end < text_.size() && text_[end] != '"' && text_[end] != '\n' && end - pos_ < 24) {
        end += text_[end] == '\\' && end + 1 < text_.size() ? 2 : 1;
      }
      if (end < text_.size() && text_[end] == '"') ++end;
    } else if (is_word(Peek())) {
      while (end < text_.size() && is_word(text_[end]) && end - pos_ < 24) ++end;
    }
    std::string shown;
    for (size_t i = pos_; i < end && i < text_.size(); ++i) {
      const unsigned char c = static_cast<unsigned char>(text_[i]);
      if (c < 0x20 || c >= 0x7f) {
        char hex[8];
        std::snprintf(hex, sizeof hex, "\\x%02x", c);
        shown += hex;
      } else {
        shown += static_cast<char>(c);
      }
    }
    return QuoteToken(shown);
  }

  Status Expected(const std::string& what) const {
    return Status::Error(Here() + ": expected " + what + ", got " + Got());
  }

  Status ParseValue(int depth, JsonNode* node) {
    node->line = line_;
    node->column = Column();
    if (AtEnd()) return Expected("a value");
    switch (Peek()) {
      case '{': return ParseObject(depth + 1, node);
      case '[': return ParseArray(depth + 1, node);
      case '"':
        node->type = JsonNode::Type::kString;
        return ParseString(&node->string);
      case 't': return ParseLiteral("true", JsonNode::Type::kBool, true, node);
      case 'f': return ParseLiteral("false", JsonNode::Type::kBool, false, node);
      case 'n': return ParseLiteral("null", JsonNode::Type::kNull, false, node);
      default:
        if (Peek() == '-' || (Peek() >= '0' && Peek() <= '9')) return ParseNumber(node);
        return Expected("a value");
    }
  }

  Status ParseLiteral(std::string_view word, JsonNode::Type type, bool value, JsonNode* node) {
    if (text_.substr(pos_, word.size()) != word) return Expected("a value");
    const size_t end = pos_ + word.size();
    if (end < text_.size()) {
      const char c = text_[end];
      if ((c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9')) {
        return Expected("a value");  // "nullx", "true1".
      }
    }
    pos_ = end;
    node->type = type;
    node->boolean = value;
    return Status::Ok();
  }

  Status ParseNumber(JsonNode* node) {
    const size_t start = pos_;
    const auto digit = [&](size_t i) { return i < text_.size() && text_[i] >= '0' && text_[i] <= '9'; };
    size_t i = pos_;
    if (text_[i] == '-') ++i;
    if (!digit(i)) return Expected("a number");
    if (text_[i] == '0') {
      ++i;
      if (digit(i)) return Expected("a number (no leading zeros)");
    } else {
      while (digit(i)) ++i;
    }
    if (i < text_.size() && text_[i] == '.') {
      ++i;
      if (!digit(i)) return Expected("a number (digits after '.')");
      while (digit(i)) ++i;
    }
    if (i < text_.size() && (text_[i] == 'e' || text_[i] == 'E')) {
      ++i;
      if (i < text_.size() && (text_[i] == '+' || text_[i] == '-')) ++i;
      if (!digit(i)) return Expected("a number (digits in the exponent)");
      while (digit(i)) ++i;
    }
    const std::string token(text_.substr(start, i - start));
    const double value = std::strtod(token.c_str(), nullptr);
    if (!std::isfinite(value)) return Expected("a number within double range");
    pos_ = i;
    node->type = JsonNode::Type::kNumber;
    node->number = value;
    return Status::Ok();
  }

  static int HexValue(char c) {
    if (c >= '0' && c <= '9') return c - '0';
    if (c >= 'a' && c <= 'f') return c - 'a' + 10;
    if (c >= 'A' && c <= 'F') return c - 'A' + 10;
    return -1;
  }

  // Four hex digits at pos_ (after "\u"); advances past them.
  Status ParseHex4(unsigned* value) {
    unsigned v = 0;
    for (int k = 0; k < 4; ++k) {
      const int h = AtEnd() ? -1 : HexValue(Peek());
      if (h < 0) return Expected("4 hex digits after \\u");
      v = v * 16 + static_cast<unsigned>(h);
      ++pos_;
    }
    *value = v;
    return Status::Ok();
  }

  static void AppendUtf8(unsigned code, std::string* out) {
    if (code < 0x80) {
      *out += static_cast<char>(code);
    } else if (code < 0x800) {
      *out += static_cast<char>(0xC0 | (code >> 6));
      *out += static_cast<char>(0x80 | (code & 0x3F));
    } else if (code < 0x10000) {
      *out += static_cast<char>(0xE0 | (code >> 12));
      *out += static_cast<char>(0x80 | ((code >> 6) & 0x3F));
      *out += static_cast<char>(0x80 | (code & 0x3F));
    } else {
      *out += static_cast<char>(0xF0 | (code >> 18));
      *out += static_cast<char>(0x80 | ((code >> 12) & 0x3F));
      *out += static_cast<char>(0x80 | ((code >> 6) & 0x3F));
      *out += static_cast<char>(0x80 | (code & 0x3F));
    }
  }

  // A string at pos_ (which is '"') into *out.
  Status ParseString(std::string* out) {
    if (AtEnd() || Peek() != '"') return Expected("a string");
    ++pos_;
    out->clear();
    while (true) {
      if (AtEnd()) return Expected("'\"' closing the string");
      const char c = Peek();
      if (c == '"') {
        ++pos_;
        return Status::Ok();
      }
      if (static_cast<unsigned char>(c) < 0x20) {
        return Expected(c == '\n' ? "'\"' before the end of the line" : "no raw control character in a string");
      }
      if (c != '\\') {
        *out += c;
        ++pos_;
        continue;
      }
      ++pos_;
      if (AtEnd()) return Expected("an escape character");
      const char e = Peek();
      ++pos_;
      switch (e) {
        case '"': *out += '"'; break;
        case '\\': *out += '\\'; break;
        case '/': *out += '/'; break;
        case 'b': *out += '\b'; break;
        case 'f': *out += '\f'; break;
        case 'n': *out += '\n'; break;
        case 'r': *out += '\r'; break;
        case 't': *out += '\t'; break;
        case 'u': {
          unsigned code = 0;
          Status status = ParseHex4(&code);
          if (!status.ok()) return status;
          if (code >= 0xDC00 && code <= 0xDFFF) {
            pos_ -= 6;
            return Expected("a high surrogate before a low one");
          }
          if (code >= 0xD800 && code <= 0xDBFF) {
            if (text_.substr(pos_, 2) != "\\u") return Expected("a low surrogate (\\uDC00-\\uDFFF)");
            pos_ += 2;
            unsigned low = 0;
            status = ParseHex4(&low);
            if (!status.ok()) return status;
            if (low < 0xDC00 || low > 0xDFFF) {
              pos_ -= 6;
              return Expected("a low surrogate (\\uDC00-\\uDFFF)");
            }
            code = 0x10000 + ((code - 0xD800) << 10) + (low - 0xDC00);
          }
          AppendUtf8(code, out);
          break;
        }
        default:
          pos_ -= 2;
          return Expected("an escape (\\\" \\\\ \\/ \\b \\f \\n \\r \\t \\uXXXX)");
      }
    }
  }

  Status CheckDepth(int depth) const {
    if (depth > options_.max_depth) {
      return Expected("at most " + std::to_string(options_.max_depth) + " nested arrays/objects");
    }
    return Status::Ok();
  }

  Status ParseArray(int depth, JsonNode* node) {
    Status status = CheckDepth(depth);
    if (!status.ok()) return status;
    node->type = JsonNode::Type::kArray;
    ++pos_;  // '['
    SkipWhitespace();
    if (!AtEnd() && Peek() == ']') {
      ++pos_;
      return Status::Ok();
    }
    while (true) {
      SkipWhitespace();
      node->items.emplace_back();
      status = ParseValue(depth, &node->items.back());
      if (!status.ok()) return status;
      SkipWhitespace();
      if (AtEnd()) return Expected("',' or ']'");
      if (Peek() == ',') {
        ++pos_;
        continue;
      }
      if (Peek() == ']') {
        ++pos_;
        return Status::Ok();
      }
      return Expected("',' or ']'");
    }
  }

  Status ParseObject(int depth, JsonNode* node) {
    Status status = CheckDepth(depth);
    if (!status.ok()) return status;
    node->type = JsonNode::Type::kObject;
    std::unordered_set<std::string> keys;  // Linear-time duplicate check for big objects.
    ++pos_;  // '{'
    SkipWhitespace();
    if (!AtEnd() && Peek() == '}') {
      ++pos_;
      return Status::Ok();
    }
    while (true) {
      SkipWhitespace();
      if (AtEnd() || Peek() != '"') return Expected("a key string");
      const size_t key_pos = pos_;
      std::string key;
      status = ParseString(&key);
      if (!status.ok()) return status;
      if (!keys.insert(key).second) {
        pos_ = key_pos;
        return Expected("a key not used before in this object");
      }
      SkipWhitespace();
      if (AtEnd() || Peek() != ':') return Expected("':'");
      ++pos_;
      SkipWhitespace();
      node->members.emplace_back(std::move(key), JsonNode());
      status = ParseValue(depth, &node->members.back().second);
      if (!status.ok()) return status;
      SkipWhitespace();
      if (AtEnd()) return Expected("',' or '}'");
      if (Peek() == ',') {
        ++pos_;
        continue;
      }
      if (Peek() == '}') {
        ++pos_;
        return Status::Ok();
      }
      return Expected("',' or '}'");
    }
  }

  std::string_view text_;
  const std::string& file_name_;
  const JsonReadOptions& options_;
  size_t pos_ = 0;
  size_t line_start_ = 0;
  int line_ = 1;
};

}  // namespace

const JsonNode* JsonNode::Find(const std::string& key) const {
  for (const auto& member : members) {
    if (member.first == key) return &member.second;
  }
  return nullptr;
}

std::string JsonNode::Where(const std::string& file_name) const {
  return file_name + ":" + std::to_string(line) + ":" + std::to_string(column);
}

const std::pair<std::string, JsonNode>* FindUnknownKey(const JsonNode& object,
                                                       const std::set<std::string>& allowed) {
  for (const auto& member : object.members) {
    if (allowed.count(member.first) == 0) return &member;
  }
  return nullptr;
}

std::string KeyList(const std::set<std::string>& allowed) {
  std::string list;
  for (const std::string& key : allowed) list += (list.empty() ? "" : ", ") + key;
  return list;
}

const char* JsonTypeName(JsonNode::Type type) {
  switch (type) {
    case JsonNode::Type::kNull: return "null";
    case JsonNode::Type::kBool: return "boolean";
    case JsonNode::Type::kNumber: return "number";
    case JsonNode::Type::kString: return "string";
    case JsonNode::Type::kArray: return "array";
    case JsonNode::Type::kObject: return "object";
  }
  return "?";
}

Status ParseJson(std::string_view text, const std::string& file_name, JsonNode* root,
                 const JsonReadOptions& options) {
  JsonNode result;
  Parser parser(text, file_name, options);
  Status status = parser.ParseDocument(&result);
  if (!status.ok()) return status;
  *root = std::move(result);
  return Status::Ok();
}

Status ReadJsonFile(const std::string& path, JsonNode* root, const JsonReadOptions& options) {
  std::string text;
  Status status = ReadFileToString(path, &text);
  if (!status.ok()) return status;
  return ParseJson(text, path, root, options);
}

}  // namespace mocapsolve
