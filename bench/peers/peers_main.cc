// mocapsolve_peers_bench: our kinematics and per-frame marker IK beside the established
// kinematics libraries Debian ships (Orocos KDL, MuJoCo, DART), on the same skeleton and
// markers (bench/peers/peer_model.h for how each library's model is built).
//
// Problem: a clip's skeleton (default CMU 01_01 BVH, 31 joints, 96 dofs) and 3 synthetic
// markers per joint (problems/marker_solve/synthetic_marker_set.h, seed 1: 93 markers),
// observed noise-free at the clip's poses. Every peer's FK is first checked against ours
// (joint origins and markers, max |difference| <= --tolerance, skeleton units) at every
// --check_stride-th frame; a peer that disagrees stops the run (exit 1).
//
// Measures, each per frame:
//   fk   world frames of every joint (ours: ForwardKinematics);
//   jac  FK plus the 3 #markers x 96 positional Jacobian of every marker (ours:
//        ForwardKinematics + MarkerSetJacobian);
//   ik   per-frame marker IK over --ik_frames frames, warm-started from the previous
//        frame's solution (frame 0 from the clip's own pose), every solver stopping once
//        the RMS marker residual is <= --ik_target_rms (skeleton units) or after
//        --ik_max_iterations; the RMS each reached is reported beside its time. IK
//        starts at --ik_first_frame (1: frame 0 of the CMU BVH conversions is a T-pose). Ours: the
//        tree DLS kernel (dls), the generic DLS (dls_generic) and Ceres (ceres), via
//        MarkerFrameSolver with an absolute-cost stop (DLS) or an iteration callback
//        (Ceres) at the target, their own tolerances left at the defaults.
//
// Modes: --interleaved runs every (measure, library) case once per round for --rounds
// rounds, interleaved, timing process CPU time, and prints each case's median per-frame
// time and its ratio to ours ("peer / ours"), plus one "PEERS key value" line per figure
// and, with --json, a JSON file (what `mocapsolve bench --problem=peers` runs).
// --check_only runs the FK agreement check and exits. Otherwise Google Benchmark runs
// the same cases (one iteration = one frame; --benchmark_* flags apply).
#include <time.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>
#include <ceres/iteration_callback.h>
#include <gflags/gflags.h>

#include "bench/peers/peer_model.h"
#ifdef MOCAPSOLVE_HAVE_DART
#include "bench/peers/dart_skeleton.h"
#endif
#include "io/atomic_file.h"
#include "io/comma_list.h"
#include "io/json_writer.h"
#include "io/motion_file.h"
#include "kinematics/forward_kinematics.h"
#include "kinematics/marker_set.h"
#include "problems/marker_solve/marker_frame_solver.h"
#include "problems/marker_solve/synthetic_marker_set.h"

DEFINE_string(motion, "", "Clip whose skeleton and poses are used (default: $MOCAPSOLVE_DATA/bvh/01_01.bvh).");
DEFINE_string(peers, "", "Comma-separated peers (default: every one built: kdl, mujoco, dart).");
DEFINE_bool(interleaved, false, "Run the interleaved harness (table, ratios, PEERS lines) instead of Google Benchmark.");
DEFINE_bool(check_only, false, "Only check every peer's FK against ours, then exit.");
DEFINE_int32(rounds, 5, "Interleaved rounds; the median per-frame CPU time is reported.");
DEFINE_string(json, "", "With --interleaved: write the figures as JSON to this file.");
DEFINE_double(tolerance, 1e-9, "FK agreement required of every peer (max |difference|, skeleton units).");
DEFINE_int32(check_stride, 25, "Check FK agreement at every N-th frame.");
DEFINE_int32(fk_frames, 20000, "FK: frames timed per round (the clip repeated).");
DEFINE_int32(jac_frames, 2000, "FK + Jacobian: frames timed per round (the clip repeated).");
DEFINE_int32(ik_frames, 120, "IK: consecutive frames solved per round.");
DEFINE_int32(ik_first_frame, 1, "IK: first frame used (01_01.bvh's frame 0 is an added T-pose, far from frame 1).");
DEFINE_int32(ik_stride, 1, "IK: use every N-th frame of the clip (larger steps between warm starts).");
DEFINE_double(ik_target_rms, 1e-4, "IK: stop at this RMS marker residual (skeleton units).");
DEFINE_int32(ik_max_iterations, 100, "IK: iteration limit per frame, every solver.");
DEFINE_string(dart_gradient, "dls", "DART IK: gradient method per end effector, dls or transpose.");
DEFINE_double(dart_damping, 2.0, "DART IK: JacobianDLS damping (DART's default 0.05; 2 was the best tried, BENCHMARKS.md).");
DEFINE_double(dart_step_size, 0.1, "DART IK: GradientDescentSolver step size (DART's default).");
DEFINE_int32(dart_ik_frames, 5, "DART IK: solve only the first N IK frames (DART takes seconds per frame).");
DEFINE_int32(dart_chunk, 10, "DART IK: solver iterations per solveAndApply call (RMS checked between calls).");

