// FitSubjectToTake (tasks/fit_skeleton_task.h): the settings' validation messages, and on
// a short real take (squat.c3d from CMU subject 2 calibrated on 02_01) the order of the
// progress events, the rounds and the report. The CLI's byte-for-byte agreement with the
// Python binding is tested in tests/python/test_skeleton_fitting.py.
#include "tasks/fit_skeleton_task.h"

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "io/marker_file.h"
#include "io/motion_file.h"
#include "kinematics/demo_character.h"
#include "kinematics/forward_kinematics.h"
#include "tasks/calibrate_task.h"
#include "problems/marker_solve/held_out_round.h"
#include "problems/marker_solve/locked_axes.h"
#include "problems/marker_repair/marker_repair.h"
#include "problems/marker_solve/synthetic_marker_set.h"
#include "tests/test_support.h"

namespace mocapsolve {
namespace {

TEST(SkeletonFitSettings, EachBadValueNamesItsOption) {
  EXPECT_TRUE(ValidateSkeletonFitSettings(SkeletonFitSettings()).ok());
  const std::vector<std::pair<void (*)(SkeletonFitSettings*), std::string>> cases = {
      {[](SkeletonFitSettings* s) { s->fit_iterations = -2; }, "--fit_iterations: expected a value in [-1, 100], got -2"},
      {[](SkeletonFitSettings* s) { s->attach_iterations = 101; }, "--attach_iterations: expected a value in [0, 100], got 101"},
      {[](SkeletonFitSettings* s) { s->attach_rounds = 21; }, "--attach_rounds: expected a value in [-1, 20], got 21"},
      {[](SkeletonFitSettings* s) { s->fit_frame_step = 0; }, "--fit_frame_step: expected a value >= 1, got 0"},
      {[](SkeletonFitSettings* s) { s->fit_max_frames = -1; }, "--fit_max_frames: expected a value >= 0, got -1"},
      {[](SkeletonFitSettings* s) { s->offset_prior = -1.0; }, "--offset_prior: expected a value >= 0, got -1"},
      {[](SkeletonFitSettings* s) { s->max_skin_cm = -1.0; }, "--max_skin_cm: expected a value >= 0, got -1"},
      {[](SkeletonFitSettings* s) { s->fit_outlier_mm = -1.0; }, "--fit_outlier_mm: expected a value >= 0, got -1"},
      {[](SkeletonFitSettings* s) { s->min_bone_scale = 1.1; }, "--min_bone_scale: expected a value in [0, 1], got 1.1"},
      {[](SkeletonFitSettings* s) { s->min_bone_scale = 0.0; }, "--min_bone_scale: expected a value in (0, 1], got 0"},
      {[](SkeletonFitSettings* s) { s->max_bone_scale = 0.9; }, "--max_bone_scale: expected a value >= 1, got 0.9"},
      {[](SkeletonFitSettings* s) { s->check = "maybe"; }, "--check: unknown 'maybe' (fail, warn, off)"},
      {[](SkeletonFitSettings* s) { s->template_labels = "/no/such/labels.txt"; }, ""},
  };
  for (const auto& [change, message] : cases) {
    SkeletonFitSettings settings;
    change(&settings);
    const Status status = ValidateSkeletonFitSettings(settings);
    EXPECT_FALSE(status.ok()) << message;
    if (!message.empty()) {
      EXPECT_EQ(status.message(), message);
    }
  }
  // The declarations' defaults are the struct's (the CLI's and Python's defaults).
  const SkeletonFitSettings defaults = SkeletonFitSettingOptions().Defaults();
  EXPECT_EQ(defaults.template_labels, kTemplateLabelsAuto);
  EXPECT_EQ(defaults.attach_rounds, SkeletonFitSettings().attach_rounds);
}

// CMU subject 2 calibrated on 02_01 (as `mocapsolve calibrate --out_subject`).
void CalibrateCmu02(const std::string& asf, const std::string& amc, const std::string& c3d,
                    SubjectCalibration* calibrated) {
  MotionFileOptions motion_options;
  motion_options.skeleton_path = asf;
  Skeleton skeleton;
  Motion motion;
  ASSERT_TRUE(ReadMotionFile(amc, motion_options, &skeleton, &motion).ok());
  MarkerTrajectories trajectories;
  ASSERT_TRUE(ReadMarkerFile(c3d, &trajectories).ok());
  SubjectCalibrationOptions calibration;
  calibration.axes = "y,z,x";
  calibration.skeleton_path = asf;
  ASSERT_TRUE(CalibrateSubject(skeleton, motion, trajectories, calibration, calibrated).ok());
}

TEST(FitSubjectToTake, ShortSquatFitReportsRoundsInOrder) {
  MOCAPSOLVE_DATA_FILE(asf, "amc/02.asf");
  MOCAPSOLVE_DATA_FILE(amc, "amc/02_01.amc");
  MOCAPSOLVE_DATA_FILE(c3d, "c3d/02_01.c3d");
  MOCAPSOLVE_DATA_FILE(squat, "c3d/squat.c3d");
  SubjectCalibration calibrated;
  ASSERT_NO_FATAL_FAILURE(CalibrateCmu02(asf, amc, c3d, &calibrated));

  SkeletonFitInputs inputs;
  inputs.templ = calibrated.subject;
  inputs.templ.name = "S02";
  inputs.template_name = "S02";
  inputs.markers_path = squat;
  SkeletonFitSettings settings;
  settings.fit_max_frames = 60;
  settings.attach_rounds = 1;
  settings.fit_iterations = 2;
  settings.attach_iterations = 1;
  MarkerSolveOptions solve;
  solve.solver = SolverKind::kDls;
  std::vector<SkeletonFitEvent> events;
  SkeletonFitResult result;
  const Status status =
      FitSubjectToTake(inputs, settings, solve, &result, [&](const SkeletonFitEvent& e) { events.push_back(e); });
  ASSERT_TRUE(status.ok()) << status.message();

  // The label map applied comes first (the take's labels are the 53-marker Vicon set's),
  // then the template's markers the take lacks, then per round: start, the frames of each
  // pose solve (1 + iterations of them) with the iterations between, and the end.
  ASSERT_GE(events.size(), 3u);
  // The second fit (the template's locked axes freed: its feet, locked_axes.h) is announced,
  // then reported as the first was, but for the take's labels.
  const auto freeing = std::find_if(events.begin(), events.end(),
                                    [](const SkeletonFitEvent& e) { return e.kind == SkeletonFitEvent::kFreeingAxes; });
  ASSERT_NE(freeing, events.end());
  EXPECT_EQ(freeing->text.rfind("lfoot, rfoot", 0), 0u) << freeing->text;
  const double freeing_seconds = freeing->seconds;
  const std::vector<SkeletonFitEvent> second(freeing + 1, events.end());
  events.erase(freeing, events.end());
  EXPECT_EQ(events[0].kind, SkeletonFitEvent::kTemplateLabels);
  EXPECT_EQ(events[0].text, "examples/vicon53_to_cmu_labels.txt");
  EXPECT_EQ(events[0].markers, static_cast<int>(result.template_labels.size()));
  EXPECT_EQ(result.template_labels_map, events[0].text);
  EXPECT_EQ(events[1].kind, SkeletonFitEvent::kAbsentMarkers);
  EXPECT_EQ(events[2].kind, SkeletonFitEvent::kRoundStart);
  int starts = 0, done = 0, iterations = 0, frame_events = 0;
  for (const SkeletonFitEvent& e : events) {
    starts += e.kind == SkeletonFitEvent::kRoundStart;
    done += e.kind == SkeletonFitEvent::kRoundDone;
    iterations += e.kind == SkeletonFitEvent::kIteration;
    if (e.kind == SkeletonFitEvent::kFrames) {
      ++frame_events;
      EXPECT_EQ(e.frames, 60);
      EXPECT_LE(e.iteration, e.iterations);
    }
  }
  EXPECT_EQ(starts, 2);
  EXPECT_EQ(done, 2);
  EXPECT_EQ(iterations, 2 + 1);
  EXPECT_EQ(frame_events, 60 * (2 + 1 + 1 + 1));
  // After the rounds, the markers the kept round blended over a hinge (its report line).
  EXPECT_EQ(events[events.size() - 2].kind, SkeletonFitEvent::kRoundDone);
  EXPECT_EQ(events.back().kind, SkeletonFitEvent::kBlended);
  // The second fit: its rounds as the first's (no labels again), its blends, then whether it
  // is kept.
  ASSERT_GE(second.size(), 3u);
  EXPECT_EQ(second.front().kind, SkeletonFitEvent::kRoundStart);
  EXPECT_EQ(std::count_if(second.begin(), second.end(),
                          [](const SkeletonFitEvent& e) { return e.kind == SkeletonFitEvent::kRoundStart; }),
            2);
  EXPECT_EQ(std::count_if(second.begin(), second.end(),
                          [](const SkeletonFitEvent& e) { return e.kind == SkeletonFitEvent::kTemplateLabels; }),
            0);
  EXPECT_GE(second.front().seconds, freeing_seconds);
  EXPECT_EQ(std::count_if(second.begin(), second.end(),
                          [](const SkeletonFitEvent& e) { return e.kind == SkeletonFitEvent::kBlended; }),
            1);
  EXPECT_EQ(second.back().kind, SkeletonFitEvent::kFreedAxes);
  EXPECT_EQ(second.back().text.rfind("lfoot, rfoot", 0), 0u) << second.back().text;
  EXPECT_EQ(second.back().markers, static_cast<int>(result.freed_axes.size()));

  EXPECT_EQ(result.frames, 60);
  EXPECT_EQ(result.attach_rounds, 1);
  ASSERT_EQ(result.rounds.size(), 2u);
  EXPECT_EQ(result.rounds[0].rms.size(), 3u);  // Before and after each iteration.
  EXPECT_EQ(result.subject.markers.num_markers(), 53);  // Round 1 attaches every marker.
  EXPECT_EQ(result.subject.name, "fitted from S02");
  EXPECT_EQ(result.motion.num_frames(), 60);
  EXPECT_GT(result.checks.rms_mm, 0.0);
  const std::string report = SkeletonFitReportJson(inputs, result).ToString();
  EXPECT_NE(report.find("\"kept_round\""), std::string::npos);
  EXPECT_NE(report.find("\"hinge_blends\""), std::string::npos);
  EXPECT_NE(report.find("\"checks\""), std::string::npos);
  // check=fail turns failed checks into the CLI's error; warn and off never do.
  if (!result.checks.ok()) {
    const Status failed = SkeletonFitCheckStatus(inputs, settings, result);
    EXPECT_EQ(failed.message().rfind(squat + ": the fitted subject fails its checks (", 0), 0u) << failed.message();
  }
  settings.check = "warn";
  EXPECT_TRUE(SkeletonFitCheckStatus(inputs, settings, result).ok());
}

// `--template_labels=auto` (the default) on the real takes, with CMU subject 2's marker set
// as the template: the CMU-labelled takes get no map, the others their protocol's.
TEST(FitSubjectToTake, AutoTemplateLabelsPickTheTakesProtocol) {
  MOCAPSOLVE_DATA_FILE(asf, "amc/02.asf");
  MOCAPSOLVE_DATA_FILE(amc, "amc/02_01.amc");
  MOCAPSOLVE_DATA_FILE(c3d, "c3d/02_01.c3d");
  SubjectCalibration calibrated;
  ASSERT_NO_FATAL_FAILURE(CalibrateCmu02(asf, amc, c3d, &calibrated));
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"c3d/02_01.c3d", ""},
      {"c3d/cmu_02_05.c3d", ""},
      {"c3d/squat.c3d", "examples/vicon53_to_cmu_labels.txt"},
      {"c3d/nick_freeform_001.c3d", "examples/vicon53_to_cmu_labels.txt"},
      {"c3d/JA1Gait35.c3d", "examples/ais_to_cmu_labels.txt"},
  };
  for (const auto& [relative, expected] : cases) {
    MOCAPSOLVE_DATA_FILE(path, relative);
    MarkerTrajectories take;
    ASSERT_TRUE(ReadMarkerFile(path, &take).ok()) << path;
    std::string name;
    std::vector<TemplateLabel> labels;
    ASSERT_TRUE(ChooseShippedTemplateLabels(calibrated.subject.markers, take, &name, &labels).ok());
    EXPECT_EQ(name, expected) << relative;
    EXPECT_EQ(labels.empty(), expected.empty()) << relative;
  }
  // "none" (and "") turn the choice off: squat's round 0 fits the 26 shared labels only.
  MOCAPSOLVE_DATA_FILE(squat, "c3d/squat.c3d");
  SkeletonFitInputs inputs;
  inputs.templ = calibrated.subject;
  inputs.markers_path = squat;
  SkeletonFitSettings settings;
  settings.fit_max_frames = 20;
  settings.fit_iterations = 1;
  settings.attach_rounds = 0;
  settings.check = "off";
  MarkerSolveOptions solve;
  solve.solver = SolverKind::kDls;
  for (const std::string& off : {std::string(kTemplateLabelsNone), std::string()}) {
    settings.template_labels = off;
    SkeletonFitResult result;
    ASSERT_TRUE(FitSubjectToTake(inputs, settings, solve, &result).ok());
    EXPECT_TRUE(result.template_labels.empty());
    EXPECT_EQ(result.template_labels_map, "");
    EXPECT_EQ(result.rounds[0].markers, 26);
  }
}

