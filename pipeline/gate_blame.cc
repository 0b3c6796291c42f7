#include "pipeline/gate_blame.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "kinematics/forward_kinematics.h"

namespace mocapsolve {
namespace {

// A marker holding this share of the error with the few before it is "a few markers".
constexpr double kFewMarkersShare = 0.5;
constexpr int kMostListed = 5;

}  // namespace

std::vector<MarkerBlame> BlameMarkers(const Skeleton& skeleton, const MarkerSet& markers,
                                      const std::vector<std::vector<Eigen::Vector3d>>& observed, const Motion& solved,
                                      double mm) {
  const int num_markers = markers.num_markers();
  const int frames = std::min<int>(observed.size(), solved.num_frames());
  std::vector<std::vector<double>> squared(num_markers, std::vector<double>(frames, 0.0));
  std::vector<int> samples(num_markers, 0);
  FkData fk(skeleton);
  for (int f = 0; f < frames; ++f) {
    ForwardKinematics(skeleton, solved.frames[f], &fk);
    for (int m = 0; m < num_markers; ++m) {
      const Eigen::Vector3d& x = observed[f][m];
      if (!x.allFinite()) continue;
      squared[m][f] = (x - markers.Position(m, fk)).squaredNorm() * mm * mm;
      ++samples[m];
    }
  }
  const int window = std::max(1, std::min(frames, static_cast<int>(std::lround(solved.frame_rate))));
  double total = 0.0;
  std::vector<MarkerBlame> blame;
  for (int m = 0; m < num_markers; ++m) {
    if (samples[m] == 0) continue;
    MarkerBlame b;
    b.label = markers.label(m);
    double sum = 0.0, in_window = 0.0, worst = -1.0;
    for (int f = 0; f < frames; ++f) {
      sum += squared[m][f];
      in_window += squared[m][f] - (f >= window ? squared[m][f - window] : 0.0);
      if (f >= window - 1 && in_window > worst) worst = in_window, b.worst_first = f - window + 1, b.worst_last = f;
    }
    b.rms_mm = std::sqrt(sum / samples[m]);
    b.share = sum;
    total += sum;
    blame.push_back(b);
  }
  for (MarkerBlame& b : blame) b.share = total > 0.0 ? b.share / total : 0.0;
  std::stable_sort(blame.begin(), blame.end(), [](const MarkerBlame& a, const MarkerBlame& b) {
    return a.share > b.share;
  });
  return blame;
}

std::string GateAdvice(const std::vector<MarkerBlame>& blame, const std::string& markers, bool subject_from_take) {
  if (blame.empty()) return "no captured sample of the subject's markers to blame";
  std::string text = "to blame:";
  double held = 0.0;
  int listed = 0;
  for (const MarkerBlame& b : blame) {
    if (listed == kMostListed || (listed > 0 && held >= kFewMarkersShare)) break;
    char item[160];
    std::snprintf(item, sizeof(item), "%s %s %.0f mm RMS (%.0f %% of the error, worst frames %d-%d)",
                  listed > 0 ? "," : "", b.label.c_str(), b.rms_mm, 100.0 * b.share, b.worst_first, b.worst_last);
    text += item;
    held += b.share;
    ++listed;
  }
  const std::string fit = "mocapsolve fit_skeleton --template_subject=<this subject's file> --markers=" + markers +
                          " --out_subject=fitted.json, then --subject=fitted.json";
  if (held >= kFewMarkersShare && listed <= 3) {
    std::string labels;
    for (int k = 0; k < listed; ++k) labels += (k > 0 ? "," : "") + blame[k].label;
    text += "; try: look at these markers in the take (a wrong label, a marker that came off or slid) and read them "
            "as missing with --ignore_markers=" + labels + " (the repair fills them from the motion)";
    // A subject fitted on the take already has this actor's placement.
    if (!subject_from_take) {
      text += "; if they are placed differently on this actor, fit the subject on this take (" + fit + ")";
    }
  } else if (subject_from_take) {
    text += "; the error is spread over the markers: the subject fitted on this take does not fit all of it; try "
            "fitting it on every frame (--fit_max_frames=0) or a subject calibrated on this actor (--subject=FILE)";
  } else {
    text += "; the error is spread over the markers: the subject does not fit this actor; try a subject fitted on "
            "this take (" + fit + ")";
  }
  return text;
}

}  // namespace mocapsolve
