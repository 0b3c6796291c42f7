// The template label maps shipped with mocapsolve (examples/*_to_cmu_labels.txt, embedded
// into the library at build time by cmake/embed_files.cmake, so the files stay their only
// source) and the rule `fit_skeleton --template_labels=auto` (the default) applies one by.
//
// A map M of pairs (t_i, k_i) (template label, take label; template_labels.h) fits a take K
// and a template set T when T holds every t_i, K holds every k_i, K holds no t_i (the take
// does not use the template's labels: a CMU-labelled take fits no map), and no marker of T
// outside the map is labelled like some k_i (the renaming would give two markers one
// label). `auto` applies the first shipped map that fits, none if none does.
#ifndef MOCAPSOLVE_PROBLEMS_MARKER_SOLVE_TEMPLATE_LABEL_MAPS_H_
#define MOCAPSOLVE_PROBLEMS_MARKER_SOLVE_TEMPLATE_LABEL_MAPS_H_

#include <string>
#include <vector>

#include "kinematics/marker_set.h"
#include "kinematics/marker_trajectories.h"
#include "kinematics/status.h"
#include "problems/marker_solve/template_labels.h"

namespace mocapsolve {

// The setting's values that pick a shipped map and that apply none ("" too).
inline constexpr char kTemplateLabelsAuto[] = "auto";
inline constexpr char kTemplateLabelsNone[] = "none";

struct ShippedTemplateLabels {
  const char* name;  // The file in the source tree ("examples/ais_to_cmu_labels.txt").
  const char* text;  // Its contents.
};

// The shipped maps, in a fixed order (the first that fits wins).
const std::vector<ShippedTemplateLabels>& ShippedTemplateLabelMaps();

// Whether `labels` fits the take `take` and the template set `templ` (the rule above).
bool TemplateLabelsFitTake(const std::vector<TemplateLabel>& labels, const MarkerSet& templ,
                           const MarkerTrajectories& take);

// The first shipped map that fits: its name and pairs; `name` "" and `labels` empty when
// none does. An error only if a shipped map does not parse (a build defect).
Status ChooseShippedTemplateLabels(const MarkerSet& templ, const MarkerTrajectories& take, std::string* name,
                                   std::vector<TemplateLabel>* labels);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_PROBLEMS_MARKER_SOLVE_TEMPLATE_LABEL_MAPS_H_