// A template with the take's whole marker set (CMU subject 2 on its take 02_05): the
// calibration holds several markers farther than --max_skin_cm from their bone (RBAC 21 cm
// from upperback). The fit must still improve on the template (each step used to clamp
// them onto the 12 cm tube, so every step was refused: 9.19 -> 9.19 mm on the whole take),
// an attach round must start where round 0 ended (it used to clamp them again: 26.68 mm),
// and round 0, a complete fit here, is kept when no round beats it. On the take's first 120
// frames, as measured (--fit_max_frames=120 now spreads them over the whole take, 1 in 16,
// where the near ties decided by prediction move a marker that starts round 1 2.6 % above
// round 0's end, and with no attach iterations round 1 is then not round 0's model again;
// with that step skipped both hold on the spread frames too).
TEST(FitSubjectToTake, CompleteTemplateRoundsStartWhereTheLastEnded) {
  MOCAPSOLVE_DATA_FILE(asf, "amc/02.asf");
  MOCAPSOLVE_DATA_FILE(amc, "amc/02_01.amc");
  MOCAPSOLVE_DATA_FILE(c3d, "c3d/02_01.c3d");
  MOCAPSOLVE_DATA_FILE(take, "c3d/cmu_02_05.c3d");
  SubjectCalibration calibrated;
  ASSERT_NO_FATAL_FAILURE(CalibrateCmu02(asf, amc, c3d, &calibrated));
  MarkerTrajectories whole;
  ASSERT_TRUE(ReadMarkerFile(take, &whole).ok());
  const MarkerTrajectories first = TrajectoryFrames(whole, 0, 120);
  SkeletonFitInputs inputs;
  inputs.templ = calibrated.subject;
  inputs.markers_path = take;
  inputs.trajectories = &first;
  inputs.axes = "y,z,x";
  SkeletonFitSettings settings;
  settings.fit_iterations = 4;
  settings.attach_rounds = 3;
  settings.attach_iterations = 2;
  settings.check = "off";
  MarkerSolveOptions solve;
  solve.solver = SolverKind::kDls;
  SkeletonFitResult result;
  Status status = FitSubjectToTake(inputs, settings, solve, &result);
  ASSERT_TRUE(status.ok()) << status.message();
  ASSERT_GE(result.rounds.size(), 2u);
  const std::vector<double>& round0 = result.rounds[0].rms;
  EXPECT_EQ(result.rounds[0].markers, 41);
  EXPECT_LT(round0.back(), 0.9 * round0.front());  // Steps accepted.
  double best = round0.back();
  for (size_t r = 1; r < result.rounds.size(); ++r) {
    const std::vector<double>& rms = result.rounds[r].rms;
    // The same skeleton and frames as the best round before it, and its markers, but for
    // those a near tie moved to the joint that predicts them better (attachment_by_prediction.h,
    // which here lowers the start): never a worse start (a relative 1e-9: the per-frame solves
    // are deterministic).
    EXPECT_LE(rms.front(), best * (1.0 + 1e-9)) << "round " << r;
    best = std::min(best, rms.back());
  }
  // The kept round is the latest within 5 % of the lowest held-out score (held_out_round.h),
  // not the lowest marker RMS.
  const auto expect_held_out_choice = [](const SkeletonFitResult& fit) {
    std::vector<double> held_out;
    std::vector<int> candidate_rounds;
    for (const SkeletonFitRound& round : fit.rounds) {
      if (round.held_out < 0.0) continue;
      held_out.push_back(round.held_out);
      candidate_rounds.push_back(round.round);
    }
    ASSERT_FALSE(held_out.empty());
    EXPECT_EQ(fit.kept_round, candidate_rounds[KeptRound(held_out, HeldOutRoundOptions().tolerance)]);
    EXPECT_NEAR(fit.report.rms.back(), fit.rounds[fit.kept_round].rms.back(),
                1e-9 * fit.rounds[fit.kept_round].rms.back());
  };
  expect_held_out_choice(result);
  // The template's own skin distances (up to 20.7 cm) do not fail the skin check.
  EXPECT_GT(result.checks.max_bone_distance_cm, 15.0);
  EXPECT_TRUE(result.checks.ok()) << result.checks.failures.front();

  // No attach iterations: each round after round 0 is the model before it with the markers
  // its attach re-decided by prediction (near ties and rigid clusters,
  // attachment_by_prediction.h: on these frames some move, so a round can start lower and
  // another follow: 2 rounds on the first 120 frames as the fit read them from the file, 3
  // on the same frames passed in memory), and the held-out choice among them is kept.
  settings.attach_iterations = 0;
  status = FitSubjectToTake(inputs, settings, solve, &result);
  ASSERT_TRUE(status.ok()) << status.message();
  ASSERT_GE(result.rounds.size(), 2u);
  expect_held_out_choice(result);
}

