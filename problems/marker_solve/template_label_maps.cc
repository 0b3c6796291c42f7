#include "problems/marker_solve/template_label_maps.h"

#include <set>
#include <utility>

namespace mocapsolve {

// Defined in the build's generated/template_label_maps.cc (CMakeLists.txt lists the files).
extern const char kAisToCmuLabels[];
extern const char kVicon53ToCmuLabels[];

const std::vector<ShippedTemplateLabels>& ShippedTemplateLabelMaps() {
  static const std::vector<ShippedTemplateLabels> maps = {
      {"examples/ais_to_cmu_labels.txt", kAisToCmuLabels},
      {"examples/vicon53_to_cmu_labels.txt", kVicon53ToCmuLabels},
  };
  return maps;
}

bool TemplateLabelsFitTake(const std::vector<TemplateLabel>& labels, const MarkerSet& templ,
                           const MarkerTrajectories& take) {
  if (labels.empty()) return false;
  std::set<std::string> mapped, take_labels;
  for (const TemplateLabel& label : labels) {
    if (templ.FindMarker(label.templ) < 0 || take.FindMarker(label.take) < 0) return false;
    if (take.FindMarker(label.templ) >= 0) return false;
    mapped.insert(label.templ);
    take_labels.insert(label.take);
  }
  for (int m = 0; m < templ.num_markers(); ++m) {
    if (!mapped.count(templ.label(m)) && take_labels.count(templ.label(m))) return false;
  }
  return true;
}

Status ChooseShippedTemplateLabels(const MarkerSet& templ, const MarkerTrajectories& take, std::string* name,
                                   std::vector<TemplateLabel>* labels) {
  name->clear();
  labels->clear();
  for (const ShippedTemplateLabels& map : ShippedTemplateLabelMaps()) {
    std::vector<TemplateLabel> pairs;
    Status status = ParseTemplateLabels(map.text, map.name, &pairs);
    if (!status.ok()) return status;
    if (TemplateLabelsFitTake(pairs, templ, take)) {
      *name = map.name;
      *labels = std::move(pairs);
      return Status::Ok();
    }
  }
  return Status::Ok();
}

}  // namespace mocapsolve
