// Cheap pre-scans that bound what a hostile file can make a third-party parser do.
//
// tinygltf (glTF JSON, `extras` parsed recursively by ParseJsonAsValue) and assimp (ASCII
// FBX, one recursion per brace) recurse once per nesting level of their input, so a file
// of a few tens of kilobytes of '[' or '{' exhausts the stack. Before handing bytes to
// them, io/ measures the nesting depth here, in one linear pass without recursion, and
// refuses files nested deeper than any real one (real glTF and FBX files nest < 20 deep).
//
// Both scans stop counting as soon as the depth passes `limit`: O(bytes), no allocation.
#ifndef MOCAPSOLVE_IO_INPUT_LIMITS_H_
#define MOCAPSOLVE_IO_INPUT_LIMITS_H_

#include <cstddef>
#include <string_view>

namespace mocapsolve {

// Deepest nesting any reader hands to a third-party parser.
constexpr int kMaxThirdPartyNesting = 128;

// Deepest '[' / '{' nesting of JSON text (brackets inside strings, with \" escapes, do
// not count); returns limit + 1 as soon as the depth exceeds `limit`.
int JsonNestingDepth(std::string_view text, int limit = kMaxThirdPartyNesting);

// Deepest '{' nesting of ASCII FBX text (braces inside "strings" and after a ';' comment
// to the end of its line do not count); returns limit + 1 as soon as it exceeds `limit`.
int FbxBraceDepth(std::string_view text, int limit = kMaxThirdPartyNesting);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_IO_INPUT_LIMITS_H_