// A take recorded with another protocol: the demo character's synthetic markers, on a
// subject with 10 % longer legs, every label renamed ("X" -> "take_X"). Without a map the
// template shares no label with the take and the fit refuses it; with the map round 0 fits
// every marker, the fitted subject holds the take's labels, and thighs and shins lengthen.
// The markers' model positions over a motion, moved by `shift`: [frame][marker].
std::vector<std::vector<Eigen::Vector3d>> WalkObservations(const Skeleton& skeleton, const MarkerSet& markers,
                                                           const Motion& motion,
                                                           const Eigen::Vector3d& shift = Eigen::Vector3d::Zero()) {
  std::vector<std::vector<Eigen::Vector3d>> observed;
  FkData fk(skeleton);
  for (const Pose& pose : motion.frames) {
    ForwardKinematics(skeleton, pose, &fk);
    observed.emplace_back();
    for (int m = 0; m < markers.num_markers(); ++m) observed.back().push_back(markers.Position(m, fk) + shift);
  }
  return observed;
}

// The demo skeleton with its legs' and feet's bones 10 % longer: a subject whose proportions
// the template does not have.
void MakeLongerLegs(const Skeleton& templ, Skeleton* longer) {
  std::vector<JointSpec> joints;
  for (int j = 0; j < templ.num_joints(); ++j) {
    joints.push_back(templ.joint(j));
    const std::string& name = templ.name(j);
    if (name.find("Leg") != std::string::npos || name.find("Foot") != std::string::npos) joints.back().offset *= 1.1;
  }
  ASSERT_TRUE(Skeleton::Create(joints, templ.end_sites(), templ.unit(), longer).ok());
}

