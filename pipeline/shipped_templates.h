// The subject templates shipped with mocapsolve (data/templates/*.json, embedded into the
// library at build time by cmake/embed_files.cmake, so the files stay their only source):
// what `fit_skeleton` starts from when it is given no template.
#ifndef MOCAPSOLVE_PIPELINE_SHIPPED_TEMPLATES_H_
#define MOCAPSOLVE_PIPELINE_SHIPPED_TEMPLATES_H_

#include <string>

#include "kinematics/status.h"
#include "pipeline/subject.h"

namespace mocapsolve {

// The file the default template comes from ("data/templates/cmu_02.json").
const char* DefaultTemplateName();

// The default template (CMU subject 2: its skeleton and calibrated 41-marker set). An error
// only if the embedded file does not read (a build defect).
Status DefaultTemplateSubject(Subject* subject);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_PIPELINE_SHIPPED_TEMPLATES_H_
