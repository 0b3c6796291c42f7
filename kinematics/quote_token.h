// A token of a file, or a name read from one, for a one-line error message: quoted, at
// most 64 bytes shown (then "..."), control and non-ASCII bytes escaped as \xNN, so that
// even a binary file, a 20 MB marker label or a name with an embedded newline gives a
// short printable single line. The one helper for echoing input in messages (io/,
// kinematics/ and problems/ use it).
#ifndef MOCAPSOLVE_KINEMATICS_QUOTE_TOKEN_H_
#define MOCAPSOLVE_KINEMATICS_QUOTE_TOKEN_H_

#include <cstdio>
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

// A number for a message: "%.6g" ("1e+39", not std::to_string's 40 digits).
inline std::string ShortNumber(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", value);
  return text;
}

// A name read from a file (a label, joint, clip or file name), for printing to a
// terminal: whole (unlike QuoteToken, not cut nor quoted), UTF-8 kept, but the C0 and
// C1 control characters and DEL escaped as \xNN (C1 as the two bytes of its UTF-8
// form), so that a label holding ESC cannot drive the terminal. The one helper for every
// command printing file-provided names to stdout or stderr.
inline std::string TerminalText(std::string_view text) {
  static const char kHex[] = "0123456789abcdef";
  std::string out;
  out.reserve(text.size());
  const auto escape = [&](unsigned char c) {
    out += "\\x";
    out += kHex[c >> 4];
    out += kHex[c & 15];
  };
  for (size_t i = 0; i < text.size(); ++i) {
    const unsigned char c = static_cast<unsigned char>(text[i]);
    const bool c1 = c == 0xc2 && i + 1 < text.size() && static_cast<unsigned char>(text[i + 1]) >= 0x80 &&
                    static_cast<unsigned char>(text[i + 1]) <= 0x9f;
    if (c < 0x20 || c == 0x7f) {
      escape(c);
    } else if (c1) {
      escape(c);
      escape(static_cast<unsigned char>(text[++i]));
    } else {
      out += static_cast<char>(c);
    }
  }
  return out;
}

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_KINEMATICS_QUOTE_TOKEN_H_
