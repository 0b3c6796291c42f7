#include "io/html_escape.h"

namespace mocapsolve {

std::string HtmlEscape(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (const char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  }
  return out;
}

std::string RelativeUrl(const std::vector<std::string>& segments) {
  static const char kHex[] = "0123456789ABCDEF";
  std::string url = ".";
  for (const std::string& segment : segments) {
    url += '/';
    const bool dots = segment == "." || segment == "..";  // Not a step up: "%2E%2E".
    for (const char c : segment) {
      const unsigned char byte = static_cast<unsigned char>(c);
      const bool unreserved = (byte >= 'A' && byte <= 'Z') || (byte >= 'a' && byte <= 'z') ||
                              (byte >= '0' && byte <= '9') || byte == '-' || byte == '.' || byte == '_' ||
                              byte == '~';
      if (unreserved && !dots) {
        url += c;
      } else {
        url += '%';
        url += kHex[byte >> 4];
        url += kHex[byte & 15];
      }
    }
  }
  return url;
}

}  // namespace mocapsolve
