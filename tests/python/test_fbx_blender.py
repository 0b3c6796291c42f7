"""The FBX files the pipeline writes, imported by Blender (headless, bpy.ops.import_scene.fbx).

Blender (Debian's `blender` package; `scripts/setup.sh --with-blender` installs it) imports
each file with no error or warning; its armature's bone heads at 10 sampled frames are our
forward kinematics within 0.1 mm (after the unit scale), the action spans the clip's frames
at its rate, and a skinned mesh keeps its vertex count, every vertex's weights sum to 1 and
the mesh Blender deforms lies on ours (linear blend skinning, mocapsolve.skin) within 0.1 mm
at those frames; where the source has texture coordinates (TEXCOORD_0) the mesh has one UV
layer with ours at every polygon corner. Cases: the project's generated walk (a BVH skeleton, no data needed), a
generated skinned character under an `Armature` node scaled 0.01 (no data needed), CMU 16_15
(walk) retargeted onto Xbot by `retarget --out=X.fbx`, and RobotExpressive's walk, whose
head, torso and limbs are meshes parented to bones (read as rigid parts of the skinned mesh).
All files go through one Blender process (scripts/fbx_blender_import.py).

Without Blender the test skips, or fails under MOCAPSOLVE_REQUIRE_DATA=1 (as CI runs it).
BLENDER names the executable (default: blender on PATH).
"""
import base64
import json
import os
import shutil
import struct
import subprocess

import numpy as np
import pytest

import mocapsolve
from conftest import REPO, data_file, run_cli

TOLERANCE_M = 1e-4  # 0.1 mm.
MAX_CHECKED_VERTICES = 1500


def blender_path():
    path = shutil.which(os.environ.get("BLENDER", "blender"))
    if path:
        return path
    if os.environ.get("MOCAPSOLVE_REQUIRE_DATA") == "1":
        pytest.fail("blender not found (MOCAPSOLVE_REQUIRE_DATA=1); scripts/setup.sh --with-blender installs it")
    pytest.skip("blender not found: the FBX import check needs it (scripts/setup.sh --with-blender)")


