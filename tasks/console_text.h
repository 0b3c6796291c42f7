// The console text a command prints (tables, summaries), built by the task as a string so
// that the CLI prints it and Python can return it: printf-style appends.
#ifndef MOCAPSOLVE_TASKS_CONSOLE_TEXT_H_
#define MOCAPSOLVE_TASKS_CONSOLE_TEXT_H_

#include <string>

namespace mocapsolve {

// Appends printf(format, ...) to *text.
void AppendF(std::string* text, const char* format, ...) __attribute__((format(printf, 2, 3)));

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_TASKS_CONSOLE_TEXT_H_
