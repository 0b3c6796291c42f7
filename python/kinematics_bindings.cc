// kinematics: Skeleton, Motion, Pose, FK, characters (glTF skin), skinning, Jacobians.
#include <cmath>

#include "io/gltf_reader.h"
#include "io/input_limits.h"
#include "kinematics/forward_kinematics.h"
#include "kinematics/kinematic_jacobians.h"
#include "kinematics/skinning.h"
#include "python/bindings.h"


namespace mocapsolve::python {
namespace {

using CharacterPtr = std::shared_ptr<GltfCharacter>;

Pose PoseFromArrays(const Skeleton& skeleton, const Array& rotations, const Array& translations) {
  const py::ssize_t joints = skeleton.num_joints();
  CheckShape(rotations, {joints, 4}, "rotations");
  Pose pose = RestPose(skeleton);
  auto r = rotations.unchecked<2>();
  for (py::ssize_t j = 0; j < joints; ++j) {
    pose.rotations[j] = Eigen::Quaterniond(r(j, 3), r(j, 0), r(j, 1), r(j, 2));
  }
  if (translations.ndim() == 1) {  // The root's only.
    CheckShape(translations, {3}, "root_translation");
    pose.translations[0] = Eigen::Vector3d(translations.at(0), translations.at(1), translations.at(2));
  } else {
    CheckShape(translations, {joints, 3}, "translations");
    auto t = translations.unchecked<2>();
    for (py::ssize_t j = 0; j < joints; ++j) pose.translations[j] = Eigen::Vector3d(t(j, 0), t(j, 1), t(j, 2));
  }
  CheckPose(skeleton, pose, "pose");
  return pose;
}

// A Motion from (frames, joints, 4) rotations and (frames, 3) root or (frames, joints, 3)
// local translations; other joints' translations are the skeleton's rest offsets.
Motion MakeMotion(const Skeleton& skeleton, const Array& rotations, const Array& translations, double rate) {
  const py::ssize_t joints = skeleton.num_joints();
  CheckShape(rotations, {-1, joints, 4}, "rotations");
  const py::ssize_t frames = rotations.shape(0);
  const bool root_only = translations.ndim() == 2;
  if (root_only) {
    CheckShape(translations, {frames, 3}, "root_translations");
  } else {
    CheckShape(translations, {frames, joints, 3}, "translations");
  }
  Motion motion;
  motion.frame_rate = rate;
  motion.frames.assign(frames, RestPose(skeleton));
  auto r = rotations.unchecked<3>();
  const double* t = translations.data();
  for (py::ssize_t f = 0; f < frames; ++f) {
    Pose& pose = motion.frames[f];
    for (py::ssize_t j = 0; j < joints; ++j) {
      pose.rotations[j] = Eigen::Quaterniond(r(f, j, 3), r(f, j, 0), r(f, j, 1), r(f, j, 2));
    }
    if (root_only) {
      pose.translations[0] = Eigen::Vector3d(t[3 * f], t[3 * f + 1], t[3 * f + 2]);
    } else {
      for (py::ssize_t j = 0; j < joints; ++j) {
        const double* p = t + 3 * (f * joints + j);
        pose.translations[j] = Eigen::Vector3d(p[0], p[1], p[2]);
      }
    }
  }
  ThrowIfError(ValidateMotion(skeleton, motion));
  return motion;
}

// ValueError naming `what` unless every row of (..., 4) rotations is a finite unit
// quaternion (to 1e-6, ValidateMotion's tolerance).
void CheckUnitQuaternions(const Array& rotations, const char* what) {
  const double* q = rotations.data();
  for (py::ssize_t i = 0; i + 4 <= rotations.size(); i += 4, q += 4) {
    const double norm = Eigen::Vector4d(q[0], q[1], q[2], q[3]).norm();
    if (!std::isfinite(norm) || std::abs(norm - 1.0) > 1e-6) {
      throw py::value_error(std::string(what) + ": expected finite unit quaternions (x, y, z, w)");
    }
  }
}

void SetRotations(Motion* motion, const Array& rotations) {
  const py::ssize_t joints = motion->frames.empty() ? 0 : motion->frames[0].rotations.size();
  CheckShape(rotations, {motion->num_frames(), joints, 4}, "rotations");
  CheckUnitQuaternions(rotations, "rotations");
  auto r = rotations.unchecked<3>();
  for (int f = 0; f < motion->num_frames(); ++f) {
    for (py::ssize_t j = 0; j < joints; ++j) {
      motion->frames[f].rotations[j] = Eigen::Quaterniond(r(f, j, 3), r(f, j, 0), r(f, j, 1), r(f, j, 2));
    }
  }
}

void SetTranslations(Motion* motion, const Array& translations, bool root_only) {
  const py::ssize_t joints = motion->frames.empty() ? 0 : motion->frames[0].translations.size();
  if (root_only) {
    CheckShape(translations, {motion->num_frames(), 3}, "root_translations");
  } else {
    CheckShape(translations, {motion->num_frames(), joints, 3}, "translations");
  }
  CheckFinite(translations, root_only ? "root_translations" : "translations");
  const double* t = translations.data();
  for (int f = 0; f < motion->num_frames(); ++f) {
    if (root_only) {
      motion->frames[f].translations[0] = Eigen::Vector3d(t[3 * f], t[3 * f + 1], t[3 * f + 2]);
      continue;
    }
    for (py::ssize_t j = 0; j < joints; ++j) {
      const double* p = t + 3 * (f * joints + j);
      motion->frames[f].translations[j] = Eigen::Vector3d(p[0], p[1], p[2]);
    }
  }
}

Array Matrix3XToArray(const Eigen::Matrix3Xd& m) {
  Array out({py::ssize_t{m.cols()}, py::ssize_t{3}});
  std::copy(m.data(), m.data() + m.size(), out.mutable_data());
  return out;
}

Eigen::VectorXi JointIndices(const Skeleton& skeleton, py::object joint) {
  if (py::isinstance<py::str>(joint)) {
    const int j = skeleton.FindJoint(joint.cast<std::string>());
    if (j < 0) throw py::value_error("unknown joint '" + joint.cast<std::string>() + "'");
    return Eigen::VectorXi::Constant(1, j);
  }
  if (!py::isinstance<py::int_>(joint) || py::isinstance<py::bool_>(joint)) {
    throw py::type_error("joint: expected a joint index or name, got " +
                         std::string(py::str(joint.get_type().attr("__name__"))));
  }
  int overflow = 0;
  const long long index = PyLong_AsLongLongAndOverflow(joint.ptr(), &overflow);
  if (overflow != 0 || index < 0 || index >= skeleton.num_joints()) {
    throw py::index_error("joint " + std::string(py::repr(joint)) + " out of range [0, " +
                          std::to_string(skeleton.num_joints()) + ")");
  }
  return Eigen::VectorXi::Constant(1, static_cast<int>(index));
}

}  // namespace

void BindKinematics(py::module_& m) {
  py::class_<Skeleton, std::shared_ptr<Skeleton>>(m, "Skeleton",
      "An immutable joint hierarchy, parents first (parents[j] < j, root 0 has -1).")
      .def_property_readonly("joint_names", [](const Skeleton& s) {
        std::vector<std::string> names;
        for (int j = 0; j < s.num_joints(); ++j) names.push_back(s.name(j));
        return names;
      })
      .def_property_readonly("parents", [](const Skeleton& s) {
        std::vector<int> parents;
        for (int j = 0; j < s.num_joints(); ++j) parents.push_back(s.parent(j));
        return parents;
      })
      .def_property_readonly("offsets", [](const Skeleton& s) {
        Array out({py::ssize_t{s.num_joints()}, py::ssize_t{3}});
        for (int j = 0; j < s.num_joints(); ++j) {
          for (int k = 0; k < 3; ++k) out.mutable_at(j, k) = s.offset(j)[k];
        }
        return out;
      }, "(joints, 3) rest offsets in the parent's frame, file units.")
      .def_property_readonly("rotation_axes", [](const Skeleton& s) {
        std::vector<std::vector<int>> axes;
        for (int j = 0; j < s.num_joints(); ++j) axes.push_back(s.rotation_axes(j));
        return axes;
      }, "Per joint, the local axes (0=x, 1=y, 2=z) it may rotate about (its dofs).")
      .def_property_readonly("num_joints", &Skeleton::num_joints)
      .def_property_readonly("units", [](const Skeleton& s) { return s.unit().name; })
      .def_property_readonly("metres_per_unit", [](const Skeleton& s) { return s.unit().metres_per_unit; })
      .def("find_joint", &Skeleton::FindJoint, py::arg("name"), "Index of the joint named name, or -1.")
      .def("rest_pose", &RestPose, "The rest pose (offsets, identity rotations).")
      .def("__repr__", [](const Skeleton& s) {
        return "<mocapsolve.Skeleton " + std::to_string(s.num_joints()) + " joints, " + s.unit().name + ">";
      });

  py::class_<Pose>(m, "Pose", "One frame: local translations and rotations of every joint.")
      .def(py::init(&PoseFromArrays), py::arg("skeleton"), py::arg("rotations"),
           py::arg("translations"),
           "A pose of skeleton: rotations (joints, 4) x, y, z, w; translations (joints, 3) or the\n"
           "root's (3,) (the others keep their rest offsets), skeleton units.")
      .def_property("rotations",
          [](const Pose& p) { return QuaternionArray(p.rotations); },
          [](Pose& p, const Array& a) {
            CheckShape(a, {static_cast<py::ssize_t>(p.rotations.size()), 4}, "rotations");
            CheckUnitQuaternions(a, "rotations");
            for (size_t j = 0; j < p.rotations.size(); ++j) {
              p.rotations[j] = Eigen::Quaterniond(a.at(j, 3), a.at(j, 0), a.at(j, 1), a.at(j, 2));
            }
          }, "(joints, 4) x, y, z, w.")
      .def_property_readonly("translations", [](const Pose& p) {
            Array out({static_cast<py::ssize_t>(p.translations.size()), py::ssize_t{3}});
            for (size_t j = 0; j < p.translations.size(); ++j) {
              for (int k = 0; k < 3; ++k) out.mutable_at(j, k) = p.translations[j][k];
            }
            return out;
          }, "(joints, 3) local translations.")
      .def("copy", [](const Pose& p) { return Pose(p); }, "An independent copy of this pose.");

  py::class_<Motion>(m, "Motion",
      "A frame rate and one pose per frame. Array properties are copies (a Motion is not one\n"
      "contiguous block); assign them to change the motion.")
      .def(py::init(&MakeMotion), py::arg("skeleton"), py::arg("rotations"), py::arg("translations"),
           py::arg("rate"),
           "A motion of skeleton: rotations (frames, joints, 4) x, y, z, w; translations (frames, 3)\n"
           "for the root (the others keep their rest offsets) or (frames, joints, 3); rate in frames per second.")
      .def_property("rate", [](const Motion& mo) { return mo.frame_rate; },
                    [](Motion& mo, double rate) {
                      ThrowIfError(CheckFrameRate(rate, "rate"));
                      mo.frame_rate = rate;
                    }, "Frames per second (> 0, finite).")
      .def_property_readonly("num_frames", &Motion::num_frames)
      .def_property("rotations", &MotionRotations, [](Motion& mo, const Array& a) { SetRotations(&mo, a); },
                    "(frames, joints, 4) x, y, z, w.")
      .def_property("translations", &MotionTranslations,
                    [](Motion& mo, const Array& a) { SetTranslations(&mo, a, false); },
                    "(frames, joints, 3) local translations, file units.")
      .def_property("root_translations", &RootTranslations,
                    [](Motion& mo, const Array& a) { SetTranslations(&mo, a, true); },
                    "(frames, 3) the root's position, file units.")
      .def("pose", [](const Motion& mo, int f) {
            if (f < 0 || f >= mo.num_frames()) throw py::index_error("frame out of range");
            return mo.frames[f];
          }, py::arg("frame"), "The Pose of frame (0-based; IndexError when out of range).")
      .def("__len__", &Motion::num_frames)
      .def("__repr__", [](const Motion& mo) {
        return "<mocapsolve.Motion " + std::to_string(mo.num_frames()) + " frames at " +
               std::to_string(mo.frame_rate) + " fps>";
      });

  m.def("forward_kinematics", [](const Skeleton& skeleton, const Motion& motion) {
        CheckMotion(skeleton, motion);
        const py::ssize_t frames = motion.num_frames();
        Array out({frames, py::ssize_t{skeleton.num_joints()}, py::ssize_t{3}});
        double* data = out.mutable_data();
        {
          py::gil_scoped_release release;
          FkData fk(skeleton);
          for (const Pose& pose : motion.frames) {
            ForwardKinematics(skeleton, pose, &fk);
            for (const Eigen::Vector3d& p : fk.world_positions) {
              for (int k = 0; k < 3; ++k) *data++ = p[k];
            }
          }
        }
        return out;
      }, py::arg("skeleton"), py::arg("motion"),
      "World joint positions (frames, joints, 3) of motion on skeleton, in the skeleton's units.");

  m.def("joint_rotations_world", [](const Skeleton& skeleton, const Motion& motion) {
        CheckMotion(skeleton, motion);
        Array out({py::ssize_t{motion.num_frames()}, py::ssize_t{skeleton.num_joints()}, py::ssize_t{4}});
        double* data = out.mutable_data();
        FkData fk(skeleton);
        for (const Pose& pose : motion.frames) {
          ForwardKinematics(skeleton, pose, &fk);
          for (const Eigen::Quaterniond& q : fk.world_rotations) {
            *data++ = q.x(); *data++ = q.y(); *data++ = q.z(); *data++ = q.w();
          }
        }
        return out;
      }, py::arg("skeleton"), py::arg("motion"),
      "World joint rotations (frames, joints, 4) x, y, z, w of motion on skeleton.");

  m.def("joint_position_jacobian", [](const Skeleton& skeleton, const Pose& pose, py::object joint) {
        const int j = JointIndices(skeleton, joint)[0];
        CheckPose(skeleton, pose, "pose");
        FkData fk(skeleton);
        ForwardKinematics(skeleton, pose, &fk);
        PoseJacobian jacobian(3, PoseTangentSize(skeleton));
        JointPositionJacobian(skeleton, fk, j, &jacobian);
        Array out({py::ssize_t{3}, py::ssize_t{jacobian.cols()}});
        for (int r = 0; r < 3; ++r) {
          for (int c = 0; c < jacobian.cols(); ++c) out.mutable_at(r, c) = jacobian(r, c);
        }
        return out;
      }, py::arg("skeleton"), py::arg("pose"), py::arg("joint"),
      "d(world position of joint)/d pose, for a pose of skeleton and joint an index or a name:\n"
      "(3, 3 + 3 joints), columns [root translation |\n"
      "delta_0 | ... | delta_{J-1}] for R_j <- R_j exp(delta_j) (kinematics/kinematic_jacobians.h).");

  m.def("retract_pose", [](const Pose& pose, const Array& tangent) {
        Pose out = pose;
        CheckShape(tangent, {static_cast<py::ssize_t>(3 + 3 * pose.rotations.size())}, "tangent");
        CheckFinite(tangent, "tangent");
        Eigen::VectorXd d = Eigen::Map<const Eigen::VectorXd>(tangent.data(), tangent.shape(0));
        RetractPose(d, &out);
        return out;
      }, py::arg("pose"), py::arg("tangent"),
      "The retraction the Jacobians refer to, a new Pose from pose and tangent d (3 + 3 joints,):\n"
      "translation += d[0:3], R_j <- R_j exp(d[3+3j:6+3j]).");

  py::class_<GltfCharacter, CharacterPtr>(m, "Character",
      "A glTF character: skeleton (metres), skinned mesh, triangles, rest and bind poses.")
      .def_property_readonly("skeleton", [](const GltfCharacter& c) { return std::make_shared<Skeleton>(c.skeleton); })
      .def_property_readonly("rest_positions", [](const GltfCharacter& c) { return Matrix3XToArray(c.mesh.rest_positions()); },
                             "(vertices, 3) bind-space positions.")
      .def_property_readonly("rest_normals", [](const GltfCharacter& c) { return Matrix3XToArray(c.mesh.rest_normals()); })
      .def_property_readonly("triangles", [](const GltfCharacter& c) {
        py::array_t<int> out({py::ssize_t{c.triangles.cols()}, py::ssize_t{3}});
        std::copy(c.triangles.data(), c.triangles.data() + c.triangles.size(), out.mutable_data());
        return out;
      })
      .def_property_readonly("texcoords", [](const GltfCharacter& c) {
        py::array_t<double> out({py::ssize_t{c.mesh.texcoords().cols()}, py::ssize_t{2}});
        std::copy(c.mesh.texcoords().data(), c.mesh.texcoords().data() + c.mesh.texcoords().size(), out.mutable_data());
        return out;
      }, "(vertices, 2) texture coordinates (glTF's u, v: TEXCOORD_0), or (0, 2) when the file has none.")
      .def_property_readonly("num_vertices", [](const GltfCharacter& c) { return c.mesh.num_vertices(); })
      .def_property_readonly("rest_pose", [](const GltfCharacter& c) { return c.rest_pose; })
      .def_property_readonly("bind_pose", [](const GltfCharacter& c) { return c.bind_pose; })
      .def_property_readonly("animation_names", [](const GltfCharacter& c) { return c.animation_names; })
      .def_property_readonly("warnings", [](const GltfCharacter& c) { return c.warnings; });

  m.def("read_character", [](const std::string& path, const std::string& skin) {
        RequireReadable(path);
        auto character = std::make_shared<GltfCharacter>();
        GltfReadOptions options;
        options.skin = skin;
        Status status = Status::Ok();
        {
          py::gil_scoped_release release;
          status = ReadGltfCharacter(path, options, character.get());
        }
        ThrowIfError(status);
        return CharacterPtr(character);
      }, py::arg("path"), py::arg("skin") = "",
      "Reads the .glb/.gltf character at path (skin 0 unless skin= names one).");

  m.def("skin", [](const GltfCharacter& character, const Motion& motion) {
        CheckMotion(character.skeleton, motion);
        const py::ssize_t frames = motion.num_frames();
        const py::ssize_t vertices = character.mesh.num_vertices();
        Array positions({frames, vertices, py::ssize_t{3}});
        Array normals({frames, character.mesh.has_normals() ? vertices : 0, py::ssize_t{3}});
        {
          py::gil_scoped_release release;
          FkData fk(character.skeleton);
          std::vector<Eigen::Isometry3d> transforms;
          Eigen::Matrix3Xd p, n;
          for (py::ssize_t f = 0; f < frames; ++f) {
            ForwardKinematics(character.skeleton, motion.frames[f], &fk);
            ComputeSkinningTransforms(character.mesh, fk, &transforms);
            SkinMesh(character.mesh, transforms, &p, character.mesh.has_normals() ? &n : nullptr);
            std::copy(p.data(), p.data() + p.size(), positions.mutable_data() + f * vertices * 3);
            if (character.mesh.has_normals()) {
              std::copy(n.data(), n.data() + n.size(), normals.mutable_data() + f * vertices * 3);
            }
          }
        }
        return py::make_tuple(positions, normals);
      }, py::arg("character"), py::arg("motion"),
      "Linear blend skinning (thesis eqs. 5, 6) of character over every frame of motion (on its\n"
      "skeleton): (positions, normals), each\n"
      "(frames, vertices, 3); normals are not renormalized (kinematics/skinning.h).");

  m.def("skinned_vertex_jacobians", [](const GltfCharacter& character, const Pose& pose, int vertex) {
        const SkinnedMesh& mesh = character.mesh;
        if (vertex < 0 || vertex >= mesh.num_vertices()) throw py::index_error("vertex out of range");
        CheckPose(character.skeleton, pose, "pose");
        FkData fk(character.skeleton);
        ForwardKinematics(character.skeleton, pose, &fk);
        std::vector<Eigen::Isometry3d> transforms;
        ComputeSkinningTransforms(mesh, fk, &transforms);
        const int n = PoseTangentSize(character.skeleton);
        PoseJacobian jp(3, n), jn(3, n);
        SkinnedPositionJacobian(character.skeleton, mesh, fk, transforms, vertex, &jp);
        Array position({py::ssize_t{3}, py::ssize_t{n}}), normal({py::ssize_t{3}, py::ssize_t{n}});
        for (int r = 0; r < 3; ++r) {
          for (int c = 0; c < n; ++c) position.mutable_at(r, c) = jp(r, c);
        }
        if (mesh.has_normals()) {
          SkinnedNormalJacobian(character.skeleton, mesh, fk, transforms, vertex, &jn);
          for (int r = 0; r < 3; ++r) {
            for (int c = 0; c < n; ++c) normal.mutable_at(r, c) = jn(r, c);
          }
        }
        return py::make_tuple(position, normal);
      }, py::arg("character"), py::arg("pose"), py::arg("vertex"),
      "Exact d(skinned position)/d pose and d(skinned normal)/d pose of one vertex (an index) of\n"
      "character at pose, each\n"
      "(3, 3 + 3 joints), tangent layout as joint_position_jacobian.");
}

}  // namespace mocapsolve::python
