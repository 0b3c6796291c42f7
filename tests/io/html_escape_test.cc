// HtmlEscape and RelativeUrl (io/html_escape.h): names from files become text and links
// that cannot break the page's markup or run a script.
#include "io/html_escape.h"

#include <cctype>
#include <string>
#include <vector>

#include <gtest/gtest.h>

namespace mocapsolve {
namespace {

TEST(HtmlEscape, EscapesMarkupCharacters) {
  EXPECT_EQ(HtmlEscape("a<b>&\"c\""), "a&lt;b&gt;&amp;&quot;c&quot;");
  EXPECT_EQ(HtmlEscape("plain 02_05"), "plain 02_05");
}

// Hostile names: whatever the name, the link starts "./", has exactly one '/' between
// segments, and holds only unreserved characters and %XX (no scheme, query, fragment,
// quote or markup character can appear).
TEST(RelativeUrl, HostileNamesStayRelativePaths) {
  EXPECT_EQ(RelativeUrl({"javascript:alert(1)", "view.html"}), "./javascript%3Aalert%281%29/view.html");
  EXPECT_EQ(RelativeUrl({"02_05", "view.html"}), "./02_05/view.html");
  EXPECT_EQ(RelativeUrl({"a b#c?d%e", "view.html"}), "./a%20b%23c%3Fd%25e/view.html");
  EXPECT_EQ(RelativeUrl({"\"><script>", "v"}), "./%22%3E%3Cscript%3E/v");
  EXPECT_EQ(RelativeUrl({"caf\xc3\xa9"}), "./caf%C3%A9");
  EXPECT_EQ(RelativeUrl({"..", "x/y"}), "./%2E%2E/x%2Fy");
  EXPECT_EQ(RelativeUrl({"//evil.example", "v"}), "./%2F%2Fevil.example/v");
  const std::vector<std::string> hostile = {"javascript:alert(1)", "data:text/html,<b>", "\\\\host\\x", "&amp;",
                                            "'single'", "tab\there", std::string("nul\0x", 5), "~.-_"};
  for (const std::string& name : hostile) {
    const std::string url = RelativeUrl({name, "view.html"});
    ASSERT_EQ(url.compare(0, 2, "./"), 0) << url;
    for (const char c : url.substr(2)) {
      const bool allowed = std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '.' || c == '_' ||
                           c == '~' || c == '%' || c == '/';
      EXPECT_TRUE(allowed) << name << " -> " << url;
    }
    EXPECT_EQ(HtmlEscape(url), url);  // Nothing left for the attribute escape to do.
    EXPECT_EQ(url.substr(url.size() - 10), "/view.html");
  }
}

}  // namespace
}  // namespace mocapsolve
