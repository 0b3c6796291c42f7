#include "io/csv_columns.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>

#include "io/atomic_file.h"

namespace mocapsolve {
namespace {

std::vector<std::string> Fields(const std::string& line) {
  std::vector<std::string> fields;
  size_t start = 0;
  while (true) {
    const size_t comma = line.find(',', start);
    std::string field = line.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    while (!field.empty() && (field.back() == ' ' || field.back() == '\r' || field.back() == '\t')) field.pop_back();
    while (!field.empty() && (field.front() == ' ' || field.front() == '\t')) field.erase(0, 1);
    fields.push_back(field);
    if (comma == std::string::npos) return fields;
    start = comma + 1;
  }
}

}  // namespace

Status ReadCsvColumns(const std::string& path, CsvColumns* table) {
  std::string text;
  Status status = ReadFileToString(path, &text);
  if (!status.ok()) return status;
  CsvColumns out;
  size_t at = 0;
  int line_number = 0;
  while (at < text.size()) {
    const size_t end = text.find('\n', at);
    const std::string line = text.substr(at, end == std::string::npos ? std::string::npos : end - at);
    at = end == std::string::npos ? text.size() : end + 1;
    ++line_number;
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    const std::vector<std::string> fields = Fields(line);
    if (out.names.empty()) {
      out.names = fields;
      out.columns.resize(fields.size());
      continue;
    }
    const std::string where = path + ":" + std::to_string(line_number) + ": ";
    if (fields.size() != out.names.size()) {
      return Status::Error(where + std::to_string(fields.size()) + " fields, the header has " +
                           std::to_string(out.names.size()));
    }
    for (size_t c = 0; c < fields.size(); ++c) {
      char* stop = nullptr;
      errno = 0;
      const double value = std::strtod(fields[c].c_str(), &stop);
      if (fields[c].empty() || *stop != '\0' || errno == ERANGE || !std::isfinite(value)) {
        return Status::Error(where + out.names[c] + ": '" + fields[c].substr(0, 40) + "' is not a finite number");
      }
      out.columns[c].push_back(value);
    }
  }
  if (out.names.empty()) return Status::Error(path + ": empty (expected a header line and rows of numbers)");
  *table = std::move(out);
  return Status::Ok();
}

}  // namespace mocapsolve
