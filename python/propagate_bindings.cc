// Edit propagation (the magic wand): pose-space falloffs (Green's function, diffusion,
// ISOMAP; spline in time), edits, and their propagation through a clip (eq. 5).
#include <cmath>

#include "io/edit_file.h"
#include "pipeline/edit_weights.h"
#include "settings/falloff_settings.h"
#include "settings/solver_settings.h"
#include "problems/edit_propagation/falloff.h"
#include "problems/edit_propagation/ik_edit.h"
#include "problems/edit_propagation/pose_edit.h"
#include "problems/edit_propagation/spline_falloff.h"
#include "settings/edit_settings.h"
#include "settings/foot_joint_settings.h"
#include "python/bindings.h"
#include "settings/method_settings.h"
#include "python/keyword_docs.h"
#include "python/solve_bindings.h"
#include "settings/propagate_settings.h"
#include "tasks/distance_task.h"
#include "tasks/propagate_task.h"

namespace mocapsolve::python {
namespace {

// propagate()'s keywords: its own options, the falloff's and the IK solve's (as the CLI).
std::string PropagateKeywordNames() {
  return PropagateSettingOptions().Names() + "," + FalloffSettingOptions().Names() + "," + SolverOptions().Names();
}

Array VectorToArray(const Eigen::VectorXd& v) {
  Array out({py::ssize_t{v.size()}});
  std::copy(v.data(), v.data() + v.size(), out.mutable_data());
  return out;
}

}  // namespace

void BindPropagate(py::module_& m) {
  py::class_<FalloffSettings> settings(m, "FalloffSettings",
      "The pose-space falloff's options, one per flag of `mocapsolve distance`/`propagate`\n"
      "(same names and defaults). falloff() takes them as keywords.");
  settings.def(py::init<>(), "Every option at the CLI's default.");
  BindOptionFields(settings, FalloffSettingOptions());
  settings.def("validate", [](const FalloffSettings& s, int num_frames) {
        FalloffOptions options;
        ThrowIfError(FalloffOptionsFromSettings(s, num_frames, &options));
      }, py::arg("num_frames"),
      "Raises ValueError (the CLI's message) if a value is invalid for a clip of num_frames frames.");
  m.attr("FALLOFF_OPTION_NAMES") = FalloffSettingOptions().Names();

  m.def("falloff", [](const Skeleton& skeleton, const Motion& motion, int frame, const std::string& method,
                      const py::kwargs& keywords) {
        CheckMotion(skeleton, motion);
        FalloffSettings falloff_settings;
        ApplyKeywords(keywords, {py::cast(&falloff_settings, py::return_value_policy::reference)},
                      FalloffSettingOptions().Names());
        FalloffMethod kind;
        if (!ParseFalloffMethod(method, &kind)) {
          throw py::value_error("--method: expected green, diffusion or isomap, got '" + method + "'");
        }
        FalloffOptions options;
        ThrowIfError(FalloffOptionsFromSettings(falloff_settings, motion.num_frames(), &options));
        Falloff falloff;
        Status status = Status::Ok();
        {
          py::gil_scoped_release release;
          status = ComputeFalloff(skeleton, motion, frame, kind, options, &falloff);
        }
        ThrowIfError(status);
        py::dict d;
        d["weight"] = VectorToArray(falloff.weight);
        d["distance"] = VectorToArray(falloff.distance);
        d["raw"] = VectorToArray(falloff.raw);
        d["frame"] = falloff.frame;
        d["region"] = py::make_tuple(falloff.region_begin, falloff.region_end);
        d["sigma"] = falloff.sigma_used;
        d["eigenpairs"] = falloff.eigenpairs_used;
        d["sparse_kernel"] = falloff.sparse_used;
        return d;
      }, py::arg("skeleton"), py::arg("motion"), py::arg("frame"), py::arg("method") = DefaultMethod(DistanceMethodOption()),
      (std::string(R"doc(The pose-space falloff of an edit at `frame` of motion (on skeleton), as `mocapsolve distance`: method
'green' (Green's function of the pose Laplacian), 'diffusion' or 'isomap'. Keywords: the
FalloffSettings (sigma, sigma_scale, eigenpairs, region='a:b', diffusion_steps, knn,
isomap_knn, falloff_kernel, feature_joints, joint_weights, temporal_weight).
Returns a dict: 'weight' (frames,) in [0, 1] (1 at the edit), 'distance', 'raw',
'region', 'sigma', 'eigenpairs', 'sparse_kernel'.)doc") +
       KeywordDefaults("Falloff keywords and defaults (FalloffSettings)", py::cast(FalloffSettings()), FalloffSettingOptions().Names())).c_str());

  m.def("distance", [](const Skeleton& skeleton, const Motion& motion, int frame, const std::string& method,
                       const std::string& sweep, const py::kwargs& keywords) {
        CheckMotion(skeleton, motion);
        DistanceConfig config;
        config.frame = frame;
        config.methods = method;
        config.falloff.sweep = sweep;
        ApplyKeywords(keywords, {py::cast(&config.falloff, py::return_value_policy::reference)},
                      FalloffSettingOptions().Names());
        DistanceResult result;
        Status status = Status::Ok();
        {
          py::gil_scoped_release release;
          status = RunDistance(skeleton, motion, "the motion", config, &result);
        }
        ThrowIfError(status);
        py::dict report = ReportToPython(result.report);
        py::dict weights, distances;
        for (size_t k = 0; k < result.methods.size(); ++k) {
          weights[result.method_names[k].c_str()] = VectorToArray(result.methods[k].weight);
          distances[result.method_names[k].c_str()] = VectorToArray(result.methods[k].distance);
        }
        py::list swept;
        for (const Falloff& f : result.swept) swept.append(VectorToArray(f.weight));
        report["weights"] = weights;
        report["distances"] = distances;
        report["sweep_weights"] = swept;
        return report;
      }, py::arg("skeleton"), py::arg("motion"), py::arg("frame"), py::arg("method") = DefaultMethod(DistanceMethodOption()), py::kw_only(),
      py::arg("sweep") = DeclaredDefault(FalloffSettingOptions(), "sweep"),
      (std::string(R"doc(The pose-space distance and falloff of an edit at `frame` of motion (on skeleton; as
read_motion returns them), as `mocapsolve distance`: method 'green', 'diffusion' or 'isomap', or several comma-separated; sweep: comma-separated
extra sigmas for Green's weights. Keywords: the FalloffSettings.
Returns the dict its --report writes (the clip's period, the weight at the same and
opposite phase of the other cycles, per method the second difference at the edit and
where the weight ends, ...) plus 'weights' and 'distances' {method: (frames,) array} and
'sweep_weights' (one (frames,) array per sigma). Releases the GIL.)doc") +
       KeywordDefaults("Falloff keywords and defaults (FalloffSettings)", py::cast(FalloffSettings()),
                       FalloffSettingOptions().Names())).c_str());

  m.def("spline_falloff", [](int num_frames, int frame, double spline_width, int region_begin, int region_end) {
        if (!(spline_width > 0.0) || !std::isfinite(spline_width)) {
          throw py::value_error("--spline_width must be positive");
        }
        return VectorToArray(SplineFalloff(num_frames, frame, spline_width, region_begin, region_end));
      }, py::arg("num_frames"), py::arg("frame"), py::arg("spline_width") = 30.0, py::arg("region_begin") = 0,
      py::arg("region_end") = -1, "The temporal baseline for a clip of num_frames frames: a cubic bump of half-width\n"
      "spline_width frames centred on frame, zero outside [region_begin, region_end) (-1 = the\n"
      "clip's end).");

  py::class_<PoseEdit>(m, "PoseEdit", "One edited frame: its index and the whole edited pose.")
      .def_readonly("frame", &PoseEdit::frame)
      .def_readonly("edited", &PoseEdit::edited);

  m.def("make_edit", [](const Motion& motion, int frame, const py::dict& rotation_offsets,
                        py::object root_offset) {
        PoseOffsets offsets;
        offsets.frame = frame;
        for (const auto& item : rotation_offsets) {
          const Array v = item.second.cast<Array>();
          CheckShape(v, {3}, "rotation offset");
          offsets.rotation_offsets.emplace_back(item.first.cast<int>(), Eigen::Vector3d(v.at(0), v.at(1), v.at(2)));
        }
        if (!root_offset.is_none()) {
          const Array root_translation_offset = root_offset.cast<Array>();
          CheckShape(root_translation_offset, {3}, "root_translation_offset");
          offsets.root_translation_offset = Eigen::Vector3d(
              root_translation_offset.at(0), root_translation_offset.at(1), root_translation_offset.at(2));
        }
        PoseEdit edit;
        ThrowIfError(MakeEdit(motion, offsets, &edit));
        return edit;
      }, py::arg("motion"), py::arg("frame"), py::arg("rotation_offsets"),
      py::arg("root_translation_offset") = py::none(),
      "An edit of motion's frame: rotation_offsets {joint index: rotation vector (radians, the\n"
      "joint's frame, R' = R exp(v))}, root_translation_offset (3,) in skeleton units.");

  m.def("read_edits", [](const std::string& path, const Skeleton& skeleton, const Motion& motion) {
        CheckMotion(skeleton, motion);
        RequireReadable(path);
        std::vector<PoseEdit> edits;
        ThrowIfError(ReadPoseEdits(path, skeleton, motion, &edits));
        return edits;
      }, py::arg("path"), py::arg("skeleton"), py::arg("motion"),
      "The edits of the edit file at path (.json, io/edit_file.h; joints named as in skeleton)\n"
      "applied to motion's frames: a list of PoseEdit.");

  m.def("propagate", [](const Skeleton& skeleton, const Motion& motion, const std::vector<PoseEdit>& edits,
                        const std::vector<Array>& weights) {
        CheckMotion(skeleton, motion);
        std::vector<Eigen::VectorXd> w;
        for (const Array& a : weights) {
          CheckShape(a, {motion.num_frames()}, "weights");
          w.push_back(Eigen::Map<const Eigen::VectorXd>(a.data(), a.shape(0)));
        }
        Motion out;
        Status status = Status::Ok();
        {
          py::gil_scoped_release release;
          status = PropagateEdits(skeleton, motion, edits, w, &out);
        }
        ThrowIfError(status);
        return out;
      }, py::arg("skeleton"), py::arg("motion"), py::arg("edits"), py::arg("weights"),
      "Propagates edits (PoseEdits) through motion on skeleton (eq. 5): weights[k] (frames,) is edit k's falloff\n"
      "(falloff()['weight'] or spline_falloff()). Returns the edited motion.");

  py::class_<PropagateSettings> propagate_settings(m, "PropagateSettings",
      "`mocapsolve propagate`'s own options (the IK edit's root pull, the harmonic and spline\n"
      "falloffs, the foot contacts); same names, defaults and units as its flags.");
  propagate_settings.def(py::init<>(), "Every option at the CLI's default.");
  BindOptionFields(propagate_settings, PropagateSettingOptions());
  m.attr("PROPAGATE_OPTION_NAMES") = PropagateSettingOptions().Names();

  m.def("propagate", [](const Skeleton& skeleton, const Motion& motion, const std::string& edit,
                        const std::string& ik_target, int frame, const std::string& method,
                        const std::string& foot_joints, const py::kwargs& keywords) {
        CheckMotion(skeleton, motion);
        PropagateConfig config;
        config.edit = edit;
        config.ik_target = ik_target;
        config.frame = frame;
        config.method = method;
        config.foot_joints = foot_joints;
        ApplyKeywords(keywords,
                      {py::cast(&config.propagate, py::return_value_policy::reference),
                       py::cast(&config.falloff, py::return_value_policy::reference),
                       py::cast(&config.solver, py::return_value_policy::reference)},
                      PropagateKeywordNames());
        if (!edit.empty()) RequireReadable(edit);
        PropagateResult result;
        Status status = Status::Ok();
        {
          py::gil_scoped_release release;
          status = RunPropagate(skeleton, motion, config, nullptr, &result);
        }
        ThrowIfError(status);
        py::list weights;
        for (const Eigen::VectorXd& w : result.weights.weights) weights.append(VectorToArray(w));
        py::dict report = ReportToPython(result.report);
        report["weights"] = weights;
        return py::make_tuple(std::move(result.propagated), report);
      }, py::arg("skeleton"), py::arg("motion"), py::kw_only(),
      py::arg("edit") = "", py::arg("ik_target") = DeclaredDefault(EditSettingOptions(), "ik_target"),
      py::arg("frame") = DeclaredDefault(EditSettingOptions(), "frame"),
      py::arg("method") = DefaultMethod(PropagateMethodOption()),
      py::arg("foot_joints") = DeclaredDefault(FootJointOption(), "foot_joints"),
      (std::string(R"doc(An edit propagated through a clip, as `mocapsolve propagate` (the whole command:
edits, falloff, propagation, foot contacts).

skeleton, motion: the clip (read_motion). Exactly one of edit (an edit file, .json) and
ik_target ('JOINT:x,y,z' in world skeleton units at frame; several separated by ';').
frame: the IK edit's frame (with edit: checked against a one-edit file; -1 = not given).
method: 'green' (default), 'harmonic' or 'spline'. foot_joints: comma-separated foot
joints for the contacts ('' = names with foot, toe or ankle).
Keywords: the PropagateSettings (keep_contacts=True holds planted feet), the
FalloffSettings and the IK solve's SolverSettings, as the CLI's flags.
Returns (motion, report): the propagated motion and what `propagate --report` writes
('edit', 'falloff', 'contacts' with max_drift_cm_without_keep / _with_keep, ...), plus
'weights': one (frames,) array per edit. Releases the GIL.)doc") +
       KeywordDefaults("Propagate keywords and defaults (PropagateSettings)", py::cast(PropagateSettings()),
                       PropagateSettingOptions().Names()) +
       KeywordDefaults("Falloff keywords and defaults (FalloffSettings)", py::cast(FalloffSettings()),
                       FalloffSettingOptions().Names())).c_str());

