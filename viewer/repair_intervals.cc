#include "viewer/repair_intervals.h"

#include <algorithm>
#include <cmath>

#include "io/json_reader.h"

namespace mocapsolve {
namespace {

// The take's marker for a report label: the same label, or one that ends in ":" + label.
int FindLabel(const std::vector<std::string>& labels, const std::string& label) {
  for (size_t m = 0; m < labels.size(); ++m) {
    if (labels[m] == label) return static_cast<int>(m);
  }
  for (size_t m = 0; m < labels.size(); ++m) {
    const std::string& l = labels[m];
    if (l.size() > label.size() && l.compare(l.size() - label.size(), label.size(), label) == 0 &&
        l[l.size() - label.size() - 1] == ':') {
      return static_cast<int>(m);
    }
  }
  return -1;
}

Status ReadList(const std::string& path, const JsonNode& root, const char* key,
                const std::vector<std::string>& labels, int num_frames, std::vector<ReportedInterval>* out) {
  const JsonNode* list = root.Find(key);
  if (list == nullptr || !list->is_array()) {
    return Status::Error(path + ": " + key + ": expected an array of intervals (a repair --report)");
  }
  for (size_t i = 0; i < list->items.size(); ++i) {
    const JsonNode& item = list->items[i];
    const std::string where = item.Where(path) + ": " + key + "[" + std::to_string(i) + "]";
    const JsonNode* marker = item.Find("marker");
    const JsonNode* first = item.Find("first_frame");
    const JsonNode* last = item.Find("last_frame");
    const JsonNode* what = item.Find("what");
    if (marker == nullptr || !marker->is_string() || first == nullptr || !first->is_number() ||
        last == nullptr || !last->is_number()) {
      return Status::Error(where + ": expected marker, first_frame and last_frame");
    }
    ReportedInterval interval;
    interval.marker = FindLabel(labels, marker->string);
    if (interval.marker < 0) return Status::Error(where + ".marker: '" + marker->string + "' is not a marker of the take");
    if (first->number != std::floor(first->number) || last->number != std::floor(last->number) ||
        first->number < 0 || last->number < first->number || last->number >= num_frames) {
      return Status::Error(where + ": frames " + std::to_string(first->number) + ".." + std::to_string(last->number) +
                           " outside the take's " + std::to_string(num_frames) + " frames");
    }
    interval.first = static_cast<int>(first->number);
    interval.last = static_cast<int>(last->number);
    if (what != nullptr && what->is_string()) interval.what = what->string;
    out->push_back(interval);
  }
  return Status::Ok();
}

}  // namespace

std::vector<ViewInterval> RepairedViewIntervals(const std::vector<ReportedInterval>& detected,
                                                const std::vector<ReportedInterval>& filled) {
  std::vector<ViewInterval> out;
  for (const ReportedInterval& d : detected) {
    if (d.what != "unlabelled") continue;
    ViewInterval interval;
    interval.marker = d.marker;
    interval.first = d.first;
    interval.last = d.last;
    interval.state = MarkerState::kRepairedUnlabelled;
    out.push_back(interval);
  }
  for (const ReportedInterval& fill : filled) {
    ViewInterval interval;
    interval.marker = fill.marker;
    interval.first = fill.first;
    interval.last = fill.last;
    int best = 0;
    for (const ReportedInterval& d : detected) {
      if (d.marker != fill.marker || d.what == "unlabelled") continue;
      const int overlap = std::min(d.last, fill.last) - std::max(d.first, fill.first) + 1;
      if (overlap > best) {
        best = overlap;
        interval.state = RepairedStateForReason(d.what);
      }
    }
    out.push_back(interval);
  }
  return out;
}

Status ReadRepairReport(const std::string& path, const std::vector<std::string>& labels, int num_frames,
                        std::vector<ReportedInterval>* detected, std::vector<ReportedInterval>* filled) {
  JsonNode root;
  Status status = ReadJsonFile(path, &root);
  if (!status.ok()) return status;
  if (!root.is_object()) return Status::Error(path + ": expected a JSON object (a repair --report)");
  std::vector<ReportedInterval> d, f;
  status = ReadList(path, root, "detected", labels, num_frames, &d);
  if (status.ok()) status = ReadList(path, root, "filled", labels, num_frames, &f);
  if (!status.ok()) return status;
  *detected = std::move(d);
  *filled = std::move(f);
  return Status::Ok();
}

}  // namespace mocapsolve