namespace mocapsolve::peers {
namespace {

double CpuSeconds() {
  timespec t;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return t.tv_sec + 1e-9 * t.tv_nsec;
}

// The problem all cases share.
struct PeersProblem {
  Skeleton skeleton;
  Motion motion;
  MarkerSet markers;
  std::vector<std::vector<Eigen::Vector3d>> observed;  // Per IK frame.
  std::vector<Pose> ik_poses;                          // The clip's poses at the IK frames.
  std::string input;
};

Status LoadProblem(PeersProblem* problem) {
  std::string path = FLAGS_motion;
  if (path.empty()) {
    const char* root = std::getenv("MOCAPSOLVE_DATA");
    path = std::string(root != nullptr && *root ? root : MOCAPSOLVE_SOURCE_DIR "/../shared/data") + "/bvh/01_01.bvh";
  }
  Status status = ReadMotionFile(path, MotionFileOptions(), &problem->skeleton, &problem->motion);
  if (!status.ok()) return status;
  if (problem->motion.frames.empty()) return Status::Error(path + ": no frames");
  problem->input = path;
  problem->markers = MakeSyntheticMarkerSet(problem->skeleton, 3, 1);
  FkData fk(problem->skeleton);
  for (int f = std::max(0, FLAGS_ik_first_frame);
       f < problem->motion.num_frames() && static_cast<int>(problem->ik_poses.size()) < FLAGS_ik_frames;
       f += std::max(1, FLAGS_ik_stride)) {
    const Pose& pose = problem->motion.frames[f];
    ForwardKinematics(problem->skeleton, pose, &fk);
    problem->observed.emplace_back();
    for (int m = 0; m < problem->markers.num_markers(); ++m) {
      problem->observed.back().push_back(problem->markers.Position(m, fk));
    }
    problem->ik_poses.push_back(pose);
  }
  if (problem->observed.empty()) return Status::Error("--ik_first_frame: past the clip's last frame");
  return CheckPeerCompatible(problem->skeleton, problem->markers);
}

// Max |peer - ours| over joint origins and markers at every stride-th frame.
double FkDisagreement(const PeersProblem& problem, PeerModel* peer) {
  FkData fk(problem.skeleton);
  std::vector<Eigen::Vector3d> joints, markers;
  double worst = 0.0;
  for (int f = 0; f < problem.motion.num_frames(); f += std::max(1, FLAGS_check_stride)) {
    const Pose& pose = problem.motion.frames[f];
    ForwardKinematics(problem.skeleton, pose, &fk);
    peer->SetPose(pose);
    peer->ForwardKinematics();
    peer->JointPositions(&joints);
    peer->MarkerPositions(&markers);
    for (int j = 0; j < problem.skeleton.num_joints(); ++j) {
      worst = std::max(worst, (joints[j] - fk.world_positions[j]).cwiseAbs().maxCoeff());
    }
    for (int m = 0; m < problem.markers.num_markers(); ++m) {
      worst = std::max(worst, (markers[m] - problem.markers.Position(m, fk)).cwiseAbs().maxCoeff());
    }
  }
  return worst;
}

// One (measure, library) case: Run(frame) does frame's work; Reset() before a pass.
struct Case {
  std::string measure;  // fk | jac | ik
  std::string library;  // mocapsolve (ours) or the peer
  std::string solver;   // ik: dls, dls_generic, ceres, or the peer's method
  std::function<void()> reset;
  std::function<void(int)> run;
  // IK bookkeeping of the last pass.
  std::vector<double> rms;
  std::vector<int> iterations;
  int failures = 0;  // IK solves that returned an error.
  int frames = 0;    // Frames per pass (0: the measure's default).
  std::string label() const { return measure + "/" + library + (solver.empty() ? "" : "/" + solver); }
};

Case MakeCase(std::string measure, std::string library, std::string solver, std::function<void()> reset,
              std::function<void(int)> run) {
  Case c;
  c.measure = std::move(measure);
  c.library = std::move(library);
  c.solver = std::move(solver);
  c.reset = std::move(reset);
  c.run = std::move(run);
  return c;
}

// Stops Ceres once the cost reaches the target (ceres has no absolute-cost rule).
class CostTargetCallback : public ceres::IterationCallback {
 public:
  explicit CostTargetCallback(double cost) : cost_(cost) {}
  ceres::CallbackReturnType operator()(const ceres::IterationSummary& summary) override {
    return summary.cost <= cost_ ? ceres::SOLVER_TERMINATE_SUCCESSFULLY : ceres::SOLVER_CONTINUE;
  }