  m.def("ik_edit", [](const Skeleton& skeleton, const Motion& motion, int frame, const std::string& ik_target,
                      double ik_root_weight, const py::kwargs& keywords) {
        CheckMotion(skeleton, motion);
        const SolverSettings settings = SettingsFromKeywords(keywords);
        if (frame < 0 || frame >= motion.num_frames()) {
          throw py::value_error("--frame: expected 0 <= frame < " + std::to_string(motion.num_frames()) +
                                " with --ik_target, got " + std::to_string(frame));
        }
        std::vector<IkTarget> targets;
        ThrowIfError(ParseIkTargets(ik_target, skeleton, &targets));
        MarkerSolveOptions solve;
        ThrowIfError(MarkerSolveOptionsFromSettings(settings, skeleton.unit(), &solve));
        PropagateSettings checked;
        checked.ik_root_weight = ik_root_weight;
        ThrowIfError(PropagateSettingOptions().Validate(checked));
        solve.prior_translation_weight = ik_root_weight;
        PoseEdit edit;
        IkEditReport ik;
        Status status = Status::Ok();
        {
          py::gil_scoped_release release;
          status = SolveIkEdit(skeleton, motion, frame, targets, solve, &edit, &ik);
        }
        ThrowIfError(status);
        py::dict report;
        report["solver"] = settings.solver;
        report["ik_iterations"] = ik.solve.iterations;
        report["ik_max_target_error"] = ik.max_target_error;
        report["ik_final_cost"] = ik.solve.final_cost;
        return py::make_tuple(std::move(edit), report);
      }, py::arg("skeleton"), py::arg("motion"), py::arg("frame"), py::arg("ik_target"), py::kw_only(),
      py::arg("ik_root_weight") = 1.0,
      (std::string(R"doc(An IK edit, as `mocapsolve propagate --ik_target`: the pose of motion's frame solved so
that joints reach world points (problems/edit_propagation/ik_edit.h).

skeleton, motion: the clip (read_motion). frame: the edited frame (0-based).
ik_target: 'JOINT:x,y,z' (world, skeleton units), several separated by ';'.
ik_root_weight: pull of the root translation toward the original, per skeleton unit
  (default 1.0; 0 lets the root slide freely).
Every other keyword is a solver option of solve() (SolverSettings: solver='dls'|'dls_generic'|'ceres',
max_iterations, prior_weight, ...).
Returns (edit, report): a PoseEdit for propagate() and a dict (ik_iterations,
ik_max_target_error in skeleton units, ik_final_cost). Releases the GIL.)doc") +
       KeywordDefaults("Solver keywords and defaults (SolverSettings)", py::cast(SolverSettings()), SolverOptions().Names())).c_str());

