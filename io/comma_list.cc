#include "io/comma_list.h"

#include <sstream>

namespace mocapsolve {

std::vector<std::string> SplitCommaList(const std::string& text) {
  std::vector<std::string> names;
  std::stringstream stream(text);
  std::string name;
  while (std::getline(stream, name, ',')) {
    if (!name.empty()) names.push_back(name);
  }
  return names;
}

}  // namespace mocapsolve
