// io: markers (C3D/TRC), motions (BVH, ASF/AMC, glTF, FBX), skeletons, subjects.
#include "io/bvh_writer.h"
#include "io/fbx_writer.h"
#include "io/gltf_reader.h"
#include "io/gltf_writer.h"
#include "io/input_limits.h"
#include "io/marker_file.h"
#include "io/marker_set_file.h"
#include "io/motion_file.h"
#include "settings/delivery_settings.h"
#include "settings/file_read_settings.h"
#include "settings/retarget_run_settings.h"
#include "python/bindings.h"
#include "python/keyword_docs.h"
#include "tasks/info_task.h"
#include "tasks/markers_task.h"

namespace mocapsolve::python {
namespace {

// A (frames, markers, 3) writable view on the trajectories' positions, kept alive by `self`.
py::array PositionsView(py::object self) {
  MarkerTrajectories& t = self.cast<MarkerTrajectories&>();
  const py::ssize_t d = sizeof(double);
  return py::array_t<double>({py::ssize_t{t.num_frames()}, py::ssize_t{t.num_markers()}, py::ssize_t{3}},
                             {3 * d * t.num_markers(), 3 * d, d},
                             t.mutable_positions_data(), self);
}

MarkersPtr MakeMarkers(const Array& positions, const std::vector<std::string>& labels, double rate,
                       const std::string& units) {
  CheckShape(positions, {-1, static_cast<py::ssize_t>(labels.size()), 3}, "positions");
  ThrowIfError(MarkerTrajectories::CheckLabels(labels));
  ThrowIfError(CheckFrameRate(rate, "rate"));
  auto markers = std::make_shared<MarkerTrajectories>(labels, static_cast<int>(positions.shape(0)));
  markers->frame_rate = rate;
  markers->unit = LengthUnitFromName(units);
  if (!units.empty() && !markers->unit.known()) {
    throw py::value_error("units='" + units + "': expected mm, cm, m or in");
  }
  auto p = positions.unchecked<3>();
  for (int f = 0; f < markers->num_frames(); ++f) {
    for (int m = 0; m < markers->num_markers(); ++m) {
      markers->SetSample(f, m, Eigen::Vector3d(p(f, m, 0), p(f, m, 1), p(f, m, 2)));
    }
  }
  if (Status status = CheckMarkerBounds(*markers); !status.ok()) throw py::value_error("positions: " + status.message());
  return markers;
}

}  // namespace

void BindIo(py::module_& m) {
  py::class_<MarkerTrajectories, MarkersPtr>(m, "Markers",
      "Labelled marker trajectories (C3D/TRC) in the file's axes and unit.\n\n"
      "positions: (frames, markers, 3) float64, NaN where a sample is missing; a writable\n"
      "view on the C++ storage (set a sample to NaN to make it missing).")
      .def(py::init(&MakeMarkers), py::arg("positions"), py::arg("labels"), py::arg("rate"),
           py::arg("units") = "mm",
           "Markers from arrays. positions: (frames, markers, 3) float64, NaN = missing; labels: one\n"
           "name per marker; rate: frames per second; units: of the positions (mm, cm, m, in; default mm).")
      .def_property_readonly("positions", &PositionsView)
      .def_property_readonly("labels", &MarkerTrajectories::labels)
      .def_property("rate", [](const MarkerTrajectories& t) { return t.frame_rate; },
                    [](MarkerTrajectories& t, double rate) {
                      ThrowIfError(CheckFrameRate(rate, "rate"));
                      t.frame_rate = rate;
                    }, "Frames per second (> 0, finite).")
      .def_property_readonly("units", [](const MarkerTrajectories& t) { return t.unit.name; })
      .def_property_readonly("metres_per_unit", [](const MarkerTrajectories& t) { return t.unit.metres_per_unit; })
      .def_readwrite("first_frame", &MarkerTrajectories::first_frame, "File frame number of frame 0.")
      .def_property_readonly("num_frames", &MarkerTrajectories::num_frames)
      .def_property_readonly("num_markers", &MarkerTrajectories::num_markers)
      .def_property_readonly("valid", [](MarkerTrajectories& t) {
            SyncMask(&t);
            py::array_t<bool> out({py::ssize_t{t.num_frames()}, py::ssize_t{t.num_markers()}});
            bool* data = out.mutable_data();
            for (std::uint8_t v : t.valid_mask()) *data++ = v != 0;
            return out;
          }, "(frames, markers) bool: the sample is present (its position is finite).")
      .def("find_marker", &MarkerTrajectories::FindMarker, py::arg("label"),
           "Index of the marker named label (subject prefixes ignored), or -1.")
      .def("__repr__", [](const MarkerTrajectories& t) {
        return "<mocapsolve.Markers " + std::to_string(t.num_frames()) + " frames x " +
               std::to_string(t.num_markers()) + " markers, " + t.unit.name + ">";
      });

  m.def("read_markers", [](const std::string& path, bool include_model_outputs, const std::string& subject_prefix) {
        RequireReadable(path);
        auto markers = std::make_shared<MarkerTrajectories>();
        MarkerReadOptions options;
        options.include_model_outputs = include_model_outputs;
        options.subject_prefix = subject_prefix;
        std::vector<std::string> warnings;
        options.warnings = &warnings;
        Status status = Status::Ok();
        {
          py::gil_scoped_release release;
          status = ReadMarkerFile(path, markers.get(), options);
        }
        ThrowIfError(status);
        for (const std::string& warning : warnings) PyErr_WarnEx(PyExc_UserWarning, warning.c_str(), 1);
        return markers;
      }, py::arg("path"),
      py::arg("include_model_outputs") = DeclaredDefault(FileReadSettingOptions(), "include_model_outputs"),
      py::arg("subject_prefix") = DeclaredDefault(FileReadSettingOptions(), "subject_prefix"),
      "Reads the .c3d or .trc file at path: Markers with .positions (frames, markers, 3; NaN where\n"
      "missing), .labels, .rate (Hz) and .units (the file's; nothing is rescaled).\n"
      "include_model_outputs: also read a C3D's model outputs (points listed by POINT:ANGLES,\n"
      "FORCES, MOMENTS, POWERS, REACTIONS, SCALARS, and Plug-in Gait's virtual points) as markers\n"
      "(default False: they are set apart, with a warning).\n"
      "subject_prefix: in a C3D of several subjects ('Daphnee:LASI', 'boite:M1'), the subject whose\n"
      "points are read, prefix stripped (default '': of several, the one with the most points,\n"
      "with a warning naming them).\n"
      "Duplicate labels are numbered (RKNE, RKNE#2) with a warning (warnings.warn).");
  m.def("write_markers", [](const std::string& path, MarkerTrajectories& markers) {
        SyncMask(&markers);
        py::gil_scoped_release release;
        ThrowIfError(WriteMarkerFile(path, markers));
      }, py::arg("path"), py::arg("markers"),
      "Writes markers (Markers) to path, a .c3d or .trc file (atomically; NaN samples as missing).");

  m.def("read_skeleton", [](const std::string& path, const std::string& skeleton_units) {
        RequireReadable(path);
        auto skeleton = std::make_shared<Skeleton>();
        ThrowIfError(ReadSkeletonFile(path, skeleton.get()));
        ThrowIfError(SetSkeletonUnits(skeleton_units, skeleton.get()));
        return SkeletonPtr(skeleton);
      }, py::arg("path"), py::arg("skeleton_units") = DeclaredDefault(FileReadSettingOptions(), "skeleton_units"),
      "The skeleton of the file at path (.bvh, .asf, .glb/.gltf (skin 0) or .fbx); skeleton_units\n"
      "(mm, cm, m, in) gives a BVH, which states none, its unit.");

  m.def("read_motion", [](const std::string& path, py::object skeleton, double amc_fps,
                          const std::string& animation, double sample_fps, const std::string& skeleton_units) {
        RequireReadable(path);
        FileReadSettings reading;
        reading.amc_fps = amc_fps;
        reading.animation = animation;
        reading.sample_fps = sample_fps;
        reading.skeleton_units = skeleton_units;
        const MotionFileOptions options =
            MotionReadOptionsOf(reading, skeleton.is_none() ? std::string() : std::string(py::str(skeleton)));
        if (!options.skeleton_path.empty()) RequireReadable(options.skeleton_path);
        auto out_skeleton = std::make_shared<Skeleton>();
        Motion motion;
        Status status = Status::Ok();
        {
          py::gil_scoped_release release;
          status = ReadMotionFile(path, options, out_skeleton.get(), &motion);
        }
        ThrowIfError(status);
        return py::make_tuple(SkeletonPtr(out_skeleton), std::move(motion));
      }, py::arg("path"), py::arg("skeleton") = py::none(),
      py::arg("amc_fps") = DeclaredDefault(FileReadSettingOptions(), "amc_fps"),
      py::arg("animation") = DeclaredDefault(FileReadSettingOptions(), "animation"),
      py::arg("sample_fps") = DeclaredDefault(FileReadSettingOptions(), "sample_fps"),
      py::arg("skeleton_units") = DeclaredDefault(FileReadSettingOptions(), "skeleton_units"),
      "Reads a motion: .bvh, .amc (skeleton= its .asf path), .glb/.gltf or .fbx\n"
      "(animation= a name or index, sample_fps= resampling rate). path: the file; amc_fps: the\n"
      "frame rate of an .amc (which states none; default 120); skeleton_units: the unit of a\n"
      "skeleton that states none (mm, cm, m, in). Returns (skeleton, motion)\n"
      "with motion.rotations (frames, joints, 4; x, y, z, w) and motion.root_translations\n"
      "(frames, 3) in the file's units.");

  m.def("info", [](const std::string& path, py::object skeleton, double amc_fps, const std::string& animation,
                   double sample_fps, const std::string& skeleton_units) {
        RequireReadable(path);
        InfoConfig config;
        if (!skeleton.is_none()) {
          config.skeleton = py::str(skeleton);
          RequireReadable(config.skeleton);
        }
        config.amc_fps = amc_fps;
        config.animation = animation;
        config.sample_fps = sample_fps;
        config.skeleton_units = skeleton_units;
        InfoResult result;
        Status status = Status::Ok();
        {
          py::gil_scoped_release release;
          status = RunInfo(path, config, &result);
        }
        for (const std::string& warning : result.warnings) py::module_::import("warnings").attr("warn")(warning);
        ThrowIfError(status);
        return ReportToPython(result.report);
      }, py::arg("path"), py::kw_only(), py::arg("skeleton") = py::none(),
      py::arg("amc_fps") = DeclaredDefault(FileReadSettingOptions(), "amc_fps"),
      py::arg("animation") = DeclaredDefault(FileReadSettingOptions(), "animation"),
      py::arg("sample_fps") = DeclaredDefault(FileReadSettingOptions(), "sample_fps"),
      py::arg("skeleton_units") = DeclaredDefault(FileReadSettingOptions(), "skeleton_units"),
      "What a file holds, as `mocapsolve info` (one task): path, a marker file (.c3d/.trc:\n"
      "labels, frames, rate, unit, missing samples, gap runs), a motion (.bvh, .amc with\n"
      "skeleton= its .asf), a skeleton (.asf) or a character (.glb/.gltf/.fbx: meshes, skins,\n"
      "the skeleton's first levels, height and bind pose, the animations; animation= a clip's\n"
      "name or index, sample_fps= its sampling rate). amc_fps: an .amc's frame rate (default\n"
      "120); skeleton_units: the unit of a skeleton that states none (mm, cm, m, in).\n"
      "Returns the dict its --report writes (without the envelope: status, version, options,\n"
      "inputs); the readers' warnings go to warnings.warn.");

  m.def("write_motion", [](const std::string& path, const Skeleton& skeleton, const Motion& motion,
                           int precision, double scale) {
        if (FileExtension(path) != ".bvh") throw py::value_error(path + ": expected a .bvh output");
        BvhWriteOptions options;
        options.precision = precision;
        options.scale = scale;
        py::gil_scoped_release release;
        ThrowIfError(WriteBvh(path, skeleton, motion, options));
      }, py::arg("path"), py::arg("skeleton"), py::arg("motion"), py::arg("precision") = 6,
      py::arg("scale") = 1.0,
      "Writes motion on skeleton to path, a .bvh (atomically): precision significant digits,\n"
      "lengths times scale.");

  m.def("write_gltf", [](const std::string& path, const std::string& target, const Motion& motion,
                         const std::string& clip_name) {
        RequireReadable(target);
        py::gil_scoped_release release;
        GltfDocument document;
        Status status = GltfDocument::Read(target, &document);
        GltfCharacter character;
        if (status.ok()) status = ReadGltfCharacter(document, GltfReadOptions(), &character);
        if (status.ok()) status = WriteGltfWithAnimation(document, character, motion, clip_name, path);
        ThrowIfError(status);
      }, py::arg("path"), py::arg("target"), py::arg("motion"), py::arg("clip_name") = "mocapsolve",
      "Writes the character file `target` (.glb/.gltf) plus `motion` (on its skeleton, e.g. from\n"
      "read_motion(target) or retarget()) as a new animation clip_name, to path (.glb/.gltf).");

  m.def("write_fbx", [](const std::string& path, const Skeleton& skeleton, const Motion& motion,
                        const std::string& clip_name, const std::string& euler_order, double fbx_key_tolerance) {
        if (FileExtension(path) != ".fbx") throw py::value_error(path + ": expected a .fbx output");
        FbxWriteOptions options;
        options.take_name = clip_name;
        options.key_tolerance_mm = fbx_key_tolerance;
        if (!euler_order.empty()) {
          EulerOrder order;
          if (!ParseEulerOrder(euler_order, &order)) {
            throw py::value_error("euler_order: '" + euler_order + "' is not one of XYZ, XZY, YXZ, YZX, ZXY, ZYX");
          }
          options.euler_order = order;
        }
        py::gil_scoped_release release;
        ThrowIfError(WriteFbx(path, skeleton, motion, options));
      }, py::arg("path"), py::arg("skeleton"), py::arg("motion"), py::kw_only(), py::arg("clip_name") = "mocapsolve",
      py::arg("euler_order") = "",
      py::arg("fbx_key_tolerance") = DeclaredDefault(DeliverySettingOptions(), "fbx_key_tolerance"),
      "Writes motion on skeleton to path as binary FBX 7.4 (atomically), as `mocapsolve convert\n"
      "IN OUT.fbx`: the skeleton as LimbNodes and the clip as the take clip_name; euler_order\n"
      "(XYZ, ..., ZYX) overrides each joint's rotation order; fbx_key_tolerance (mm) as the CLI's.");
  m.def("write_fbx", [](const std::string& path, const std::string& target, const Motion& motion,
                        const std::string& clip_name, bool animation_only, double fbx_key_tolerance) {
        if (FileExtension(path) != ".fbx") throw py::value_error(path + ": expected a .fbx output");
        RequireReadable(target);
        py::gil_scoped_release release;
        GltfCharacter character;
        Status status = ReadGltfCharacter(target, GltfReadOptions(), &character);
        if (status.ok()) status = WriteFbxCharacter(path, character, motion, clip_name, animation_only, fbx_key_tolerance);
        ThrowIfError(status);
      }, py::arg("path"), py::arg("target"), py::arg("motion"), py::kw_only(), py::arg("clip_name") = "mocapsolve",
      py::arg("animation_only") = DeclaredDefault(RetargetRunSettingOptions(), "animation_only"),
      py::arg("fbx_key_tolerance") = DeclaredDefault(DeliverySettingOptions(), "fbx_key_tolerance"),
      "Writes the character file `target` (.glb/.gltf) with `motion` (on its skeleton, e.g. from\n"
      "read_motion(target) or retarget()) as binary FBX 7.4 (atomically), as `convert IN OUT.fbx\n"
      "--target=`: the character's skeleton, skinned mesh (not with animation_only) and the clip\n"
      "as the take clip_name.");

  py::class_<Subject, SubjectPtr>(m, "Subject",
      "One actor: skeleton, calibrated marker set and how marker files map onto it.")
      .def_property_readonly("name", [](const Subject& s) { return s.name; })
      .def_property_readonly("skeleton", [](const Subject& s) { return std::make_shared<Skeleton>(s.skeleton); })
      .def_property_readonly("marker_labels", [](const Subject& s) {
        std::vector<std::string> labels;
        for (int i = 0; i < s.markers.num_markers(); ++i) labels.push_back(s.markers.label(i));
        return labels;
      })
      .def_property_readonly("axes", [](const Subject& s) { return s.axes; })
      .def_property_readonly("marker_scale", [](const Subject& s) { return s.marker_scale; })
      .def_property_readonly("amc_fps", [](const Subject& s) { return s.amc_fps; })
      .def_property_readonly("mean_pose", [](const Subject& s) -> py::object {
            if (s.mean_pose.empty()) return py::none();
            return QuaternionArray(s.mean_pose);
          },
          "(joints, 4) x, y, z, w: each joint's mean local rotation over the take the subject was fitted or\n"
          "calibrated on (the rest prior's reference, rest_prior_weight), or None if the file has none.");

  m.def("read_subject", [](const std::string& path) {
        RequireReadable(path);
        auto subject = std::make_shared<Subject>();
        ThrowIfError(ReadSubject(path, subject.get()));
        return SubjectPtr(subject);
      }, py::arg("path"), "Reads the subject file at path (calibrate/fit_skeleton --out_subject).");
  m.def("subject", [](const std::string& skeleton, const std::string& markerset, const std::string& axes,
                      double marker_scale, const std::string& skeleton_units, double amc_fps) {
        RequireReadable(skeleton);
        RequireReadable(markerset);
        SubjectFiles files;
        files.skeleton_path = skeleton;
        files.markerset_path = markerset;
        files.axes = axes;
        files.marker_scale = marker_scale;
        files.skeleton_units = skeleton_units;
        files.amc_fps = amc_fps;
        auto subject = std::make_shared<Subject>();
        ThrowIfError(LoadSubjectFromFiles(files, subject.get()));
        return SubjectPtr(subject);
      }, py::arg("skeleton"), py::arg("markerset"), py::arg("axes") = DeclaredDefault(FileReadSettingOptions(), "axes"),
      py::arg("marker_scale") = DeclaredDefault(FileReadSettingOptions(), "marker_scale"),
      py::arg("skeleton_units") = DeclaredDefault(FileReadSettingOptions(), "skeleton_units"),
      py::arg("amc_fps") = DeclaredDefault(FileReadSettingOptions(), "amc_fps"),
      "A subject from files, as the CLI's --skeleton, --markerset, --axes, --marker_scale,\n"
      "--skeleton_units and --amc_fps assemble it. skeleton: .bvh/.asf path; markerset: marker\n"
      "set .json path; axes: marker file -> skeleton axes (e.g. 'y,z,x'); marker_scale: marker\n"
      "units -> skeleton units (0 = from the units); skeleton_units: a BVH's unit (mm, cm, m,\n"
      "in); amc_fps: the frame rate of AMC motions (default 120).");
  m.def("write_subject", [](const std::string& path, const Subject& subject) {
        ThrowIfError(WriteSubject(path, subject));
      }, py::arg("path"), py::arg("subject"), "Writes subject to path, a subject .json file (atomically).");

  py::class_<SyntheticMarkerSettings> synthetic(m, "SyntheticMarkerSettings",
      "How `mocapsolve markers` writes synthetic markers, one per flag (noise_mm, seed, units;\n"
      "same defaults). markers() takes them as keywords.");
  synthetic.def(py::init<>(), "Every option at the CLI's default.");
  synthetic.def_readwrite("noise_mm", &SyntheticMarkerSettings::noise_mm)
      .def_readwrite("seed", &SyntheticMarkerSettings::seed)
      .def_readwrite("units", &SyntheticMarkerSettings::units);
  m.def("markers", [](const Skeleton& skeleton, const Motion& motion, const std::string& markerset,
                      const std::string& axes, double marker_scale, const py::kwargs& keywords) {
        CheckMotion(skeleton, motion);
        MarkersConfig config;
        config.markerset = markerset;
        config.axes = axes;
        config.marker_scale = marker_scale;
        ApplyKeywords(keywords, {py::cast(&config.markers, py::return_value_policy::reference)},
                      SyntheticMarkerOptions().Names());
        if (markerset.compare(0, 5, "auto:") != 0) RequireReadable(markerset);
        MarkersResult result;
        Status status = Status::Ok();
        {
          py::gil_scoped_release release;
          status = RunMarkers(skeleton, motion, "the motion", config, nullptr, &result);
        }
        ThrowIfError(status);
        if (!result.warning.empty()) py::module_::import("warnings").attr("warn")(result.warning);
        auto subject = std::make_shared<Subject>();
        subject->name = "synthetic";
        subject->skeleton = skeleton;
        subject->markers = result.marker_set;
        subject->axes = axes;
        subject->marker_scale = marker_scale;
        return py::make_tuple(std::make_shared<MarkerTrajectories>(std::move(result.trajectories)),
                              SubjectPtr(subject), ReportToPython(result.report));
      }, py::arg("skeleton"), py::arg("motion"), py::arg("markerset") = "auto:3", py::kw_only(),
      py::arg("axes") = DeclaredDefault(FileReadSettingOptions(), "axes"),
      py::arg("marker_scale") = DeclaredDefault(FileReadSettingOptions(), "marker_scale"),
      (std::string(R"doc(Synthetic markers from a motion, as `mocapsolve markers` (thesis eq. 9: each marker's
position after FK), optionally with Gaussian noise.

skeleton, motion: the clip (read_motion). markerset: 'auto:N' (N markers around every bone,
deterministic for the seed; 'auto:N:SEED' fixes the set's own seed) or a marker set .json
path. axes, marker_scale: the written file's axes and scale, as for solve() (the file from
the model: x_file = A^T x_model / scale; marker_scale 0 = from the units).
Keywords: noise_mm (standard deviation per coordinate, mm), seed, units (of the markers
when the skeleton states its unit: mm, cm, m, in).
Returns (markers, subject, report): the Markers (what --out writes), a Subject holding the
skeleton and the marker set used (solve(subject, markers) recovers the motion), and the
--report dict.)doc") + KeywordDefaults("Keywords and defaults (SyntheticMarkerSettings)", py::cast(SyntheticMarkerSettings()),
                                       SyntheticMarkerOptions().Names())).c_str());
}

}  // namespace mocapsolve::python