  m.def("edit_weights", [](const Skeleton& skeleton, const Motion& motion, const std::vector<PoseEdit>& edits,
                           const std::string& method, double harmonic_ground, double spline_width,
                           const std::string& sparse_library, const py::kwargs& keywords) {
        CheckMotion(skeleton, motion);
        FalloffSettings falloff_settings;
        ApplyKeywords(keywords, {py::cast(&falloff_settings, py::return_value_policy::reference)},
                      FalloffSettingOptions().Names());
        ThrowIfError(PropagateMethodOption().Validate(MethodSetting{method}));
        FalloffOptions options;
        ThrowIfError(FalloffOptionsFromSettings(falloff_settings, motion.num_frames(), &options));
        const int region_begin = options.region_begin;
        const int region_end = options.region_end < 0 ? motion.num_frames() : options.region_end;
        std::vector<int> frames;
        for (const PoseEdit& edit : edits) {
          if (edit.frame < region_begin || edit.frame >= region_end) {
            throw py::value_error("--region: edited frame " + std::to_string(edit.frame) + " lies outside " +
                                  std::to_string(region_begin) + ":" + std::to_string(region_end));
          }
          frames.push_back(edit.frame);
        }
        EditWeightSettings settings;
        settings.harmonic_ground = harmonic_ground;
        settings.spline_width = spline_width;
        settings.sparse_library = sparse_library;
        EditWeights weights;
        Status status = Status::Ok();
        {
          py::gil_scoped_release release;
          status = ComputeEditWeights(method, skeleton, motion, options, frames, settings, &weights);
        }
        ThrowIfError(status);
        py::list arrays;
        for (const Eigen::VectorXd& w : weights.weights) arrays.append(VectorToArray(w));
        py::object report = ReportToPython(weights.report);
        return py::make_tuple(arrays, report);
      }, py::arg("skeleton"), py::arg("motion"), py::arg("edits"), py::arg("method") = DefaultMethod(PropagateMethodOption()), py::kw_only(),
      py::arg("harmonic_ground") = EditWeightSettings().harmonic_ground,
      py::arg("spline_width") = EditWeightSettings().spline_width,
      py::arg("sparse_library") = EditWeightSettings().sparse_library,
      (std::string(R"doc(The falloff weights of edits as `mocapsolve propagate` computes them
(pipeline/edit_weights.h), one (frames,) array per edit, for propagate().

skeleton, motion: the clip. edits: PoseEdits (make_edit, read_edits, ik_edit).
method: 'green' (default; the normalized row of the pose-space Green's function),
  'harmonic' (the harmonic function on the kNN pose graph: 1 at the edit, 0 at the other
  edits, at a ground node and at the ends of the region; Zhu et al. 2003) or 'spline'.
harmonic_ground: method='harmonic': weight of every frame's edge to the ground node held
  at 0, as a fraction of the graph's mean degree (default 0.002; 0 = pure harmonic with the
  clip's ends held at 0).
spline_width: method='spline': half-width of the cubic bump, frames (default 30).
sparse_library: the harmonic solve's sparse library, 'eigen_sparse' (default) or
  'suite_sparse'.
Other keywords: the FalloffSettings (sigma, sigma_scale, eigenpairs, region='a:b', knn,
falloff_kernel, feature_joints, joint_weights, temporal_weight; as falloff()).
Returns (weights, report): the list of arrays and the CLI report's 'falloff' dict.
Releases the GIL.)doc") +
       KeywordDefaults("Falloff keywords and defaults (FalloffSettings)", py::cast(FalloffSettings()), FalloffSettingOptions().Names())).c_str());
}

}  // namespace mocapsolve::python
