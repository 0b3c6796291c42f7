// Any lab's marker protocol, measured: each take's markers renamed at random, some dropped,
// model-output-like points added, units and up axis changed; then the marker association
// (problems/marker_solve/marker_association.h) and the subject fit from a template with no
// label map (tasks/fit_skeleton_task.h, association on). Prints one table row and one JSON
// line per take. Variants ("seed"): 1 and 2 renamed P0.. (Scramble); 3, on the takes with
// CMU-style waist labels, a Plug-in Gait export with Nexus model outputs (PluginGait).
// Environment: ASSOC_TAKE=<take> and ASSOC_SEED=<1|2|3> run one take, one variant;
// ASSOC_VERBOSE=1 lists each excluded point with its reason.
// The fit's pose solves use the solver settings' defaults, as `fit_skeleton` and `pipeline
// --subject=auto` do (pose prior, mean-pose and hidden-joint priors); --bare_solve uses a
// default-constructed MarkerSolveOptions instead (no priors: what this tool measured before
// 7 December 2026, a fit no command runs).
//   protocol_association TEMPLATE.json [DATA_DIR] [--fit_max_frames=N] [--no_fit] [--bare_solve]
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <random>
#include <regex>
#include <set>
#include <string>
#include <vector>

#include "io/marker_file.h"
#include "pipeline/subject.h"
#include "problems/marker_solve/marker_association.h"
#include "settings/solver_settings.h"
#include "tasks/fit_skeleton_task.h"

namespace ms = mocapsolve;