TEST(FitSubjectToTake, RenamedLabelsFitThroughTheTemplateLabelMap) {
  const Skeleton templ = MakeDemoSkeleton();  // cm
  Skeleton subject;
  ASSERT_NO_FATAL_FAILURE(MakeLongerLegs(templ, &subject));
  const MarkerSet subject_markers = MakeSyntheticMarkerSet(subject, 2, 7);
  MarkerTrajectories take = ObservationTrajectories(
      subject_markers, WalkObservations(subject, subject_markers, MakeDemoWalk(subject, 40, 30.0)));
  take.unit = templ.unit();
  take.frame_rate = 30.0;
  std::string pairs;
  for (int m = 0; m < take.num_markers(); ++m) {
    pairs += (m ? "," : "") + take.label(m) + ":take_" + take.label(m);
    take.set_label(m, "take_" + take.label(m));
  }
  SkeletonFitInputs inputs;
  inputs.from_template_subject = false;
  inputs.markers_path = ::mocapsolve::testing::TempPath("renamed.trc");
  ASSERT_TRUE(WriteMarkerFile(inputs.markers_path, take).ok());
  inputs.templ.skeleton = templ;
  inputs.templ.markers = MakeSyntheticMarkerSet(templ, 2, 7);
  SkeletonFitSettings settings;
  settings.fit_iterations = 4;
  settings.check = "off";
  MarkerSolveOptions solve;
  solve.solver = SolverKind::kDls;
  SkeletonFitResult result;
  // Without the association (--associate=never), labels are all the fit goes by.
  settings.associate = "never";
  Status status = FitSubjectToTake(inputs, settings, solve, &result);
  ASSERT_FALSE(status.ok());
  EXPECT_EQ(status.message(), inputs.markers_path + ": fewer than 3 of the template marker set's labels "
                              "(--template_labels maps the template's labels to the take's)");
  // By default the markers are associated with segments from the data instead.
  settings.associate = "auto";
  status = FitSubjectToTake(inputs, settings, solve, &result);
  ASSERT_TRUE(status.ok()) << status.message();
  EXPECT_TRUE(result.associated);

  settings.template_labels = pairs;
  status = FitSubjectToTake(inputs, settings, solve, &result);
  ASSERT_TRUE(status.ok()) << status.message();
  EXPECT_TRUE(result.absent.empty());
  ASSERT_EQ(result.rounds.size(), 1u);
  EXPECT_EQ(result.rounds[0].markers, take.num_markers());
  EXPECT_EQ(result.template_labels.size(), static_cast<size_t>(take.num_markers()));
  for (int m = 0; m < result.subject.markers.num_markers(); ++m) {
    EXPECT_EQ(result.subject.markers.label(m).rfind("take_", 0), 0u) << result.subject.markers.label(m);
  }
  const std::vector<double>& rms = result.rounds[0].rms;
  EXPECT_GT(rms.front(), 1.0) << "the template's legs miss by more than 1 cm";
  // Measured 1.84 -> 0.41 cm: what is left is the hips' width (the UpLeg offsets), which a
  // walk hardly measures.
  EXPECT_LT(rms.back(), 0.3 * rms.front());
  // Thigh and shin (the offsets of the Leg and Foot joints) land within 3 % of 1.1
  // (measured 1.098 and 1.092).
  int legs = 0;
  for (int j = 1; j < templ.num_joints(); ++j) {
    const std::string& name = templ.name(j);
    if (name == "LeftLeg" || name == "RightLeg" || name == "LeftFoot" || name == "RightFoot") {
      ++legs;
      EXPECT_NEAR(result.report.bone_scales[j], 1.1, 0.03) << name;
    }
  }
  EXPECT_EQ(legs, 4);
  EXPECT_NE(SkeletonFitReportJson(inputs, result).ToString().find("\"take\": \"take_"), std::string::npos);
}

