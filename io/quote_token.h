// A token of a file for a one-line error message: at most 40 bytes, control and non-ASCII
// bytes escaped as \xNN, so that even a binary file gives a printable single line.
#ifndef MOCAPSOLVE_IO_QUOTE_TOKEN_H_
#define MOCAPSOLVE_IO_QUOTE_TOKEN_H_

#include <string>
#include <string_view>

namespace mocapsolve {

inline std::string QuoteToken(std::string_view token) {
  constexpr size_t kMaxShown = 40;
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

#endif  // MOCAPSOLVE_IO_QUOTE_TOKEN_H_
