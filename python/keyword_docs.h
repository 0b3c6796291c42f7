// Docstring text generated from the settings structs, so that help() lists every keyword
// option with the default the library holds (pipeline/*_settings.h) and cannot drift.
#ifndef MOCAPSOLVE_PYTHON_KEYWORD_DOCS_H_
#define MOCAPSOLVE_PYTHON_KEYWORD_DOCS_H_

#include <stdexcept>
#include <string>
#include <vector>

#include "python/bindings.h"
#include "settings/option.h"

namespace mocapsolve::python {

// "\n<title>:\n  name=default, name=default, ..." for each comma-separated name, the values
// read from `defaults` (a bound settings object), wrapped at 88 columns.
inline std::string KeywordDefaults(const std::string& title, const py::object& defaults, const std::string& names) {
  std::string text = "\n" + title + ":\n ", line;
  size_t begin = 0;
  while (begin <= names.size()) {
    size_t end = names.find(',', begin);
    if (end == std::string::npos) end = names.size();
    const std::string name = names.substr(begin, end - begin);
    begin = end + 1;
    if (name.empty()) continue;
    const std::string item = " " + name + "=" + std::string(py::repr(defaults.attr(name.c_str()))) + ",";
    if (line.size() + item.size() > 86) {
      text += line + "\n ";
      line.clear();
    }
    line += item;
  }
  if (!line.empty()) line.pop_back();  // The last comma.
  return text + line;
}

// "  name (default D): help [unit]" per declared option, D read from `defaults` (a bound
// settings object) as Python writes it, the text from the declarations themselves.
inline std::string KeywordHelp(const std::vector<Option>& options, const py::object& defaults) {
  std::string text;
  for (const Option& option : options) {
    text += "  " + option.name + " (default " + std::string(py::repr(defaults.attr(option.name.c_str()))) +
            "): " + option.Description() + "\n";
  }
  return text;
}

// The default of declared option `name` of `group` as a Python value: a keyword argument's
// default comes from its declaration, not from a value typed again in a binding.
template <class Settings>
py::object DeclaredDefault(const OptionGroup<Settings>& group, const std::string& name) {
  const Settings defaults = group.Defaults();
  py::object value;
  group.VisitFields([&](const Option& option, auto field) {
    if (option.name == name) value = py::cast(defaults.*field);
  });
  if (!value) throw std::logic_error("no declared option '" + name + "'");  // A binding's own bug.
  return value;
}

// The settings class's attributes, one per declared option of `group` (the name, the field):
// a new declaration is an attribute without a line here.
template <class Settings, class... Extra>
void BindOptionFields(py::class_<Settings, Extra...>& cls, const OptionGroup<Settings>& group) {
  group.VisitFields([&](const Option& option, auto field) { cls.def_readwrite(option.name.c_str(), field); });
}

}  // namespace mocapsolve::python

#endif  // MOCAPSOLVE_PYTHON_KEYWORD_DOCS_H_
