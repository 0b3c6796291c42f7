// Numeric CSV tables as the commands write them (propagate --weights_csv, distance, fk):
// a header line of column names, then rows of numbers, comma-separated. Read back as
// columns, for plotting (the viewer's falloff curve).
//
// Errors are one line, "NAME:LINE: ...": an empty file, a row whose field count differs
// from the header's, a field that is not a finite number.
#ifndef MOCAPSOLVE_IO_CSV_COLUMNS_H_
#define MOCAPSOLVE_IO_CSV_COLUMNS_H_

#include <string>
#include <vector>

#include "kinematics/status.h"

namespace mocapsolve {

struct CsvColumns {
  std::vector<std::string> names;               // The header's fields.
  std::vector<std::vector<double>> columns;     // columns[c][row].
};

Status ReadCsvColumns(const std::string& path, CsvColumns* table);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_IO_CSV_COLUMNS_H_
