#include "problems/marker_solve/template_labels.h"

#include <cctype>
#include <set>
#include <utility>

#include "io/atomic_file.h"

namespace mocapsolve {

Status ReadTemplateLabels(const std::string& value, std::vector<TemplateLabel>* labels) {
  labels->clear();
  if (value.find(':') != std::string::npos) return ParseTemplateLabels(value, "", labels);
  std::string text;
  Status status = ReadFileToString(value, &text);
  if (!status.ok()) return Status::Error("--template_labels: " + status.message());
  return ParseTemplateLabels(text, value, labels);
}

Status ParseTemplateLabels(const std::string& text, const std::string& file, std::vector<TemplateLabel>* labels) {
  labels->clear();
  const bool from_file = !file.empty();
  // Where an error points: the flag, or the file and line.
  auto where = [&](int line) {
    return from_file ? file + ":" + std::to_string(line) : std::string("--template_labels");
  };
  std::set<std::string> templ, take;
  int line = 1;
  size_t i = 0;
  while (i < text.size()) {
    const char c = text[i];
    if (c == '\n') ++line;
    if (c == '#') {
      while (i < text.size() && text[i] != '\n') ++i;
      continue;
    }
    if (c == ',' || std::isspace(static_cast<unsigned char>(c))) {
      ++i;
      continue;
    }
    size_t end = i;
    while (end < text.size() && text[end] != ',' && text[end] != '#' &&
           !std::isspace(static_cast<unsigned char>(text[end]))) {
      ++end;
    }
    const std::string pair = text.substr(i, end - i);
    i = end;
    const size_t colon = pair.find(':');
    if (colon == std::string::npos || colon == 0 || colon + 1 == pair.size() ||
        pair.find(':', colon + 1) != std::string::npos) {
      return Status::Error(where(line) + ": '" + pair + "': expected TEMPLATE:TAKE");
    }
    TemplateLabel label{pair.substr(0, colon), pair.substr(colon + 1)};
    if (!templ.insert(label.templ).second) {
      return Status::Error(where(line) + ": template label " + label.templ + " mapped twice");
    }
    if (!take.insert(label.take).second) {
      return Status::Error(where(line) + ": take label " + label.take + " named twice");
    }
    labels->push_back(std::move(label));
  }
  if (labels->empty()) return Status::Error((from_file ? file : "--template_labels") + ": no TEMPLATE:TAKE pairs");
  return Status::Ok();
}

Status RenameTemplateMarkers(const std::vector<TemplateLabel>& labels, const Skeleton& skeleton,
                             const MarkerTrajectories& take, const std::string& take_path, MarkerSet* markers) {
  std::vector<MarkerSpec> specs;
  for (int m = 0; m < markers->num_markers(); ++m) specs.push_back(markers->marker(m));
  for (const TemplateLabel& label : labels) {
    const int m = markers->FindMarker(label.templ);
    if (m < 0) {
      return Status::Error("--template_labels: " + label.templ + " is not a label of the template's marker set");
    }
    if (take.FindMarker(label.take) < 0) {
      return Status::Error("--template_labels: " + label.take + " (for " + label.templ + ") is not in " + take_path);
    }
    specs[m].label = label.take;
  }
  std::set<std::string> seen;
  for (const MarkerSpec& spec : specs) {
    if (!seen.insert(spec.label).second) {
      // An unmapped template marker holds the label too: which of the two is the take's
      // marker is the user's to say.
      return Status::Error("--template_labels: two template markers would be labelled " + spec.label +
                           " (map the template's own " + spec.label + " too)");
    }
  }
  return MarkerSet::Create(skeleton, std::move(specs), markers);
}

}  // namespace mocapsolve
