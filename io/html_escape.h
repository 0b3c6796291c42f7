// Text for HTML pages (the viewer's page title, the batch's summary.html): &, <, > and "
// as entities, so that a take or file name cannot break the markup; and links built from
// names (RelativeUrl), so that a name cannot become a script or another site.
#ifndef MOCAPSOLVE_IO_HTML_ESCAPE_H_
#define MOCAPSOLVE_IO_HTML_ESCAPE_H_

#include <string>
#include <vector>

namespace mocapsolve {

std::string HtmlEscape(const std::string& text);

// A relative link to a file below the page's folder, from its path's segments: "./" and
// each segment percent-encoded (every byte but A-Z a-z 0-9 - . _ ~ as %XX; so '/', ':',
// '#', '?', '%', quotes, spaces and non-ASCII bytes cannot end a segment, start a query or
// fragment, or make a scheme such as "javascript:"; a segment "." or ".." is encoded
// whole), joined by '/'. HtmlEscape it for an
// attribute. RelativeUrl({"javascript:alert(1)", "view.html"}) is
// "./javascript%3Aalert%281%29/view.html".
std::string RelativeUrl(const std::vector<std::string>& segments);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_IO_HTML_ESCAPE_H_
