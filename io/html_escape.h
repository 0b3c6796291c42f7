// Text for HTML pages (the viewer's page title, the batch's summary.html): &, <, > and "
// as entities, so that a take or file name cannot break the markup.
#ifndef MOCAPSOLVE_IO_HTML_ESCAPE_H_
#define MOCAPSOLVE_IO_HTML_ESCAPE_H_

#include <string>

namespace mocapsolve {

std::string HtmlEscape(const std::string& text);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_IO_HTML_ESCAPE_H_