// A foot that rolls about its long axis in the take (0.35 rad), on a template whose feet
// lock that axis (two dofs, the toes one: an ASF's feet), 1 mm of marker noise: the fit is
// run again with the feet freed and kept, since it predicts the held-out markers better
// (measured 0.240 -> 0.196 cm); with free_locked_axes false the template's axes stay. The
// same take without the roll keeps the template's feet (0.194 -> 0.195 cm). The demo
// foot's long axis is local z.
TEST(FitSubjectToTake, AFootThatRollsGetsTheAxisItsTemplateLocks) {
  const Skeleton truth = MakeDemoSkeleton();  // cm; every joint three dofs.
  std::vector<JointSpec> joints;
  for (int j = 0; j < truth.num_joints(); ++j) {
    joints.push_back(truth.joint(j));
    const std::string& name = truth.name(j);
    if (name == "LeftFoot" || name == "RightFoot") joints.back().rotation_axes = std::vector<int>{1, 0};
    if (name == "LeftToe") joints.back().rotation_axes = std::vector<int>{0};
  }
  Skeleton templ;
  ASSERT_TRUE(Skeleton::Create(joints, truth.end_sites(), truth.unit(), &templ).ok());
  const MarkerSet truth_markers = MakeSyntheticMarkerSet(truth, 3, 11);
  SkeletonFitInputs inputs;
  inputs.from_template_subject = false;
  inputs.templ.skeleton = templ;
  inputs.templ.markers = MakeSyntheticMarkerSet(templ, 3, 11);
  EXPECT_EQ(LockedAxisJoints(templ, inputs.templ.markers).size(), 2u);
  auto write_take = [&](double roll_rad, const std::string& name) {
    Motion walk = MakeDemoWalk(truth, 60, 30.0);
    for (size_t f = 0; f < walk.frames.size(); ++f) {
      const double roll = roll_rad * std::sin(2.0 * 3.141592653589793 * f / 23.0);
      for (const char* foot : {"LeftFoot", "RightFoot"}) {
        const int j = truth.FindJoint(foot);
        walk.frames[f].rotations[j] = walk.frames[f].rotations[j] * Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitZ());
      }
    }
    std::vector<std::vector<Eigen::Vector3d>> observed = WalkObservations(truth, truth_markers, walk);
    std::mt19937 rng(3);
    std::normal_distribution<double> skin(0.0, 0.1);  // 1 mm.
    for (auto& frame : observed) {
      for (Eigen::Vector3d& x : frame) x += Eigen::Vector3d(skin(rng), skin(rng), skin(rng));
    }
    MarkerTrajectories take = ObservationTrajectories(truth_markers, observed);
    take.unit = truth.unit();
    take.frame_rate = 30.0;
    inputs.markers_path = ::mocapsolve::testing::TempPath(name);
    ASSERT_TRUE(WriteMarkerFile(inputs.markers_path, take).ok());
  };
  SkeletonFitSettings settings;
  settings.fit_iterations = 3;
  settings.attach_rounds = 1;
  settings.attach_iterations = 2;
  settings.check = "off";
  settings.associate = "never";
  MarkerSolveOptions solve;
  solve.solver = SolverKind::kDls;
  SkeletonFitResult result;
  std::vector<std::string> events;
  const auto record = [&](const SkeletonFitEvent& e) {
    if (e.kind == SkeletonFitEvent::kFreedAxes) events.push_back(e.text + (e.markers > 0 ? ": kept" : ""));
  };

  write_take(0.35, "rolling_feet.trc");
  Status status = FitSubjectToTake(inputs, settings, solve, &result, record);
  ASSERT_TRUE(status.ok()) << status.message();
  EXPECT_EQ(result.freed_axes, (std::vector<std::string>{"LeftFoot", "RightFoot"}));
  ASSERT_EQ(result.locked_axes_held_out.size(), 2u);
  EXPECT_LT(result.locked_axes_held_out[1], 0.9 * result.locked_axes_held_out[0]);
  const int left = result.subject.skeleton.FindJoint("LeftFoot");
  EXPECT_EQ(result.subject.skeleton.rotation_axes(left), (std::vector<int>{1, 2, 0}));
  EXPECT_NE(SkeletonFitReportJson(inputs, result).ToString().find("\"freed_axes\": [\"LeftFoot\""), std::string::npos);
  settings.free_locked_axes = false;
  status = FitSubjectToTake(inputs, settings, solve, &result);
  ASSERT_TRUE(status.ok()) << status.message();
  EXPECT_TRUE(result.freed_axes.empty());
  EXPECT_TRUE(result.locked_axes_held_out.empty());
  EXPECT_EQ(result.subject.skeleton.num_rotation_dofs(left), 2);

  settings.free_locked_axes = true;
  write_take(0.0, "still_feet.trc");
  status = FitSubjectToTake(inputs, settings, solve, &result, record);
  ASSERT_TRUE(status.ok()) << status.message();
  EXPECT_TRUE(result.freed_axes.empty());
  ASSERT_EQ(result.locked_axes_held_out.size(), 2u);
  EXPECT_EQ(result.subject.skeleton.num_rotation_dofs(left), 2);
  EXPECT_EQ(events, (std::vector<std::string>{"LeftFoot, RightFoot: kept", "LeftFoot, RightFoot"}));
}

