// `view` as one function: the files named (markers, a motion, characters, a repair report,
// a falloff, a second take to compare) read, paired and assembled into one ViewScene, and
// its self-contained HTML page (viewer/view_page.h). The CLI (apps/view_command.cc: writes
// the page, prints a line) and Python's view() both call it.
//
// Worlds: with a subject the markers are mapped onto its skeleton (axes, units, label
// prefix) and shown in its frame with the per-frame marker residual of the motion
// (pipeline/take_view.h), whose rotations are first re-expressed on the subject's skeleton
// (a BVH has no rest rotations: one written from an ASF subject folds them into its angles;
// kinematics/motion_on_skeleton.h); a compared motion of the same skeleton is drawn there
// too. Without a subject, each file is shown in its own unit with its up axis from `up`
// (default: guessed per file, viewer/view_scene.h).
#ifndef MOCAPSOLVE_TASKS_VIEW_TASK_H_
#define MOCAPSOLVE_TASKS_VIEW_TASK_H_

#include <string>
#include <vector>

#include "kinematics/status.h"
#include "pipeline/subject.h"
#include "settings/view_settings.h"
#include "viewer/view_scene.h"

namespace mocapsolve {

// The files shown (paths; "" = none). Errors name them as the CLI's flags do (--markers, ...).
struct ViewInputs {
  std::string markers;                  // .c3d/.trc.
  std::string motion;                   // .bvh, .amc (with skeleton), .glb/.gltf, .fbx.
  std::vector<std::string> characters;  // .glb/.gltf, each playing its animation.
  std::string compare;                  // Ghosted: a marker file (with markers) or a motion (with motion).
  std::string repair_report;            // A repair report (JSON): colours markers' repaired samples.
  std::string falloff;                  // A falloff weights CSV (propagate --weights_csv).
  // With markers: the subject they are mapped onto; nullptr: each file in its own world.
  const Subject* subject = nullptr;
  // How motions are read: an .amc's .asf and frame rate; a glTF/FBX clip and sampling
  // rate; the unit of a skeleton that states none.
  std::string skeleton;
  double amc_fps = 120.0;
  std::string animation;
  double sample_fps = 0.0;
  std::string skeleton_units;
};

// The declared options (settings/view_settings.h) and what a front end adds.
struct ViewConfig : ViewSettings {
  std::string page_name;  // Names the page in messages (the CLI's --out).
};

struct ViewResult {
  ViewScene scene;
  std::string html;                   // The page.
  double marker_rms_mm = 0.0;         // With a subject and a motion: the marker residual
  int residual_samples = 0;           // over the take (TakeMarkerRmsMm) and its samples.
  std::vector<std::string> warnings;  // The readers' (an .amc's).
};

// Errors: nothing to show, a compare or repair report without what it goes with, an
// unreadable file (naming it), the viewer's runtime missing (checked before any file is read).
Status RunView(const ViewInputs& inputs, const ViewConfig& config, ViewResult* result);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_TASKS_VIEW_TASK_H_