def write_scaled_armature_gltf(path):
    """A small skinned character under an `Armature` node scaled 0.01 (its joints and mesh
    in cm, as Mixamo exports them), with UVs and a 24-frame clip turning every joint."""
    # Joints: Hips (root, 100 cm up), Spine, Head above it, LeftLeg and RightLeg below.
    joints = [("Hips", -1, (0, 100, 0)), ("Spine", 0, (0, 25, 0)), ("Head", 1, (0, 35, 0)),
              ("LeftLeg", 0, (10, -5, 0)), ("RightLeg", 0, (-10, -5, 0))]
    world = []
    for name, parent, t in joints:
        world.append(np.array(t, float) + (world[parent] if parent >= 0 else 0.0))
    # Vertices: a diamond of 4 around each joint and one 45 cm below each leg joint (the feet).
    positions, weights, uvs = [], [], []
    for j, p in enumerate(world):
        for dx, dz in ((8, 0), (0, 8), (-8, 0), (0, -8)):
            positions.append(p + (dx, 0, dz))
            weights.append((j, 0 if j == 0 else (1 if j == 2 else 0), 1.0 if j in (0, 1) else 0.7))
            uvs.append((0.5 + dx / 20.0, j / 5.0 + dz / 40.0 + 0.1))
    for j in (3, 4):
        positions.append(world[j] + (0, -45, 0))
        weights.append((j, j, 1.0))
        uvs.append((0.9, 0.05 * j))
    n = len(positions)
    triangles = []
    for j in range(len(joints)):
        base = 4 * j
        triangles += [(base, base + 1, base + 2), (base, base + 2, base + 3)]
    for parent_ring, child_ring in ((0, 1), (1, 2), (0, 3), (0, 4)):
        a, b = 4 * parent_ring, 4 * child_ring
        for k in range(4):
            triangles += [(a + k, b + k, b + (k + 1) % 4), (a + k, b + (k + 1) % 4, a + (k + 1) % 4)]
    triangles += [(12, 13, 20), (16, 17, 21)]
    frames = 24
    times = [k / 24.0 for k in range(frames)]

    def axis_angle(axis, degrees):
        half = np.radians(degrees) / 2
        return list(np.sin(half) * np.array(axis, float)) + [np.cos(half)]

    rotations = {1: [axis_angle((0, 0, 1), 30 * np.sin(2 * np.pi * t)) for t in times],
                 2: [axis_angle((0, 1, 0), 60 * t) for t in times],
                 3: [axis_angle((1, 0, 0), 40 * np.sin(2 * np.pi * t)) for t in times],
                 4: [axis_angle((1, 0, 0), -40 * np.sin(2 * np.pi * t)) for t in times]}
    hips_t = [(0, 100 + 3 * np.sin(4 * np.pi * t), 50 * t) for t in times]

    blob = bytearray()
    views, accessors = [], []

    def add(array, dtype, gltf_type, component, target=None, minmax=False):
        data = np.asarray(array, dtype=dtype)
        while len(blob) % 4:
            blob.append(0)
        view = {"buffer": 0, "byteOffset": len(blob), "byteLength": data.nbytes}
        if target:
            view["target"] = target
        blob.extend(data.tobytes())
        views.append(view)
        accessor = {"bufferView": len(views) - 1, "componentType": component, "count": len(data), "type": gltf_type}
        if minmax:
            accessor["min"] = [float(x) for x in data.reshape(len(data), -1).min(axis=0)]
            accessor["max"] = [float(x) for x in data.reshape(len(data), -1).max(axis=0)]
        accessors.append(accessor)
        return len(accessors) - 1

    position = add(positions, np.float32, "VEC3", 5126, 34962, minmax=True)
    texcoord = add(uvs, np.float32, "VEC2", 5126, 34962)
    joint_index = add([(a, b, 0, 0) for a, b, _ in weights], np.uint16, "VEC4", 5123, 34962)
    weight = add([(w, 1 - w, 0, 0) if a != b else (1, 0, 0, 0) for a, b, w in weights], np.float32, "VEC4", 5126,
                 34962)
    indices = add(np.array(triangles, np.uint16).reshape(-1), np.uint16, "SCALAR", 5123, 34963)
    # Inverse bind matrices in the Armature's (cm) space, column-major.
    ibms = []
    for p in world:
        m = np.eye(4)
        m[:3, 3] = -p
        ibms.append(m.T.reshape(-1))
    ibm = add(ibms, np.float32, "MAT4", 5126)
    time_accessor = add(times, np.float32, "SCALAR", 5126, minmax=True)
    samplers, channels = [], []
    for j, values in rotations.items():
        samplers.append({"input": time_accessor, "output": add(values, np.float32, "VEC4", 5126)})
        channels.append({"sampler": len(samplers) - 1, "target": {"node": 1 + j, "path": "rotation"}})
    samplers.append({"input": time_accessor, "output": add(hips_t, np.float32, "VEC3", 5126)})
    channels.append({"sampler": len(samplers) - 1, "target": {"node": 1, "path": "translation"}})
    nodes = [{"name": "Armature", "scale": [0.01, 0.01, 0.01], "children": [1, 6]}]
    for j, (name, parent, t) in enumerate(joints):
        node = {"name": name, "translation": [float(x) for x in t]}
        children = [1 + k for k, (_, p, _) in enumerate(joints) if p == j]
        if children:
            node["children"] = children
        nodes.append(node)
    nodes.append({"name": "body", "mesh": 0, "skin": 0})
    document = {
        "asset": {"version": "2.0", "generator": "mocapsolve test"},
        "scene": 0, "scenes": [{"nodes": [0]}], "nodes": nodes,
        "meshes": [{"name": "body", "primitives": [{"attributes": {"POSITION": position, "TEXCOORD_0": texcoord,
                                                                     "JOINTS_0": joint_index, "WEIGHTS_0": weight},
                                                      "indices": indices}]}],
        "skins": [{"joints": [1 + j for j in range(len(joints))], "inverseBindMatrices": ibm, "skeleton": 1}],
        "animations": [{"name": "sway", "samplers": samplers, "channels": channels}],
        "accessors": accessors, "bufferViews": views,
        "buffers": [{"byteLength": len(blob),
                     "uri": "data:application/octet-stream;base64," + base64.b64encode(bytes(blob)).decode()}],
    }
    with open(path, "w") as f:
        json.dump(document, f)
    return n


