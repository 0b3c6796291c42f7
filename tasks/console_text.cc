#include "tasks/console_text.h"

#include <cstdarg>
#include <cstdio>

namespace mocapsolve {

void AppendF(std::string* text, const char* format, ...) {
  va_list arguments;
  va_start(arguments, format);
  va_list copy;
  va_copy(copy, arguments);
  const int size = std::vsnprintf(nullptr, 0, format, copy);
  va_end(copy);
  if (size > 0) {
    const size_t old_size = text->size();
    text->resize(old_size + static_cast<size_t>(size) + 1);
    std::vsnprintf(&(*text)[old_size], static_cast<size_t>(size) + 1, format, arguments);
    text->resize(old_size + static_cast<size_t>(size));
  }
  va_end(arguments);
}

}  // namespace mocapsolve
