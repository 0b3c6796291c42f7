// A token of a file, or a name read from one, for a one-line error message: quoted, at
// most 64 bytes shown (then "..."), control and non-ASCII bytes escaped as \xNN, so that
// even a binary file, a 20 MB marker label or a name with an embedded newline gives a
// short printable single line. The one helper for echoing input in messages (io/,
// kinematics/ and problems/ use it).
#ifndef MOCAPSOLVE_KINEMATICS_QUOTE_TOKEN_H_
#define MOCAPSOLVE_KINEMATICS_QUOTE_TOKEN_H_

#include <string>
#include <string_view>

namespace mocapsolve {

inline std::string QuoteToken(std::string_view token) {
  constexpr size_t kMaxShown = 64;
  std::string out = "'";
  for (size_t i = 0; i < token.size() && i < kMaxShown; ++i) {
    const unsigned char c = static_cast<unsigned char>(token[i]);
    if (c >= 0x20 && c < 0x7f) {
      out += static_cast<char>(c);
    } else {
      static const char kHex[] = "0123456789abcdef";
      out += "\\x";
      out += kHex[c >> 4];
      out += kHex[c & 15];
    }
  }
  if (token.size() > kMaxShown) out += "...";
  return out + "'";
}

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_KINEMATICS_QUOTE_TOKEN_H_
