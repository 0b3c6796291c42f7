#include "io/trc_reader.h"

#include <cctype>
#include <charconv>
#include <climits>
#include <cmath>
#include <utility>
#include <vector>

#include "io/atomic_file.h"
#include "io/input_limits.h"
#include "kinematics/quote_token.h"

namespace mocapsolve {
namespace {

std::string_view TrimView(std::string_view s) {
  const auto blank = [](char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n'; };
  while (!s.empty() && blank(s.front())) s.remove_prefix(1);
  while (!s.empty() && blank(s.back())) s.remove_suffix(1);
  return s;
}

// Cells of a line: tab-separated; a line without tabs is split at runs of spaces (some
// exporters pad with spaces instead).
std::vector<std::string_view> SplitCells(std::string_view line) {
  std::vector<std::string_view> cells;
  if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
  if (line.find('\t') != std::string_view::npos) {
    size_t start = 0;
    while (true) {
      const size_t tab = line.find('\t', start);
      cells.push_back(TrimView(line.substr(start, tab - start)));
      if (tab == std::string_view::npos) break;
      start = tab + 1;
    }
  } else {
    size_t i = 0;
    while (i < line.size()) {
      while (i < line.size() && line[i] == ' ') ++i;
      const size_t start = i;
      while (i < line.size() && line[i] != ' ') ++i;
      if (i > start) cells.push_back(line.substr(start, i - start));
    }
  }
  return cells;
}

// A whole cell as a double (locale independent); "nan" gives NaN.
bool ParseNumber(std::string_view cell, double* value) {
  if (!cell.empty() && cell.front() == '+') cell.remove_prefix(1);
  if (cell.empty()) return false;
  const auto [end, error] = std::from_chars(cell.data(), cell.data() + cell.size(), *value);
  return error == std::errc() && end == cell.data() + cell.size();
}

bool IsNan(std::string_view cell) {
  return cell.size() == 3 && std::tolower(static_cast<unsigned char>(cell[0])) == 'n' &&
         std::tolower(static_cast<unsigned char>(cell[1])) == 'a' &&
         std::tolower(static_cast<unsigned char>(cell[2])) == 'n';
}

bool EqualsIgnoringCase(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (size_t i = 0; i < a.size(); ++i) {
    if (std::tolower(static_cast<unsigned char>(a[i])) !=
        std::tolower(static_cast<unsigned char>(b[i]))) {
      return false;
    }
  }
  return true;
}

struct Line {
  int number = 0;  // 1-based.
  std::string_view text;
};

}  // namespace

Status ParseTrc(std::string_view text, const std::string& file_name,
                MarkerTrajectories* trajectories, const TrcReadOptions& options) {
  const auto error = [&](int line, const std::string& what) {
    return Status::Error(file_name + ":" + std::to_string(line) + ": " + what);
  };
  // The five header lines, then the non-blank rows (blank lines are not stored, so
  // memory stays proportional to the data).
  std::vector<Line> lines;
  std::vector<Line> rows;
  int number = 0;
  for (size_t start = 0; start < text.size();) {
    size_t end = text.find('\n', start);
    if (end == std::string_view::npos) end = text.size();
    if (number == INT_MAX) return error(number, "too many lines");
    const Line line{++number, text.substr(start, end - start)};
    start = end + 1;
    if (lines.size() < 5) {
      lines.push_back(line);
    } else if (!TrimView(line.text).empty()) {
      rows.push_back(line);
    }
  }
  if (lines.size() < 5) {
    return error(number, "file ends inside the 5-line TRC header (" +
                             std::to_string(lines.size()) + " lines)");
  }
  // Line 1.
  const std::vector<std::string_view> first = SplitCells(lines[0].text);
  if (first.empty() || first[0] != "PathFileType") {
    return error(1, "expected 'PathFileType' (a TRC file), got " +
                        QuoteToken(first.empty() ? "" : first[0]));
  }
  // Lines 2-3: keys and values.
  const std::vector<std::string_view> keys = SplitCells(lines[1].text);
  const std::vector<std::string_view> values = SplitCells(lines[2].text);
  const auto header_value = [&](std::string_view key, std::string_view* value) {
    for (size_t i = 0; i < keys.size(); ++i) {
      if (EqualsIgnoringCase(keys[i], key)) {
        if (i >= values.size() || values[i].empty()) return false;
        *value = values[i];
        return true;
      }
    }
    return false;
  };
  std::string_view cell;
  double rate, frames_value, markers_value;
  if (!header_value("DataRate", &cell)) return error(3, "missing DataRate");
  if (!ParseNumber(cell, &rate) || !(rate > 0.0) || !std::isfinite(rate)) {
    return error(3, "DataRate " + QuoteToken(cell) + " is not a positive number");
  }
  if (Status s = CheckFrameRate(rate, "DataRate"); !s.ok()) return error(3, s.message());  // io/input_limits.h
  if (!header_value("NumFrames", &cell)) return error(3, "missing NumFrames");
  if (!ParseNumber(cell, &frames_value) || frames_value < 0 || frames_value > INT_MAX ||
      frames_value != std::floor(frames_value)) {
    return error(3, "NumFrames " + QuoteToken(cell) + " is not a frame count");
  }
  if (!header_value("NumMarkers", &cell)) return error(3, "missing NumMarkers");
  if (!ParseNumber(cell, &markers_value) || markers_value < 0 || markers_value > INT_MAX ||
      markers_value != std::floor(markers_value)) {
    return error(3, "NumMarkers " + QuoteToken(cell) + " is not a marker count");
  }
  if (!header_value("Units", &cell)) return error(3, "missing Units");
  const LengthUnit unit = LengthUnitFromName(std::string(cell));
  if (!unit.known()) return error(3, "Units " + QuoteToken(cell) + " is not mm, cm or m");
  const int num_frames = static_cast<int>(frames_value);
  const int num_markers = static_cast<int>(markers_value);

  // Line 4: Frame# Time name (tab tab) name ...
  const std::vector<std::string_view> name_cells = SplitCells(lines[3].text);
  if (name_cells.size() < 2 || !EqualsIgnoringCase(name_cells[0], "Frame#")) {
    return error(4, "expected the 'Frame#  Time  <marker names>' row, got " +
                        QuoteToken(TrimView(lines[3].text)));
  }
  std::vector<std::string> labels;
  for (size_t i = 2; i < name_cells.size(); ++i) {
    if (!name_cells[i].empty()) labels.emplace_back(name_cells[i]);
  }
  if (static_cast<int>(labels.size()) != num_markers) {
    return error(4, std::to_string(labels.size()) + " marker names, but NumMarkers is " +
                        std::to_string(num_markers));
  }
  // Line 5 (X1 Y1 Z1 ...) carries nothing the names row does not.

  if (static_cast<int>(rows.size()) != num_frames) {
    return error(rows.empty() ? number : rows.back().number,
                 std::to_string(rows.size()) + " frame rows, but NumFrames is " +
                     std::to_string(num_frames));
  }

  if (Status status = MarkerTrajectories::CheckLabels(labels); !status.ok()) {
    return error(4, status.message());
  }
  MarkerTrajectories out(std::move(labels), num_frames);
  out.frame_rate = rate;
  out.unit = unit;
  const size_t needed = 2 + 3 * static_cast<size_t>(num_markers);
  for (int f = 0; f < num_frames; ++f) {
    const int line = rows[f].number;
    const std::vector<std::string_view> cells = SplitCells(rows[f].text);
    if (cells.size() < needed) {
      return error(line, std::to_string(cells.size()) + " columns, expected 2 + 3 x " +
                             std::to_string(num_markers) + " = " + std::to_string(needed));
    }
    for (size_t c = needed; c < cells.size(); ++c) {
      if (!cells[c].empty()) {
        return error(line, "column " + std::to_string(c + 1) + " " + QuoteToken(cells[c]) +
                               " beyond the " + std::to_string(needed) + " expected");
      }
    }
    double frame_number, time;
    if (!ParseNumber(cells[0], &frame_number) || frame_number != std::floor(frame_number) ||
        std::abs(frame_number) > INT_MAX) {
      return error(line, "column 1 (Frame#) " + QuoteToken(cells[0]) + " is not a frame number");
    }
    if (!ParseNumber(cells[1], &time)) {
      return error(line, "column 2 (Time) " + QuoteToken(cells[1]) + " is not a number");
    }
    if (f == 0) out.first_frame = static_cast<int>(frame_number);
    for (int m = 0; m < num_markers; ++m) {
      Eigen::Vector3d position;
      bool present = true;
      for (int k = 0; k < 3; ++k) {
        const size_t c = 2 + 3 * static_cast<size_t>(m) + k;
        if (cells[c].empty() || IsNan(cells[c])) {
          present = false;
        } else if (!ParseNumber(cells[c], &position[k])) {
          return error(line, "column " + std::to_string(c + 1) + " (" + "XYZ"[k] + " of " +
                                 QuoteToken(out.label(m)) + ") " + QuoteToken(cells[c]) +
                                 " is not a number");
        } else if (!(std::abs(position[k]) <= MarkerTrajectories::kMaxCoordinate)) {
          return error(line, "column " + std::to_string(c + 1) + " (" + "XYZ"[k] + " of " +
                                 QuoteToken(out.label(m)) + ") " + QuoteToken(cells[c]) +
                                 " is beyond +-1e9");
        }
      }
      if (!present || !position.allFinite()) continue;  // Stays missing.
      if (options.zero_position_is_missing && (position.array() == 0.0).all()) continue;
      out.SetSample(f, m, position);
    }
  }
  *trajectories = std::move(out);
  return Status::Ok();
}

Status ReadTrc(const std::string& path, MarkerTrajectories* trajectories,
               const TrcReadOptions& options) {
  std::string text;
  Status status = ReadFileToString(path, &text);
  if (!status.ok()) return status;
  return ParseTrc(text, path, trajectories, options);
}

}  // namespace mocapsolve
