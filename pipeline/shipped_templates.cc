#include "pipeline/shipped_templates.h"

namespace mocapsolve {

extern const char kCmu02Template[];

const char* DefaultTemplateName() { return "data/templates/cmu_02.json"; }

Status DefaultTemplateSubject(Subject* subject) {
  return ParseSubject(kCmu02Template, DefaultTemplateName(), subject);
}

}  // namespace mocapsolve