 private:
  double cost_;
};

class Harness {
 public:
  Status Build(const PeersProblem& problem) {
    problem_ = &problem;
    std::vector<std::string> names = SplitCommaList(FLAGS_peers);
    if (names.empty()) names = AvailablePeers();
    for (const std::string& name : names) {
      std::unique_ptr<PeerModel> peer;
      Status status = Status::Ok();
#ifdef MOCAPSOLVE_HAVE_DART
      if (name == "dart") {
        DartIkSettings settings;
        settings.gradient = FLAGS_dart_gradient;
        settings.damping = FLAGS_dart_damping;
        settings.step_size = FLAGS_dart_step_size;
        settings.chunk = std::max(1, FLAGS_dart_chunk);
        peer = MakeDartSkeleton(problem.skeleton, problem.markers, settings);
      } else
#endif
      {
        status = MakePeerModel(name, problem.skeleton, problem.markers, &peer);
      }
      if (!status.ok()) return status;
      const double disagreement = FkDisagreement(problem, peer.get());
      std::printf("check %-8s FK max |peer - ours| = %.3g (tolerance %.3g): %s; %s\n", name.c_str(), disagreement,
                  FLAGS_tolerance, disagreement <= FLAGS_tolerance ? "agree" : "DISAGREE",
                  peer->description().c_str());
      figures_.push_back({"fk_agreement_" + name, disagreement});
      if (!(disagreement <= FLAGS_tolerance)) {
        return Status::Error("peers: " + name + "'s FK differs from ours by " + std::to_string(disagreement) +
                             " (tolerance " + std::to_string(FLAGS_tolerance) + ")");
      }
      peers_.push_back(std::move(peer));
    }
    return Status::Ok();
  }