namespace {

// The segments a labelled marker of the shipped captures may ride on (joint markers: either
// segment the joint connects). Labels without their subject prefix, upper case.
std::set<std::string> TruthRoles(const std::string& raw) {
  std::string label = raw.substr(raw.find(':') == std::string::npos ? 0 : raw.find(':') + 1);
  const std::vector<std::pair<std::string, std::vector<std::string>>> table = {
      {"^(ARIEL|[LR][FB]HD)$", {"head"}},
      {"^(C7|T10|T7|CLAV|STRN|RBAK|MAN)$", {"chest"}},
      {"^([LR][FBM]WT|[LR]ASI|SACR|P[123])$", {"pelvis"}},
      {"^[LR](SHO|SH|FSH|BSH)$", {"chest", "upper_arm"}},
      {"^[LR](UPA|ARM)$", {"upper_arm"}},
      {"^[LR](ELB|IEL)$", {"upper_arm", "forearm"}},
      {"^[LR](FRM|WRE|FOREARM)$", {"forearm"}},
      {"^[LR](WRA|WRB|IWR|OWR|WR)$", {"forearm", "hand"}},
      {"^[LR](FIN|IHAND|OHAND)$", {"hand"}},
      {"^[LR](THI|HIP|TH[LA][PD])$", {"thigh"}},
      {"^[LR](KNE|KNI|LEPI|PAT)$", {"thigh", "shin"}},
      {"^[LR](SHN|TI[LA][APDT]|TILAT)$", {"shin"}},
      {"^[LR](ANK|LMAL)$", {"shin", "foot"}},
      {"^[LR](HEE|HEL|HEEL|TOE|MT1|MT5|P1MT|P5MT|MFS|MFL)$", {"foot"}},
  };
  std::set<std::string> roles;
  for (const auto& [pattern, names] : table) {
    if (!std::regex_match(label, std::regex(pattern))) continue;
    const bool lateral = names[0] != "head" && names[0] != "pelvis" && !(names[0] == "chest" && names.size() == 1);
    for (const std::string& n : names) {
      if (lateral && n != "chest") roles.insert(std::string(label[0] == 'L' ? "left_" : "right_") + n);
      else roles.insert(n);
    }
  }
  return roles;
}

struct Scrambled {
  ms::MarkerTrajectories take;
  std::map<std::string, std::string> original;  // New label -> original.
  int dropped = 0, added = 0;
};

// Renamed (P0..), 10 % of the markers dropped, 3 model-output-like points added (an angle
// near the origin, a constant point, a point seen in 5 % of frames), metres when the file is
// mm, and the axes rotated so that up is +y or -x.
Scrambled Scramble(const ms::MarkerTrajectories& in, uint32_t seed) {
  std::mt19937 rng(seed);
  std::vector<int> order(in.num_markers());
  for (int m = 0; m < in.num_markers(); ++m) order[m] = m;
  std::shuffle(order.begin(), order.end(), rng);
  const int keep = in.num_markers() - in.num_markers() / 10;
  Scrambled out;
  out.dropped = in.num_markers() - keep;
  out.added = 3;
  std::vector<std::string> labels;
  for (int k = 0; k < keep; ++k) labels.push_back("P" + std::to_string(k));
  for (const char* extra : {"Angle1", "Const2", "Rare3"}) labels.push_back(extra);
  out.take = ms::MarkerTrajectories(labels, in.num_frames());
  out.take.frame_rate = in.frame_rate;
  const bool to_metres = in.unit.metres_per_unit == 0.001;
  out.take.unit = to_metres ? ms::Metres() : in.unit;
  const double scale = to_metres ? 0.001 : 1.0;
  Eigen::Matrix3d rotation;
  rotation << 1, 0, 0, 0, 0, 1, 0, -1, 0;  // z up -> +y up.
  if (seed % 2 == 1) rotation << 0, 0, -1, 0, 1, 0, 1, 0, 0;  // z up -> -x up.
  for (int f = 0; f < in.num_frames(); ++f) {
    for (int k = 0; k < keep; ++k) {
      if (in.valid(f, order[k])) out.take.SetSample(f, k, scale * (rotation * in.position(f, order[k])));
    }
    out.take.SetSample(f, keep, Eigen::Vector3d(10.0 + std::sin(f * 0.05), 20.0, -5.0) * 0.001 * 3);
    out.take.SetSample(f, keep + 1, Eigen::Vector3d(0.1, 0.2, 0.3) * scale * 1000.0 * 0.001);
    if (f % 20 == 0) out.take.SetSample(f, keep + 2, scale * (rotation * Eigen::Vector3d(100.0, 100.0, 1000.0)));
  }
  for (int k = 0; k < keep; ++k) out.original["P" + std::to_string(k)] = in.label(order[k]);
  return out;
}

// A Vicon Nexus Plug-in Gait export of a CMU take: the CMU labels under the Plug-in Gait
// names (front and back waist -> ASI, PSI; shin -> TIB; back -> RBAK), no subject prefix,
// the file's axes and millimetres kept, and Nexus' model outputs written as points, as
// a lab's C3D holds them when its POINT groups do not set them apart: joint angles
// (degrees), forces (N/kg), moments (N mm/kg), powers (W/kg), and two virtual points that
// move with the body (the centre of mass, a hip joint centre).
Scrambled PluginGait(const ms::MarkerTrajectories& in) {
  const std::map<std::string, std::string> rename = {{"LFWT", "LASI"}, {"RFWT", "RASI"}, {"LBWT", "LPSI"},
                                                     {"RBWT", "RPSI"}, {"LSHN", "LTIB"}, {"RSHN", "RTIB"},
                                                     {"RBAC", "RBAK"}};
  const std::vector<std::string> outputs = {"LKneeAngles", "RHipAngles", "LAnkleForce", "RKneeMoment",
                                            "LHipPower", "CentreOfMass", "LHJC"};
  Scrambled out;
  out.added = static_cast<int>(outputs.size());
  std::vector<std::string> labels;
  for (int m = 0; m < in.num_markers(); ++m) {
    std::string name = in.label(m).substr(in.label(m).find(':') == std::string::npos ? 0 : in.label(m).find(':') + 1);
    if (rename.count(name)) name = rename.at(name);
    labels.push_back(name);
    out.original[labels.back()] = in.label(m);
  }
  for (const std::string& o : outputs) labels.push_back(o);
  out.take = ms::MarkerTrajectories(labels, in.num_frames());
  out.take.frame_rate = in.frame_rate;
  out.take.unit = ms::Millimetres();
  const double scale = in.unit.metres_per_unit / 0.001;
  const int n = in.num_markers();
  int pelvis[2] = {-1, -1};
  for (int m = 0; m < n; ++m) {
    if (labels[m] == "LASI") pelvis[0] = m;
    if (labels[m] == "RASI") pelvis[1] = m;
  }
  for (int f = 0; f < in.num_frames(); ++f) {
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();
    int seen = 0;
    for (int m = 0; m < n; ++m) {
      if (!in.valid(f, m)) continue;
      out.take.SetSample(f, m, scale * in.position(f, m));
      centre += scale * in.position(f, m), ++seen;
    }
    const double t = f / std::max(1.0, in.frame_rate);
    const double w = 2.0 * M_PI * t;  // One cycle a second.
    out.take.SetSample(f, n + 0, {35.0 + 30.0 * std::sin(w), 3.0 * std::cos(w), 8.0 * std::sin(2 * w)});
    out.take.SetSample(f, n + 1, {20.0 * std::sin(w + 1.0), -4.0, 6.0 * std::cos(w)});
    out.take.SetSample(f, n + 2, {2.0 * std::sin(w), 1.0, 9.8 + 3.0 * std::cos(w)});
    out.take.SetSample(f, n + 3, {900.0 * std::sin(w), 150.0 * std::cos(w), 60.0});
    out.take.SetSample(f, n + 4, {0.0, 0.0, 2.5 * std::sin(w + 0.5)});
    if (seen > 0) out.take.SetSample(f, n + 5, centre / seen);
    if (pelvis[0] >= 0 && pelvis[1] >= 0 && in.valid(f, pelvis[0]) && in.valid(f, pelvis[1])) {
      const Eigen::Vector3d l = scale * in.position(f, pelvis[0]), r = scale * in.position(f, pelvis[1]);
      out.take.SetSample(f, n + 6, 0.5 * (l + r) + 0.3 * (l - r) + Eigen::Vector3d(0, 0, -80.0));
    }
  }
  return out;
}

double Seconds(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s TEMPLATE.json [DATA_DIR] [--fit_max_frames=N] [--no_fit] [--bare_solve]\n",
                 argv[0]);
    return 1;
  }
  std::string data = "../shared/data";
  int max_frames = 600;
  bool fit = true, bare_solve = false;
  for (int i = 2; i < argc; ++i) {
    if (std::strncmp(argv[i], "--fit_max_frames=", 17) == 0) max_frames = std::atoi(argv[i] + 17);
    else if (std::strcmp(argv[i], "--no_fit") == 0) fit = false;
    else if (std::strcmp(argv[i], "--bare_solve") == 0) bare_solve = true;
    else data = argv[i];
  }
  ms::Subject templ;
  ms::Status status = ms::ReadSubject(argv[1], &templ);
  if (!status.ok()) return std::fprintf(stderr, "%s\n", status.message().c_str()), 1;
  std::printf("| take | seed | markers | associated correctly | excluded (of 3 added) | up, unit | fit RMS mm | torso deg | checks | association s | fit s |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|---|\n");
  for (const char* name : {"02_01", "cmu_02_05", "squat", "JA1Gait35", "nick_freeform_001"}) {
    if (std::getenv("ASSOC_TAKE") && std::string(std::getenv("ASSOC_TAKE")) != name) continue;
    ms::MarkerTrajectories take;
    const std::string path = data + "/c3d/" + name + ".c3d";
    status = ms::ReadMarkerFile(path, &take);
    if (!status.ok()) return std::fprintf(stderr, "%s\n", status.message().c_str()), 1;
    if (const char* pairs_env = std::getenv("ASSOC_PAIRS")) {
      std::vector<int> all;
      for (int m = 0; m < take.num_markers(); ++m) all.push_back(m);
      const ms::PairwiseSpread p = ms::ComputePairwiseSpread(take, all, 0.001, ms::RigidClusterOptions());
      std::string wanted = pairs_env;
      for (int a = 0; a < take.num_markers(); ++a) {
        for (int b = a + 1; b < take.num_markers(); ++b) {
          const std::string la = take.label(a).substr(take.label(a).find(':') + 1), lb = take.label(b).substr(take.label(b).find(':') + 1);
          if (wanted.find("," + la + ",") == std::string::npos || wanted.find("," + lb + ",") == std::string::npos) continue;
          std::fprintf(stderr, "%s %s-%s spread %.1f mm dist %.0f mm\n", name, la.c_str(), lb.c_str(), 1000 * p.spread(a, b), 1000 * p.distance(a, b));
        }
      }
      continue;
    }
    // The CMU and Vicon 53 sets (LFWT, LBWT: the waist markers Plug-in Gait calls ASI, PSI).
    const bool cmu_labels = take.FindMarker("TakeoMonday:LFWT") >= 0 || take.FindMarker("LFWT") >= 0;
    for (uint32_t seed : {1u, 2u, 3u}) {
      // Seed 3: the take as a Plug-in Gait export (takes with CMU-style waist labels).
      if (seed == 3 && !cmu_labels) continue;
      if (std::getenv("ASSOC_SEED") && std::atoi(std::getenv("ASSOC_SEED")) != static_cast<int>(seed)) continue;
      Scrambled s = seed == 3 ? PluginGait(take) : Scramble(take, seed);
      if (const char* dir = std::getenv("ASSOC_WRITE")) {
        const ms::Status written =
            ms::WriteMarkerFile(std::string(dir) + "/" + name + "_" + std::to_string(seed) + ".c3d", s.take);
        if (!written.ok()) std::fprintf(stderr, "ASSOC_WRITE: %s\n", written.message().c_str());
      }
      const auto start = std::chrono::steady_clock::now();
      ms::MarkerAssociation association;
      status = ms::AssociateMarkers(s.take, name, ms::MarkerAssociationOptions(), &association);
      const double association_seconds = Seconds(start);
      int correct = 0, total = 0, excluded_added = 0;
      std::string wrong, kept_added;  // Kept added points: label->role.
      for (const auto& a : association.markers) {
        auto it = s.original.find(a.label);
        if (it == s.original.end()) {
          kept_added += " " + a.label + "->" + a.role;
          continue;
        }
        ++total;
        const std::set<std::string> truth = TruthRoles(it->second);
        if (truth.count(a.role)) ++correct;
        else wrong += " " + it->second + "->" + a.role;
      }
      for (const auto& [label, why] : association.excluded) {
        excluded_added += s.original.count(label) == 0;
        if (std::getenv("ASSOC_VERBOSE")) std::fprintf(stderr, "%s seed %u excluded %s: %s\n", name, seed, label.c_str(), why.c_str());
      }
      const int markers = static_cast<int>(s.original.size());
      if (!status.ok()) std::fprintf(stderr, "%s: %s\n", name, status.message().c_str());
      double rms = -1.0, torso = -1.0, fit_seconds = 0.0;
      bool passed = false;
      if (fit && status.ok()) {
        ms::SkeletonFitInputs inputs;
        inputs.templ = templ;
        inputs.markers_path = name;
        inputs.trajectories = &s.take;
        ms::SkeletonFitSettings settings;
        settings.fit_max_frames = max_frames;
        ms::SkeletonFitResult result;
        const auto fit_start = std::chrono::steady_clock::now();
        ms::MarkerSolveOptions solve;
        if (!bare_solve) {
          status = ms::MarkerSolveOptionsFromSettings(ms::SolverSettings(), templ.skeleton.unit(), &solve);
        }
        if (status.ok()) status = ms::FitSubjectToTake(inputs, settings, solve, &result);
        fit_seconds = Seconds(fit_start);
        if (status.ok()) {
          rms = result.checks.rms_mm, torso = result.checks.torso_error_mean_deg, passed = result.checks.ok();
          if (!passed) std::fprintf(stderr, "%s: %s\n", name, result.checks.failures[0].c_str());
        } else {
          std::fprintf(stderr, "%s: %s\n", name, status.message().c_str());
        }
      }
      std::printf("| %s | %u | %d | %d / %d | %d | %s, %s | %.2f | %.1f | %s | %.3f | %.1f |\n", name, seed, markers,
                  correct, total, excluded_added, association.UpName().c_str(), association.unit.name.c_str(), rms,
                  torso, passed ? "pass" : "FAIL", association_seconds, fit_seconds);
      if (std::getenv("ASSOC_DEBUG")) {
        for (size_t c = 0; c < association.clusters.size(); ++c) {
          std::fprintf(stderr, "  cluster %zu:", c);
          for (const auto& l : association.clusters[c]) {
            const auto* a = association.Find(l);
            std::fprintf(stderr, " %s(%s h%.2f s%.2f c%.2f)", s.original[l].c_str(), a->role.c_str(), a->height, a->side_m, a->confidence);
          }
          std::fprintf(stderr, "\n");
        }
      }
      if (!wrong.empty()) std::fprintf(stderr, "%s seed %u wrong:%s\n", name, seed, wrong.c_str());
      if (!kept_added.empty()) std::fprintf(stderr, "%s seed %u added points kept:%s\n", name, seed, kept_added.c_str());
      std::printf("{\"take\": \"%s\", \"seed\": %u, \"markers\": %d, \"correct\": %d, \"associated\": %d, "
                  "\"excluded_added\": %d, \"fit_rms_mm\": %.3f, \"torso_deg\": %.2f, \"passed\": %s, "
                  "\"association_seconds\": %.4f, \"fit_seconds\": %.2f}\n",
                  name, seed, markers, correct, total, excluded_added, rms, torso, passed ? "true" : "false",
                  association_seconds, fit_seconds);
      std::fflush(stdout);
    }
  }
  return 0;
}