// Fitting by labels, points that are no markers (a lab's joint angles written as points at
// the file's origin while the body walks 3 m away) are left out, named with the reason in
// the result and the report, not attached to the skin by the rounds.
TEST(FitSubjectToTake, PointsThatAreNoMarkersAreLeftOutAndReported) {
  const Skeleton templ = MakeDemoSkeleton();  // cm
  const MarkerSet markers = MakeSyntheticMarkerSet(templ, 2, 7);
  MarkerTrajectories body = ObservationTrajectories(
      markers, WalkObservations(templ, markers, MakeDemoWalk(templ, 40, 30.0), Eigen::Vector3d(300.0, 0.0, 0.0)));
  std::vector<std::string> labels = body.labels();
  for (const char* name : {"LKneeAngle_x", "RKneeAngle_x", "LHipPower_z"}) labels.push_back(name);
  MarkerTrajectories take(labels, body.num_frames());
  take.unit = templ.unit();
  take.frame_rate = 30.0;
  for (int f = 0; f < take.num_frames(); ++f) {
    for (int m = 0; m < body.num_markers(); ++m) take.SetSample(f, m, body.position(f, m));
    for (int k = 0; k < 3; ++k) {  // Degrees-like values that swing with the gait.
      const double phase = 0.3 * f + k;
      take.SetSample(f, body.num_markers() + k, Eigen::Vector3d(20.0 * std::sin(phase), 5.0 * k, 10.0 * std::cos(phase)));
    }
  }
  SkeletonFitInputs inputs;
  inputs.from_template_subject = false;
  inputs.markers_path = ::mocapsolve::testing::TempPath("with_outputs.trc");
  ASSERT_TRUE(WriteMarkerFile(inputs.markers_path, take).ok());
  inputs.templ.skeleton = templ;
  inputs.templ.markers = markers;
  SkeletonFitSettings settings;
  settings.fit_iterations = 2;
  settings.check = "off";
  MarkerSolveOptions solve;
  solve.solver = SolverKind::kDls;
  SkeletonFitResult result;
  const Status status = FitSubjectToTake(inputs, settings, solve, &result);
  ASSERT_TRUE(status.ok()) << status.message();
  EXPECT_FALSE(result.associated) << "the labels are the template's";
  ASSERT_EQ(result.not_markers.size(), 3u);
  EXPECT_EQ(result.not_markers[0].first, "LKneeAngle_x");
  EXPECT_EQ(result.subject.markers.num_markers(), markers.num_markers());
  EXPECT_NE(SkeletonFitReportJson(inputs, result).ToString().find("\"not_markers\": [{\"label\": \"LKneeAngle_x\""),
            std::string::npos);
}

