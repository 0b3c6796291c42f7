// Comma-separated lists as flags, config keys and Python keywords spell them ("a,b,c").
#ifndef MOCAPSOLVE_IO_COMMA_LIST_H_
#define MOCAPSOLVE_IO_COMMA_LIST_H_

#include <string>
#include <vector>

namespace mocapsolve {

// Splits "a,b,c" (empty items dropped).
std::vector<std::string> SplitCommaList(const std::string& text);

// Splits at every separator, keeping empty items: "a;;b" gives {"a", "", "b"}, "" gives
// {""} (for formats where a position means something, such as JOINT:x,y,z;...).
std::vector<std::string> SplitFields(const std::string& text, char separator);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_IO_COMMA_LIST_H_