def sampled_frames(num_frames):
    return sorted(set((num_frames - 1) * k // 9 for k in range(10)))


def expected_case(name, fbx, motion_path, animation="", character_path=None):
    """What our own code computes for `fbx`: joint positions (and the skinned mesh's vertices
    when character_path is a glTF character) at 10 sampled frames of the clip."""
    skeleton, motion = mocapsolve.read_motion(motion_path, animation=animation)
    positions = mocapsolve.forward_kinematics(skeleton, motion)
    nf = motion.num_frames
    names = skeleton.joint_names
    case = {"name": name, "fbx": fbx, "num_frames": nf, "rate": motion.rate, "joints": {}}
    for f in sampled_frames(nf):
        case["joints"][str(f)] = {names[j]: [float(x) for x in positions[f, j]] for j in range(len(names))}
    if character_path:
        character = mocapsolve.read_character(character_path)
        skinned, _ = mocapsolve.skin(character, motion)
        nv = character.num_vertices
        indices = list(range(0, nv, max(1, nv // MAX_CHECKED_VERTICES)))
        case["num_vertices"] = nv
        case["vertex_indices"] = indices
        case["vertices"] = {str(f): skinned[f, indices].tolist() for f in sampled_frames(nf)}
        texcoords = character.texcoords
        if len(texcoords):
            case["uvs"] = texcoords[indices].tolist()
    return case


@pytest.fixture(scope="module")
def imported(tmp_path_factory):
    """Every case written, imported by one Blender process: {name: (case, result, messages)}."""
    blender = blender_path()
    folder = tmp_path_factory.mktemp("fbx_blender")
    cases = []
    # 1. The generated walk (a BVH skeleton in cm).
    walk = str(folder / "walk.bvh")
    run_cli("generate", "--demo_out=" + walk, "--frames=60", "--fps=30")
    run_cli("convert", walk, str(folder / "walk.fbx"), "--clip_name=take")
    cases.append(expected_case("generated walk (BVH)", str(folder / "walk.fbx"), walk))
    # 2. A generated skinned character under an Armature node scaled 0.01.
    scaled = str(folder / "scaled.gltf")
    write_scaled_armature_gltf(scaled)
    run_cli("convert", scaled, str(folder / "scaled.fbx"), "--clip_name=take")
    cases.append(expected_case("generated character under a 0.01 Armature", str(folder / "scaled.fbx"), scaled,
                               character_path=scaled))
    # 3. CMU 16_15 (walk) retargeted onto Xbot, 1 s of it: the FBX as retarget writes it, and
    #    the GLB of the same run, whose first clip is the take, for our FK and skinning.
    xbot = data_file("gltf/Xbot.glb")
    walk_bvh = data_file("bvh/16_15.bvh")
    for out in ("xbot_walk.fbx", "xbot_walk.glb"):
        run_cli("retarget", "--source=" + walk_bvh, "--target=" + xbot, "--out=" + str(folder / out),
                "--frames=0:120", expect=None)
        assert os.path.isfile(str(folder / out)), "retarget wrote no " + out
    glb = str(folder / "xbot_walk.glb")
    cases.append(expected_case("CMU 16_15 onto Xbot", str(folder / "xbot_walk.fbx"), glb, character_path=glb))
    # 4. RobotExpressive's walk: meshes parented to bones, the rig under RobotArmature scaled 100.
    robot = data_file("gltf/RobotExpressive.glb")
    run_cli("convert", robot, str(folder / "robot.fbx"), "--animation=Walking", "--clip_name=take")
    cases.append(expected_case("RobotExpressive Walking", str(folder / "robot.fbx"), robot, animation="Walking",
                               character_path=robot))

    cases_path, result_path = str(folder / "cases.json"), str(folder / "result.json")
    with open(cases_path, "w") as f:
        json.dump(cases, f)
    run = subprocess.run([blender, "-b", "--factory-startup", "--python-exit-code", "1", "--python",
                          os.path.join(REPO, "scripts", "fbx_blender_import.py"), "--", cases_path, result_path],
                         stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, timeout=600)
    assert run.returncode == 0, run.stdout[-3000:]
    messages, current = {}, None
    for line in run.stdout.splitlines():
        if line.startswith("fbx_check: case "):
            current = line[len("fbx_check: case "):]
            messages[current] = []
        elif line.startswith("fbx_check: done "):
            current = None
        elif current is not None:
            messages[current].append(line)
    results = json.load(open(result_path))
    return {case["name"]: (case, result, messages.get(case["name"], [])) for case, result in zip(cases, results)}


CASES = ["generated walk (BVH)", "generated character under a 0.01 Armature", "CMU 16_15 onto Xbot",
         "RobotExpressive Walking"]


@pytest.mark.parametrize("name", CASES)
def test_blender_imports_fbx(imported, name):
    case, got, messages = imported[name]
    complaints = [line for line in messages if "warning" in line.lower() or "error" in line.lower()]
    assert not complaints, "%s: Blender printed: %s" % (name, complaints[:3])
    assert got["armatures"] == 1 and got["has_action"], got
    assert got["missing"] == 0, "%s: %d joint samples have no bone" % (name, got["missing"])
    assert got["last"] - got["first"] + 1 == case["num_frames"], got
    assert abs(got["fps"] - round(case["rate"], 4)) <= 1e-4 * case["rate"], (got["fps"], case["rate"])
    assert got["axes_error"] < 1e-6, "%s: the armature's axes are not FBX Y up turned to Blender Z up" % name
    summary = ("%s: %d bones, %d frames at %g fps, bone heads within %.4g mm (%s) over %d samples" %
               (name, got["bones"], case["num_frames"], got["fps"], got["worst_bone"] * 1e3, got["worst_bone_at"],
                got["compared"]))
    assert got["worst_bone"] <= TOLERANCE_M, summary
    if "num_vertices" in case:
        assert got["meshes"] == 1 and got["vertices"] == case["num_vertices"], (got["vertices"], case["num_vertices"])
        assert got["badly_weighted"] == 0, "%s: %d vertices' weights do not sum to 1" % (name, got["badly_weighted"])
        summary += "; %d vertices, %d checked, within %.4g mm (%s)" % (
            got["vertices"], len(case["vertex_indices"]), got["worst_vertex"] * 1e3, got["worst_vertex_at"])
        assert got["worst_vertex"] <= TOLERANCE_M, summary
        if "uvs" in case:  # One UV layer, a UV at every polygon corner, ours within float precision.
            assert got["uv_layers"] == [1] and got["uv_data"] == got["loops"], (got["uv_layers"], got.get("uv_data"))
            assert got["uv_loops"] > 0 and got["worst_uv"] <= 1e-6, (got["uv_loops"], got["worst_uv"])
            summary += "; UVs at %d corners within %.2g" % (got["uv_loops"], got["worst_uv"])
        else:
            assert got["uv_layers"] == [0], got["uv_layers"]
    print(summary)
