// A small JSON reader (RFC 8259) for the project's own input files: marker sets, and
// later edit lists and options. The writer side is json_writer.h.
//
// Grammar accepted: exactly one value, surrounded by optional whitespace (space, tab,
// CR, LF) and an optional UTF-8 byte-order mark. Values are objects, arrays, numbers,
// strings, true, false and null, as RFC 8259 defines them:
//   numbers   -?(0|[1-9][0-9]*)(.[0-9]+)?([eE][+-]?[0-9]+)?, parsed to the nearest
//             double; a number that overflows a double is an error (no inf in JSON);
//   strings   raw control characters (< 0x20) are errors; escapes \" \\ \/ \b \f \n \r
//             \t \uXXXX (surrogate pairs combined, a lone surrogate is an error) are
//             decoded to UTF-8; other bytes are kept as they are;
//   objects   keys in file order (JsonNode::members); a repeated key is an error.
// No comments, trailing commas, NaN/Infinity or single quotes (JSON has none).
//
// Errors are one line, "NAME:LINE:COL: expected X, got 'Y'" (LINE and COL 1-based, COL
// counting bytes; 'Y' is the offending text, "end of file" at the end), e.g.
//   markers.json:3:17: expected ',' or '}', got '"offset"'
// Nesting deeper than JsonReadOptions::max_depth is an error, so no input can exhaust
// the stack; any byte sequence gives a node tree or a Status, never a crash or hang.
//
// Every node records where its value starts (line, column), so code that interprets
// the tree can name the place of a bad field (JsonNode::Where).
#ifndef MOCAPSOLVE_IO_JSON_READER_H_
#define MOCAPSOLVE_IO_JSON_READER_H_

#include <set>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "kinematics/status.h"

namespace mocapsolve {

class JsonNode {
 public:
  enum class Type { kNull, kBool, kNumber, kString, kArray, kObject };

  Type type = Type::kNull;
  bool boolean = false;                  // kBool.
  double number = 0.0;                   // kNumber.
  std::string string;                    // kString (UTF-8).
  std::vector<JsonNode> items;           // kArray, in order.
  std::vector<std::pair<std::string, JsonNode>> members;  // kObject, in file order.
  int line = 0;                          // Where the value starts (1-based; 0 = unknown).
  int column = 0;

  bool is_null() const { return type == Type::kNull; }
  bool is_bool() const { return type == Type::kBool; }
  bool is_number() const { return type == Type::kNumber; }
  bool is_string() const { return type == Type::kString; }
  bool is_array() const { return type == Type::kArray; }
  bool is_object() const { return type == Type::kObject; }

  // Member `key` of an object, or nullptr (also for non-objects).
  const JsonNode* Find(const std::string& key) const;
  // "NAME:LINE:COL" of this value (for messages about its meaning, not its syntax).
  std::string Where(const std::string& file_name) const;
};

// "null", "boolean", "number", "string", "array", "object".
const char* JsonTypeName(JsonNode::Type type);

// The first member of `object` whose key is not in `allowed` (nullptr if none), and the
// allowed keys as "a, b, c" for the message: file formats reject unknown keys so that
// typos surface.
const std::pair<std::string, JsonNode>* FindUnknownKey(const JsonNode& object,
                                                       const std::set<std::string>& allowed);
std::string KeyList(const std::set<std::string>& allowed);

struct JsonReadOptions {
  int max_depth = 128;  // Arrays and objects nested deeper than this are an error.
};

// Parses text; file_name only labels error messages. *root is left alone on error.
Status ParseJson(std::string_view text, const std::string& file_name, JsonNode* root,
                 const JsonReadOptions& options = {});

// Reads and parses the file at path (errors name the path).
Status ReadJsonFile(const std::string& path, JsonNode* root, const JsonReadOptions& options = {});

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_IO_JSON_READER_H_
