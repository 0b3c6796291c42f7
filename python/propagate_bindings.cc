// Edit propagation (the magic wand): pose-space falloffs (Green's function, diffusion,
// ISOMAP; spline in time), edits, and their propagation through a clip (eq. 5).
#include <cmath>

#include "io/edit_file.h"
#include "pipeline/falloff_settings.h"
#include "problems/edit_propagation/falloff.h"
#include "problems/edit_propagation/pose_edit.h"
#include "problems/edit_propagation/spline_falloff.h"
#include "python/bindings.h"

namespace mocapsolve::python {
namespace {

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
  settings.def(py::init<>());
#define MOCAPSOLVE_FIELD(name) settings.def_readwrite(#name, &FalloffSettings::name)
  MOCAPSOLVE_FIELD(sigma); MOCAPSOLVE_FIELD(sigma_scale); MOCAPSOLVE_FIELD(eigenpairs);
  MOCAPSOLVE_FIELD(region); MOCAPSOLVE_FIELD(diffusion_steps); MOCAPSOLVE_FIELD(knn);
  MOCAPSOLVE_FIELD(isomap_knn); MOCAPSOLVE_FIELD(falloff_kernel); MOCAPSOLVE_FIELD(feature_joints);
  MOCAPSOLVE_FIELD(joint_weights); MOCAPSOLVE_FIELD(temporal_weight);
#undef MOCAPSOLVE_FIELD
  settings.def("validate", [](const FalloffSettings& s, int num_frames) {
        FalloffOptions options;
        ThrowIfError(FalloffOptionsFromSettings(s, num_frames, &options));
      }, py::arg("num_frames"), "Raises ValueError (the CLI's message) if a value is invalid for a clip this long.");
  m.attr("FALLOFF_OPTION_NAMES") = std::string(kFalloffSettingNames);

  m.def("falloff", [](const Skeleton& skeleton, const Motion& motion, int frame, const std::string& method,
                      const py::kwargs& keywords) {
        FalloffSettings falloff_settings;
        ApplyKeywords(keywords, {py::cast(&falloff_settings, py::return_value_policy::reference)},
                      kFalloffSettingNames);
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
      }, py::arg("skeleton"), py::arg("motion"), py::arg("frame"), py::arg("method") = "green",
      R"doc(The pose-space falloff of an edit at `frame` (as `mocapsolve distance`): method
'green' (Green's function of the pose Laplacian), 'diffusion' or 'isomap'. Keywords: the
FalloffSettings (sigma, sigma_scale, eigenpairs, region='a:b', diffusion_steps, knn,
isomap_knn, falloff_kernel, feature_joints, joint_weights, temporal_weight).
Returns a dict: 'weight' (frames,) in [0, 1] (1 at the edit), 'distance', 'raw',
'region', 'sigma', 'eigenpairs', 'sparse_kernel'.)doc");

  m.def("spline_falloff", [](int num_frames, int frame, double spline_width, int region_begin, int region_end) {
        if (!(spline_width > 0.0) || !std::isfinite(spline_width)) {
          throw py::value_error("--spline_width must be positive");
        }
        return VectorToArray(SplineFalloff(num_frames, frame, spline_width, region_begin, region_end));
      }, py::arg("num_frames"), py::arg("frame"), py::arg("spline_width") = 30.0, py::arg("region_begin") = 0,
      py::arg("region_end") = -1, "The temporal baseline: a cubic bump of half-width spline_width frames.");

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
        RequireReadable(path);
        std::vector<EditFileEntry> entries;
        ThrowIfError(ReadEditFile(path, skeleton, &entries));
        std::vector<PoseEdit> edits;
        for (const EditFileEntry& entry : entries) {
          if (entry.frame >= motion.num_frames()) {
            throw py::value_error(entry.where + ": frame: " + std::to_string(entry.frame) +
                                  " is past the motion's last frame " + std::to_string(motion.num_frames() - 1));
          }
          PoseOffsets offsets;
          offsets.frame = entry.frame;
          offsets.rotation_offsets = entry.rotation_offsets_rad;
          offsets.root_translation_offset = entry.root_translation_offset;
          PoseEdit edit;
          const Status status = MakeEdit(motion, offsets, &edit);
          if (!status.ok()) throw py::value_error(entry.where + ": " + status.message());
          edits.push_back(std::move(edit));
        }
        return edits;
      }, py::arg("path"), py::arg("skeleton"), py::arg("motion"),
      "The edits of an edit file (.json, io/edit_file.h) applied to motion's frames.");

  m.def("propagate", [](const Skeleton& skeleton, const Motion& motion, const std::vector<PoseEdit>& edits,
                        const std::vector<Array>& weights) {
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
      "Propagates edits through the clip (eq. 5): weights[k] (frames,) is edit k's falloff\n"
      "(falloff()['weight'] or spline_falloff()). Returns the edited motion.");
}

}  // namespace mocapsolve::python