  void MakeCases() {
    const PeersProblem& p = *problem_;
    const int clip = p.motion.num_frames();
    fk_ = FkData(p.skeleton);
    // FK and FK + Jacobian: ours, then each peer (frames converted once, untimed).
    cases_.push_back(MakeCase("fk", "mocapsolve", "", [] {}, [this, &p, clip](int f) {
                        ForwardKinematics(p.skeleton, p.motion.frames[f % clip], &fk_);
                        benchmark::DoNotOptimize(fk_.world_positions.back().x());
                      }));
    for (auto& peer : peers_) {
      PeerModel* model = peer.get();
      auto& frames = coordinates_[model->name()];
      for (const Pose& pose : p.motion.frames) {
        model->SetPose(pose);
        frames.emplace_back();
        model->GetCoordinates(&frames.back());
      }
      cases_.push_back(MakeCase("fk", model->name(), "", [] {}, [model, &frames, clip](int f) {
                          model->SetCoordinates(frames[f % clip]);
                          model->ForwardKinematics();
                        }));
    }
    cases_.push_back(MakeCase("jac", "mocapsolve", "", [] {}, [this, &p, clip](int f) {
                        ForwardKinematics(p.skeleton, p.motion.frames[f % clip], &fk_);
                        MarkerSetJacobian(p.skeleton, p.markers, fk_, &rotations_, &jacobian_);
                        benchmark::DoNotOptimize(jacobian_(0, 0));
                      }));
    for (auto& peer : peers_) {
      PeerModel* model = peer.get();
      auto& frames = coordinates_[model->name()];
      cases_.push_back(MakeCase("jac", model->name(), "", [] {}, [model, &frames, clip](int f) {
                          model->SetCoordinates(frames[f % clip]);
                          model->FkAndJacobian();
                        }));
    }
    // IK.
    const int nm = p.markers.num_markers();
    const double target_cost = 0.5 * nm * FLAGS_ik_target_rms * FLAGS_ik_target_rms;
    callback_ = std::make_unique<CostTargetCallback>(target_cost);
    for (const char* solver : {"dls", "dls_generic", "ceres"}) {
      MarkerSolveOptions options;
      ParseSolverKind(solver, &options.solver);
      options.dls.max_iterations = FLAGS_ik_max_iterations;
      options.dls.absolute_cost_tolerance = target_cost;
      options.ceres = DefaultFrameCeresOptions();
      options.ceres.max_num_iterations = FLAGS_ik_max_iterations;
      options.ceres.callbacks.push_back(callback_.get());
      ours_.push_back(std::make_unique<MarkerFrameSolver>(p.skeleton, p.markers, options));
      MarkerFrameSolver* frame_solver = ours_.back().get();
      auto pose = std::make_shared<Pose>();
      const int index = static_cast<int>(cases_.size());
      cases_.push_back(MakeCase("ik", "mocapsolve", solver, [this, index, pose, &p] {
                          *pose = p.ik_poses[0];
                          cases_[index].rms.clear();
                          cases_[index].iterations.clear();
                          cases_[index].failures = 0;
                        },
                        [this, index, pose, frame_solver, &p](int f) {
                          FrameSolveReport report;
                          if (!frame_solver->Solve(p.observed[f % p.observed.size()], pose.get(), &report).ok()) {
                            ++cases_[index].failures;
                          }
                          cases_[index].rms.push_back(report.rms_marker_error);
                          cases_[index].iterations.push_back(report.iterations);
                        }));
    }
    IkTarget target;
    target.target_rms = FLAGS_ik_target_rms;
    target.max_iterations = FLAGS_ik_max_iterations;
    for (auto& peer : peers_) {
      PeerModel* model = peer.get();
      if (!model->has_ik()) continue;
      const int index = static_cast<int>(cases_.size());
      std::string method = model->name() == "kdl" ? "TreeIkSolverPos_NR_JL" : "WholeBodyIK";
      cases_.push_back(MakeCase("ik", model->name(), method, [this, index, model, &p] {
                          model->SetPose(p.ik_poses[0]);
                          cases_[index].rms.clear();
                          cases_[index].iterations.clear();
                          cases_[index].failures = 0;
                        },
                        [this, index, model, target, &p](int f) {
                          IkResult result;
                          if (!model->SolveIk(p.observed[f % p.observed.size()], target, &result).ok()) {
                            ++cases_[index].failures;
                          }
                          cases_[index].rms.push_back(result.rms);
                          cases_[index].iterations.push_back(result.iterations);
                        }));
      if (model->name() == "dart") {
        cases_.back().frames = std::min(static_cast<int>(p.observed.size()), std::max(1, FLAGS_dart_ik_frames));
      }
    }
  }

