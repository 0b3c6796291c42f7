# Blender side of the FBX import check (tests/python/test_fbx_blender.py): run as
#   blender -b --factory-startup --python-exit-code 1 --python scripts/fbx_blender_import.py -- CASES.json RESULT.json
# CASES.json lists FBX files with what our own code computes for them (joint positions at
# sampled frames, and for a skinned mesh its vertex count and the skinned positions of
# some of its vertices (vertex_indices) at those frames, all in the file's units and axes). Each file is imported on its own into an
# empty scene (bpy.ops.import_scene.fbx); RESULT.json gets, per case, what Blender shows:
# the action's frame range and the scene's rate, the armature's axes, the largest
# difference (metres) of bone heads and of the deformed mesh's vertices from ours, the
# vertex count, the vertices whose weights do not sum to 1, and where the case gives the
# texture coordinates (glTF's u, v) of its checked vertices, the largest difference of the
# first UV layer's (u, 1 - v) at their polygon corners. Lines "fbx_check: case NAME"
# go to stdout before each import, so the caller attributes Blender's messages to a case.
#
# Frames: Blender's armature object carries the file's axes and unit (FBX Y up turned Z
# up, scaled by UnitScaleFactor / 100 to metres); positions taken into armature space are
# in file units, so they compare with ours as they are, and a difference in metres is
# that times the object's scale.
import json
import sys

import bpy
from mathutils import Matrix, Vector


def check_case(case):
    bpy.ops.wm.read_factory_settings(use_empty=True)
    bpy.ops.import_scene.fbx(filepath=case["fbx"])
    scene = bpy.context.scene
    out = {"name": case["name"]}
    armatures = [o for o in scene.objects if o.type == "ARMATURE"]
    out["armatures"] = len(armatures)
    if len(armatures) != 1:
        return out
    arm = armatures[0]
    action = arm.animation_data.action if arm.animation_data else None
    out["has_action"] = action is not None
    if action is None:
        return out
    first = int(round(action.frame_range[0]))
    out["first"], out["last"] = first, int(round(action.frame_range[1]))
    out["fps"] = scene.render.fps / scene.render.fps_base
    out["bones"] = len(arm.data.bones)
    scale = arm.matrix_world.to_scale()[0]
    out["scale"] = scale
    axes = arm.matrix_world.to_3x3() * (1.0 / scale)
    y_up_to_z_up = Matrix(((1, 0, 0), (0, 0, -1), (0, 1, 0)))
    out["axes_error"] = max(abs(axes[i][k] - y_up_to_z_up[i][k]) for i in range(3) for k in range(3))
    meshes = [o for o in scene.objects if o.type == "MESH"]
    out["meshes"] = len(meshes)
    out["vertices"] = sum(len(o.data.vertices) for o in meshes)
    out["uv_layers"] = [len(o.data.uv_layers) for o in meshes]
    unweighted = 0
    for o in meshes:
        for v in o.data.vertices:
            if abs(sum(g.weight for g in v.groups) - 1.0) > 1e-4:
                unweighted += 1
    out["badly_weighted"] = unweighted
    worst_uv, uv_loops = 0.0, 0
    if case.get("uvs") and len(meshes) == 1 and meshes[0].data.uv_layers:
        mesh = meshes[0].data
        uv_data = mesh.uv_layers[0].data
        expected_uv = dict(zip(case["vertex_indices"], case["uvs"]))
        for loop in mesh.loops:
            uv = expected_uv.get(loop.vertex_index)
            if uv is None:
                continue
            got = uv_data[loop.index].uv
            worst_uv = max(worst_uv, abs(got[0] - uv[0]), abs(got[1] - (1.0 - uv[1])))
            uv_loops += 1
        out["uv_data"] = len(uv_data)
        out["loops"] = len(mesh.loops)
    out["worst_uv"], out["uv_loops"] = worst_uv, uv_loops
    arm_from_world = arm.matrix_world.inverted()
    worst_bone, worst_bone_at, compared, missing = 0.0, "", 0, 0
    worst_vertex, worst_vertex_at = 0.0, ""
    for frame_text, joints in sorted(case["joints"].items(), key=lambda item: int(item[0])):
        f = int(frame_text)
        scene.frame_set(first + f)
        for name, p in joints.items():
            bone = arm.pose.bones.get(name)
            if bone is None:
                missing += 1
                continue
            d = scale * (Vector(bone.head) - Vector(p)).length
            compared += 1
            if d > worst_bone:
                worst_bone, worst_bone_at = d, "%s at frame %d" % (name, f)
        expected = case.get("vertices", {}).get(frame_text)
        if expected is None or len(meshes) != 1:
            continue
        mesh_object = meshes[0]
        depsgraph = bpy.context.evaluated_depsgraph_get()
        evaluated = mesh_object.evaluated_get(depsgraph)
        mesh = evaluated.to_mesh()
        to_arm = arm_from_world @ mesh_object.matrix_world
        if len(mesh.vertices) != case["num_vertices"]:
            worst_vertex, worst_vertex_at = float("inf"), "%d vertices deformed" % len(mesh.vertices)
        else:
            for i, p in zip(case["vertex_indices"], expected):
                d = scale * (to_arm @ mesh.vertices[i].co - Vector(p)).length
                if d > worst_vertex:
                    worst_vertex, worst_vertex_at = d, "vertex %d at frame %d" % (i, f)
        evaluated.to_mesh_clear()
    out.update({"worst_bone": worst_bone, "worst_bone_at": worst_bone_at, "compared": compared,
                "missing": missing, "worst_vertex": worst_vertex, "worst_vertex_at": worst_vertex_at})
    return out


def main():
    cases_path, result_path = sys.argv[sys.argv.index("--") + 1:][:2]
    results = []
    for case in json.load(open(cases_path)):
        print("fbx_check: case %s" % case["name"], flush=True)
        results.append(check_case(case))
        print("fbx_check: done %s" % case["name"], flush=True)
    json.dump(results, open(result_path, "w"))


main()
