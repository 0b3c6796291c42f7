#include <algorithm>
#include "io/c3d_points.h"

#include <map>
#include <set>
#include <unordered_map>
#include <unordered_set>

#include "kinematics/marker_trajectories.h"
#include "kinematics/quote_token.h"

namespace mocapsolve {
namespace {

bool EndsWith(const std::string& text, const std::string& suffix) {
  return text.size() > suffix.size() &&
         text.compare(text.size() - suffix.size(), suffix.size(), suffix) == 0;
}

std::string JoinQuoted(const std::vector<std::string>& items) {
  std::string out;
  for (size_t i = 0; i < items.size() && i < 8; ++i) out += (i == 0 ? "" : ", ") + QuoteToken(items[i]);
  return items.size() > 8 ? out + ", ..." : out;
}

// Duplicate labels numbered: the second RKNE becomes RKNE#2 (or the next free number).
void NumberDuplicates(std::vector<std::string>* labels, std::vector<std::string>* warnings) {
  std::unordered_set<std::string> taken(labels->begin(), labels->end());
  std::unordered_map<std::string, std::vector<int>> uses;  // Original label -> points.
  std::vector<std::string> order;                          // Repeated labels, first seen first.
  std::unordered_set<std::string> seen;
  for (int m = 0; m < static_cast<int>(labels->size()); ++m) {
    const std::string label = (*labels)[m];
    std::vector<int>& points = uses[label];
    points.push_back(m);
    if (points.size() == 1) continue;
    if (points.size() == 2) order.push_back(label);
    for (int n = static_cast<int>(points.size());; ++n) {
      const std::string candidate = label + "#" + std::to_string(n);
      if (taken.insert(candidate).second) {
        (*labels)[m] = candidate;
        break;
      }
    }
  }
  if (order.empty()) return;
  std::string text;
  for (size_t i = 0; i < order.size(); ++i) {
    if (i == 5) {
      text += "; and " + std::to_string(order.size() - 5) + " more";
      break;
    }
    const std::vector<int>& points = uses[order[i]];
    std::string numbers, names;
    for (size_t k = 0; k < points.size() && k < 4; ++k) {
      numbers += (k == 0 ? "" : ", ") + std::to_string(points[k] + 1);
      names += (k == 0 ? "" : ", ") + (*labels)[points[k]];
    }
    if (points.size() > 4) {
      numbers += ", ... (" + std::to_string(points.size()) + " in all)";
      names += ", ...";
    }
    text += (i == 0 ? "" : "; ") + QuoteToken(order[i]) + " (points " + numbers + " read as " + names + ")";
  }
  warnings->push_back("POINT:LABELS: " + std::to_string(order.size()) + " label" +
                      (order.size() == 1 ? " is" : "s are") + " used more than once, renamed: " + text);
}

// The prefixes some label carries: the file's list, or the labels' "Name:" parts.
std::vector<std::string> SubjectsPresent(const C3dPointLists& lists) {
  std::vector<std::string> present;
  if (!lists.subject_prefixes.empty()) {
    for (const std::string& prefix : lists.subject_prefixes) {
      for (const std::string& label : lists.labels) {
        if (label.size() > prefix.size() && label.compare(0, prefix.size(), prefix) == 0) {
          present.push_back(prefix);
          break;
        }
      }
    }
    return present;
  }
  std::set<std::string> found;
  for (const std::string& label : lists.labels) {
    const std::string prefix = SplitSubjectPrefix(label).prefix;
    if (!prefix.empty() && found.insert(prefix).second) present.push_back(prefix);
  }
  return present;
}

// The prefix `choice` names: a prefix itself, a prefix without its ':', or a SUBJECTS:NAMES
// entry (paired with LABEL_PREFIXES by position). "" when none.
std::string ChosenPrefix(const C3dPointLists& lists, const std::vector<std::string>& present,
                         const std::string& choice) {
  for (const std::string& prefix : present) {
    if (prefix == choice || prefix == choice + ":") return prefix;
  }
  for (size_t i = 0; i < lists.subject_names.size() && i < lists.subject_prefixes.size(); ++i) {
    if (lists.subject_names[i] != choice) continue;
    for (const std::string& prefix : present) {
      if (prefix == lists.subject_prefixes[i]) return prefix;
    }
  }
  return "";
}

}  // namespace

const std::vector<std::string>& C3dModelOutputKinds() {
  static const std::vector<std::string> kinds = {"ANGLES", "FORCES", "MOMENTS", "POWERS", "REACTIONS", "SCALARS"};
  return kinds;
}

bool IsPluginGaitOutputName(const std::string& name, std::string* kind) {
  static const std::set<std::string> virtual_points = [] {
    std::set<std::string> points = {"CentreOfMass", "CentreOfMassFloor"};
    for (const char* segment : {"PEL", "HED", "TRX", "LCL", "RCL", "LFE", "RFE", "LTI", "RTI", "LFO", "RFO",
                                "LTO", "RTO", "LHU", "RHU", "LRA", "RRA", "LHN", "RHN"}) {
      for (const char* axis : {"O", "A", "L", "P"}) points.insert(std::string(segment) + axis);
    }
    return points;
  }();
  static const std::vector<std::pair<std::string, std::string>> suffixes = {
      {"Angles", "ANGLES"}, {"Angle", "ANGLES"}, {"Force", "FORCES"}, {"GRF", "FORCES"},
      {"Moment", "MOMENTS"}, {"Power", "POWERS"}};
  std::string found;
  bool is_output = virtual_points.count(name) > 0;
  for (const auto& [suffix, suffix_kind] : suffixes) {
    if (is_output) break;
    // At least two letters before the suffix: "LHipAngles", not "Force" or "XForce".
    if (EndsWith(name, suffix) && name.size() >= suffix.size() + 2) is_output = true, found = suffix_kind;
  }
  if (is_output && kind != nullptr) *kind = found;
  return is_output;
}

Status SelectC3dPoints(const C3dPointLists& lists, const std::string& subject_prefix,
                       bool include_model_outputs, C3dPointSelection* selection,
                       const std::string& preferred_subject_prefix) {
  C3dPointSelection out;
  const int num_points = static_cast<int>(lists.labels.size());
  out.labels = lists.labels;
  out.roles.assign(num_points, C3dPointSelection::Role::kMarker);
  out.kinds.assign(num_points, "");

  // Subjects.
  const std::vector<std::string> present = SubjectsPresent(lists);
  const std::string where = lists.subject_prefixes.empty() ? lists.labels_field + " (subject prefixes)"
                                                           : "SUBJECTS:LABEL_PREFIXES";
  std::string chosen;
  if (!subject_prefix.empty()) {
    chosen = ChosenPrefix(lists, present, subject_prefix);
    if (chosen.empty()) {
      return Status::Error(where + ": no subject " + QuoteToken(subject_prefix) + " (" +
                           (present.empty() ? "the file has no subject prefixes" : "subjects: " + JoinQuoted(present)) +
                           ")");
    }
  } else if (present.size() > 1) {
    // No choice: the subject the caller prefers (a subject file's own prefix), else the one
    // with the most points (a body, not a prop's few), named in a warning.
    chosen = preferred_subject_prefix.empty() ? "" : ChosenPrefix(lists, present, preferred_subject_prefix);
    const bool preferred = !chosen.empty();
    size_t most = 0;
    for (const std::string& prefix : present) {
      const size_t points = std::count_if(lists.labels.begin(), lists.labels.end(), [&](const std::string& label) {
        return label.size() > prefix.size() && label.compare(0, prefix.size(), prefix) == 0;
      });
      if (!preferred && points > most) most = points, chosen = prefix;
    }
    out.warnings.push_back(where + ": " + std::to_string(present.size()) + " subjects (" + JoinQuoted(present) +
                           "); reading " + QuoteToken(chosen) +
                           (preferred ? " (the subject's own prefix)" : " (the one with the most points)") +
                           "; --subject_prefix=NAME reads another");
  }
  if (!chosen.empty()) {
    for (int m = 0; m < num_points; ++m) {
      std::string& label = out.labels[m];
      if (label.size() > chosen.size() && label.compare(0, chosen.size(), chosen) == 0) {
        label = label.substr(chosen.size());
        continue;
      }
      for (const std::string& other : present) {
        if (label.size() > other.size() && label.compare(0, other.size(), other) == 0) {
          out.roles[m] = C3dPointSelection::Role::kDropped;
          ++out.num_dropped;
          break;
        }
      }
    }
  } else {
    out.subject_prefixes = lists.subject_prefixes;
  }
  // After the prefixes are stripped, so that "Daphnee:LASI" and a bare "LASI" do not clash.
  NumberDuplicates(&out.labels, &out.warnings);

  // Model outputs: listed (raw label or without prefix), or named by Plug-in Gait.
  std::map<std::string, std::string> listed;  // Label -> kind.
  for (const auto& [kind, labels] : lists.output_lists) {
    for (const std::string& label : labels) {
      if (label.empty()) continue;
      listed.emplace(label, kind);
      listed.emplace(SplitSubjectPrefix(label, lists.subject_prefixes).name, kind);
    }
  }
  for (int m = 0; m < num_points; ++m) {
    if (out.roles[m] != C3dPointSelection::Role::kMarker) continue;
    const std::string name = SplitSubjectPrefix(lists.labels[m], lists.subject_prefixes).name;
    std::string kind;
    auto it = listed.find(lists.labels[m]);
    if (it == listed.end()) it = listed.find(name);
    const bool is_output = it != listed.end() ? (kind = it->second, true) : IsPluginGaitOutputName(name, &kind);
    if (!is_output || include_model_outputs) continue;
    out.roles[m] = C3dPointSelection::Role::kModelOutput;
    out.kinds[m] = kind;
    ++out.num_model_outputs;
  }
  if (out.num_model_outputs > 0) {
    out.warnings.push_back(std::to_string(out.num_model_outputs) + " of " + std::to_string(num_points) +
                           " points are model outputs (POINT:ANGLES/FORCES/MOMENTS/POWERS/REACTIONS/SCALARS, "
                           "Plug-in Gait virtual points), not read as markers (--include_model_outputs keeps them)");
  }
  *selection = std::move(out);
  return Status::Ok();
}

}  // namespace mocapsolve
