// mocapsolve bands --motion=IN --weights=w0,..,wN --out=OUT: frequency band editing
// (Huang, Boulic & Thalmann, eq. 7). signal/motion_pyramid.h.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <string>
#include <vector>

#include "apps/command.h"
#include "apps/option_flags.h"
#include "settings/band_settings.h"
#include "settings/memory_settings.h"
#include "apps/pyramid_flags.h"
#include "apps/common_flags.h"
#include "signal/laplacian_pyramid.h"

namespace mocapsolve {

namespace {

Status ParseWeights(const std::string& text, std::vector<double>* weights) {
  weights->clear();
  size_t begin = 0;
  while (begin <= text.size()) {
    const size_t end = std::min(text.find(',', begin), text.size());
    const std::string item = text.substr(begin, end - begin);
    char* stop = nullptr;
    const double value = std::strtod(item.c_str(), &stop);
    if (item.empty() || *stop != '\0' || !std::isfinite(value)) {
      return Status::Error("--weights: '" + item + "' is not a number");
    }
    weights->push_back(value);
    begin = end + 1;
  }
  if (weights->size() < 2) return Status::Error("--weights: need at least 2 values (N >= 1)");
  return Status::Ok();
}

Status RunBands(const std::vector<std::string>& arguments) {
  if (!arguments.empty()) return Status::Error("unexpected argument '" + arguments[0] + "'");
  BandSettings bands;
  ReadOptionFlags(BandSettingOptions(), &bands);
  if (bands.weights.empty()) return Status::Error("--weights is required");
  std::vector<double> weights;
  Status status = ParseWeights(bands.weights, &weights);
  if (!status.ok()) return status;
  return FilterFromFlags("bands", static_cast<int>(weights.size()) - 1, weights);
}

}  // namespace

extern const Command kBandsCommand = {
    "bands", "frequency band editing of a motion (per-band weights)",
    "mocapsolve bands --motion=IN.bvh|--markers=IN.c3d --weights=2,1.5,0,1 --out=OUT\n\n"
    "Builds a Laplacian pyramid with N = (number of weights) - 1 levels and collapses it\n"
    "with each band scaled: G'_0 = w_N G_N + sum w_l L_l (Huang, Boulic & Thalmann, eq. 7);\n"
    "w_0 weights the finest band. All ones returns the input (to rounding).",
    __FILE__, RunBands,
    {SharedOptions("motion,markers,out,skeleton,skeleton_units,amc_fps,report"),
     BandSettingOptions().Only("weights").options(), PyramidSettingOptions().options(),
     MemoryOption().options()}};

}  // namespace mocapsolve