  std::vector<Case>& cases() { return cases_; }
  const PeersProblem& problem() const { return *problem_; }
  std::vector<std::pair<std::string, double>>& figures() { return figures_; }

 private:
  const PeersProblem* problem_ = nullptr;
  std::vector<std::unique_ptr<PeerModel>> peers_;
  std::map<std::string, std::vector<Eigen::VectorXd>> coordinates_;
  std::vector<Case> cases_;
  std::vector<std::unique_ptr<MarkerFrameSolver>> ours_;
  std::unique_ptr<CostTargetCallback> callback_;
  FkData fk_;
  std::vector<Eigen::Matrix3d> rotations_;
  Eigen::MatrixXd jacobian_;
  std::vector<std::pair<std::string, double>> figures_;
};

double Median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  return values.empty() ? 0.0 : values[values.size() / 2];
}

int RunInterleaved(Harness* harness) {
  std::vector<Case>& cases = harness->cases();
  const PeersProblem& p = harness->problem();
  std::vector<std::vector<double>> per_frame(cases.size());
  for (int round = 0; round < std::max(1, FLAGS_rounds); ++round) {
    for (size_t c = 0; c < cases.size(); ++c) {
      Case& k = cases[c];
      const int frames = k.frames > 0                ? k.frames
                         : k.measure == "ik"   ? static_cast<int>(p.observed.size())
                         : k.measure == "jac" ? FLAGS_jac_frames
                                               : FLAGS_fk_frames;
      k.reset();
      const double start = CpuSeconds();
      for (int f = 0; f < frames; ++f) k.run(f);
      per_frame[c].push_back((CpuSeconds() - start) / frames);
    }
    std::fprintf(stderr, "peers: round %d of %d done\n", round + 1, FLAGS_rounds);
  }
  std::map<std::string, double> ours;  // Per measure: ours (ik: the dls kernel).
  for (size_t c = 0; c < cases.size(); ++c) {
    if (cases[c].library == "mocapsolve" && !ours.count(cases[c].measure)) ours[cases[c].measure] = Median(per_frame[c]);
  }
  std::printf("\n%-5s %-10s %-22s %14s %12s %11s %11s %8s %8s\n", "what", "library", "solver", "per frame",
              "frames/s", "peer/ours", "mean RMS", "max RMS", "iters");
  JsonObject json;
  std::vector<JsonObject> records;
  auto& figures = harness->figures();
  for (size_t c = 0; c < cases.size(); ++c) {
    const Case& k = cases[c];
    const double t = Median(per_frame[c]);
    const double ratio = t / ours[k.measure];
    char time[32];
    if (t < 1e-6) {
      std::snprintf(time, sizeof(time), "%.0f ns", 1e9 * t);
    } else if (t < 1e-3) {
      std::snprintf(time, sizeof(time), "%.2f us", 1e6 * t);
    } else {
      std::snprintf(time, sizeof(time), "%.2f ms", 1e3 * t);
    }
    double mean_rms = 0.0, max_rms = 0.0, mean_iterations = 0.0;
    int reached = 0;
    for (size_t i = 0; i < k.rms.size(); ++i) {
      mean_rms += k.rms[i] / k.rms.size();
      max_rms = std::max(max_rms, k.rms[i]);
      mean_iterations += static_cast<double>(k.iterations[i]) / k.rms.size();
      reached += k.rms[i] <= FLAGS_ik_target_rms * (1 + 1e-9);
    }
    std::printf("%-5s %-10s %-22s %14s %12.1f %11.2f", k.measure.c_str(), k.library.c_str(),
                k.solver.empty() ? "-" : k.solver.c_str(), time, 1.0 / t, ratio);
    if (k.measure == "ik") {
      if (mean_iterations < 0) {  // KDL does not report its iterations.
        std::printf(" %11.3g %8.3g %8s  %d/%zu at target", mean_rms, max_rms, "n/a", reached, k.rms.size());
      } else {
        std::printf(" %11.3g %8.3g %8.1f  %d/%zu at target", mean_rms, max_rms, mean_iterations, reached, k.rms.size());
      }
      if (k.failures > 0) std::printf(", %d failed", k.failures);
    }
    std::printf("\n");
    const std::string key = k.measure + "_" + k.library + (k.solver.empty() ? "" : "_" + k.solver);
    figures.push_back({key + "_us_per_frame", 1e6 * t});
    figures.push_back({key + "_ratio_to_ours", ratio});
    JsonObject record;
    record.Add("measure", k.measure).Add("library", k.library).Add("solver", k.solver)
        .Add("seconds_per_frame", t).Add("frames_per_second", 1.0 / t).Add("ratio_to_ours", ratio);
    if (k.measure == "ik") {
      figures.push_back({key + "_mean_rms", mean_rms});
      record.Add("mean_rms", mean_rms).Add("max_rms", max_rms).Add("mean_iterations", mean_iterations)
          .Add("frames_at_target", reached).Add("frames", static_cast<int>(k.rms.size()));
    }
    records.push_back(record);
  }
  std::printf("\nratios are peer / ours (ik: / our tree DLS kernel); CPU time, median of %d interleaved rounds; "
              "%s, %d joints, %d markers; ik: %zu frames, target RMS %.3g units, limit %d iterations\n",
              FLAGS_rounds, p.input.c_str(), p.skeleton.num_joints(), p.markers.num_markers(), p.observed.size(),
              FLAGS_ik_target_rms, FLAGS_ik_max_iterations);
  for (const auto& [name, value] : figures) std::printf("PEERS %s %.9g\n", name.c_str(), value);
  if (!FLAGS_json.empty()) {
    json.Add("input", p.input).Add("rounds", FLAGS_rounds).Add("ik_target_rms", FLAGS_ik_target_rms)
        .Add("ik_frames", static_cast<int>(p.observed.size())).Add("records", records);
    Status status = WriteFileAtomically(FLAGS_json, json.ToString() + "\n");
    if (!status.ok()) {
      std::fprintf(stderr, "%s\n", status.message().c_str());
      return 1;
    }
  }
  return 0;
}

void RegisterBenchmarks(Harness* harness) {
  for (Case& k : harness->cases()) {
    Case* c = &k;
    const int frames = k.frames > 0 ? k.frames : k.measure == "ik" ? static_cast<int>(harness->problem().observed.size()) : 1 << 30;
    benchmark::RegisterBenchmark(("BM_" + k.label()).c_str(), [c, frames](benchmark::State& state) {
      c->reset();
      int f = 0;
      for (auto _ : state) {
        if (f == frames) {
          state.PauseTiming();
          c->reset();
          f = 0;
          state.ResumeTiming();
        }
        c->run(f++);
      }
    });
  }
}

}  // namespace
}  // namespace mocapsolve::peers

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  gflags::SetUsageMessage(
      "mocapsolve_peers_bench [--interleaved [--rounds=N] [--json=OUT]] [--check_only] [--peers=kdl,mujoco,dart]\n"
      "Our FK, Jacobian and marker IK beside Orocos KDL, MuJoCo and DART on the same skeleton.");
  gflags::ParseCommandLineFlags(&argc, &argv, true);
  using namespace mocapsolve::peers;
  PeersProblem problem;
  mocapsolve::Status status = LoadProblem(&problem);
  Harness harness;
  if (status.ok()) status = harness.Build(problem);
  if (!status.ok()) {
    std::fprintf(stderr, "%s\n", status.message().c_str());
    return 1;
  }
  if (FLAGS_check_only) return 0;
  harness.MakeCases();
  if (FLAGS_interleaved) return RunInterleaved(&harness);
  RegisterBenchmarks(&harness);
  benchmark::RunSpecifiedBenchmarks();
  return 0;
}