TEST(FitSubjectToTake, MissingTakeNamesTheFile) {
  SkeletonFitInputs inputs;
  inputs.markers_path = ::mocapsolve::testing::TempPath("absent.c3d");
  JointSpec root;
  root.name = "root";
  ASSERT_TRUE(Skeleton::Create({root}, {}, LengthUnitFromName("cm"), &inputs.templ.skeleton).ok());
  SkeletonFitResult result;
  const Status status = FitSubjectToTake(inputs, SkeletonFitSettings(), MarkerSolveOptions(), &result);
  ASSERT_FALSE(status.ok());
  EXPECT_NE(status.message().find("absent.c3d"), std::string::npos) << status.message();
}

// `calibrate --refit`: calibration places the markers on the given motion's poses, here a
// walk on the demo skeleton while the markers were made on one with 10 % longer legs (as
// CMU's AMC poses do not quite fit its markers); the offsets absorb the difference. The
// refit (fit_skeleton --template_subject on the same markers) replaces the subject with one
// whose legs are fitted to the markers against our own solve; the calibration's marker set
// and table stay, and the report says what the refit kept.
TEST(RunCalibrate, RefitFitsTheLengthsTheGivenMotionGotWrong) {
  const Skeleton templ = MakeDemoSkeleton();  // cm
  Skeleton longer;
  ASSERT_NO_FATAL_FAILURE(MakeLongerLegs(templ, &longer));
  const MarkerSet markers = MakeSyntheticMarkerSet(longer, 2, 7);
  const Motion walk = MakeDemoWalk(longer, 40, 30.0);
  MarkerTrajectories take = ObservationTrajectories(markers, WalkObservations(longer, markers, walk));
  take.unit = templ.unit();
  take.frame_rate = 30.0;
  // The motion calibrate is given: the walk's rotations on the template's bones (a pose's
  // translations are its bones).
  Motion given = walk;
  const Pose rest = RestPose(templ);
  for (Pose& pose : given.frames) {
    for (int j = 1; j < templ.num_joints(); ++j) pose.translations[j] = rest.translations[j];
  }
  SubjectCalibrationOptions options;
  options.markers_name = "walk.trc";
  CalibrateSettings settings;
  CalibrateTaskResult calibrated;
  ASSERT_TRUE(RunCalibrate(templ, given, take, settings, options, &calibrated).ok());
  EXPECT_EQ(calibrated.report.ToString().find("\"refit\""), std::string::npos);
  const double calibration_rms = calibrated.calibration.result.rms;
  EXPECT_GT(calibration_rms, 0.5) << "cm: the shorter legs' poses put the markers off";  // Measured 0.93.

  settings.refit = true;
  CalibrateTaskResult refitted;
  ASSERT_TRUE(RunCalibrate(templ, given, take, settings, options, &refitted).ok());
  ASSERT_TRUE(refitted.refit_kept);
  EXPECT_EQ(refitted.calibration.result.rms, calibration_rms);  // The calibration itself is unchanged.
  ASSERT_FALSE(refitted.refit.report.rms.empty());
  EXPECT_LT(refitted.refit.report.rms.back(), 0.3 * calibration_rms);
  // The subject is the refit's: thighs and shins (1.0 in the calibration's) at least a fifth
  // of the way to the markers' 1.1 and not past it by 3 % (the offsets calibrated on the short
  // bones, its start, hold some of it back: measured 1.059 and 1.024).
  const Skeleton& fitted = refitted.calibration.subject.skeleton;
  ASSERT_EQ(fitted.num_joints(), templ.num_joints());
  int legs = 0;
  for (int j = 1; j < templ.num_joints(); ++j) {
    const std::string& name = templ.name(j);
    if (name == "LeftLeg" || name == "RightLeg" || name == "LeftFoot" || name == "RightFoot") {
      ++legs;
      const double scale = fitted.joint(j).offset.norm() / templ.joint(j).offset.norm();
      EXPECT_GT(scale, 1.02) << name;
      EXPECT_LT(scale, 1.13) << name;
    }
  }
  EXPECT_EQ(legs, 4);
  EXPECT_EQ(refitted.calibration.subject.markers.num_markers(), markers.num_markers());
  EXPECT_NE(refitted.report.ToString().find("\"refit\""), std::string::npos);
  EXPECT_EQ(refitted.refit_line.rfind("refit on our own solve", 0), 0u);
  EXPECT_TRUE(calibrated.refit_line.empty());
}

}  // namespace
}  // namespace mocapsolve
