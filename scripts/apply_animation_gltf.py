"""Blender: put an animation-only glTF (`retarget --animation_only`, `pipeline --animation_only`)
onto the character it was made for.

    blender -b --factory-startup --python-exit-code 1 --python scripts/apply_animation_gltf.py -- \\
        CHARACTER.glb ANIMATION.glb [--compare=FULL.glb] [--frames=10] [--render=OUT.png --render_frame=N]
        [--save=OUT.blend]

Imports CHARACTER.glb (the character file, mesh and armature), then ANIMATION.glb (its skeleton,
skin and one animation: Blender makes the same armature of it, the bones' rest from the same
nodes and inverse bind matrices), moves the animation's action onto the character's armature
(bone names match; a bone the character lacks is an error) and deletes the imported skeleton.

--compare=FULL.glb: the full retargeted file (the character plus the same animation, as
`retarget` writes without --animation_only) is imported too, its animation made active, and
every bone's head and tail in world space compared between the two armatures at --frames
frames spread over the action (metres; float32 keys and Blender's float32 matrices give ~1e-6).
--render: a Cycles (CPU) image of the character at --render_frame, camera framing the armature.
--save: the .blend with the character and the applied action.

Prints one line "MOCAPSOLVE_APPLY bones=B animated_bones=A frames=F[ compared_frames=C
max_travel_m=T worst_m=W]" (comparing: the farthest a bone tail moves from its place at the
first compared frame, a control that the frames differ, and the worst distance between the
two armatures); exits 1 with a message on an error.
"""
import math
import sys

import bpy
import numpy
from mathutils import Vector

# Debian 12's Blender 3.4 glTF add-on uses numpy.bool, which numpy 1.24 removed
# ("AttributeError: module 'numpy' has no attribute 'bool'"); it meant the builtin.
if "bool" not in numpy.__dict__:
    numpy.bool = bool


def fail(message):
    print("MOCAPSOLVE_APPLY error: " + message)
    sys.exit(1)


def parse_arguments():
    args = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    positional = [a for a in args if not a.startswith("--")]
    options = dict(a[2:].split("=", 1) for a in args if a.startswith("--") and "=" in a)
    if len(positional) != 2:
        fail("usage: blender -b --python apply_animation_gltf.py -- CHARACTER.glb ANIMATION.glb "
             "[--compare=FULL.glb] [--frames=10] [--render=OUT.png --render_frame=N] [--save=OUT.blend]")
    known = {"compare", "frames", "render", "render_frame", "save"}
    unknown = set(options) - known
    if unknown:
        fail("unknown option --" + sorted(unknown)[0])
    return positional[0], positional[1], options


def import_gltf(path):
    """Imports a glTF; returns (the armature objects, the actions) it created."""
    objects_before = set(bpy.data.objects)
    actions_before = set(bpy.data.actions)
    try:
        result = bpy.ops.import_scene.gltf(filepath=path)
    except RuntimeError as e:
        fail("%s: import failed: %s" % (path, str(e).strip().splitlines()[-1]))
    if "FINISHED" not in result:
        fail("%s: import failed" % path)
    objects = [o for o in bpy.data.objects if o not in objects_before]
    armatures = [o for o in objects if o.type == "ARMATURE"]
    actions = [a for a in bpy.data.actions if a not in actions_before]
    return objects, armatures, actions


def one_armature(path, armatures):
    if len(armatures) != 1:
        fail("%s: expected one armature, got %d" % (path, len(armatures)))
    return armatures[0]


def animated_bones(action):
    bones = set()
    for curve in action.fcurves:
        if curve.data_path.startswith('pose.bones["'):
            bones.add(curve.data_path.split('"')[1])
    return bones


def apply_action(armature, action):
    if armature.animation_data is None:
        armature.animation_data_create()
    armature.animation_data.action = action
    scene = bpy.context.scene
    scene.frame_start = int(math.floor(action.frame_range[0]))
    scene.frame_end = int(math.ceil(action.frame_range[1]))


def bone_points(armature):
    world = armature.matrix_world
    return {b.name: (world @ b.head, world @ b.tail) for b in armature.pose.bones}


def render(armature, path, frame):
    scene = bpy.context.scene
    scene.frame_set(frame)
    points = [p for pair in bone_points(armature).values() for p in pair]
    low = Vector((min(p.x for p in points), min(p.y for p in points), min(p.z for p in points)))
    high = Vector((max(p.x for p in points), max(p.y for p in points), max(p.z for p in points)))
    centre = (low + high) / 2
    size = max((high - low).length, 0.5)
    camera_data = bpy.data.cameras.new("apply_camera")
    camera = bpy.data.objects.new("apply_camera", camera_data)
    scene.collection.objects.link(camera)
    camera.location = centre + Vector((0.9 * size, -2.2 * size, 0.35 * size))
    camera.rotation_euler = (centre - camera.location).to_track_quat("-Z", "Y").to_euler()
    scene.camera = camera
    sun_data = bpy.data.lights.new("apply_sun", type="SUN")
    sun_data.energy = 3.0
    sun = bpy.data.objects.new("apply_sun", sun_data)
    sun.rotation_euler = (math.radians(40), math.radians(10), math.radians(30))
    scene.collection.objects.link(sun)
    world = bpy.data.worlds.new("apply_world") if scene.world is None else scene.world
    scene.world = world
    world.color = (0.8, 0.8, 0.8)
    scene.render.engine = "CYCLES"
    scene.cycles.device = "CPU"
    scene.cycles.samples = 8
    scene.cycles.use_denoising = False  # Debian builds Cycles without OpenImageDenoise.
    scene.render.resolution_x = 480
    scene.render.resolution_y = 640
    scene.render.filepath = path
    bpy.ops.render.render(write_still=True)


def main():
    character_path, animation_path, options = parse_arguments()
    bpy.ops.wm.read_factory_settings(use_empty=True)
    character_objects, armatures, _ = import_gltf(character_path)
    character = one_armature(character_path, armatures)

    animation_objects, armatures, actions = import_gltf(animation_path)
    skeleton = one_armature(animation_path, armatures)
    if any(o.type == "MESH" for o in animation_objects):
        fail("%s: holds a mesh; expected an animation-only glTF" % animation_path)
    actions = [a for a in actions if animated_bones(a)]
    if len(actions) != 1:
        fail("%s: expected one animation of its skeleton, got %d" % (animation_path, len(actions)))
    action = actions[0]
    # The track name without the importer's "_<armature object>" suffix.
    name = action.name
    suffix = "_" + skeleton.name
    if name.endswith(suffix):
        name = name[: -len(suffix)]
    missing = sorted(animated_bones(action) - set(b.name for b in character.data.bones))
    if missing:
        fail("%s: bones %s are not bones of %s" % (animation_path, ", ".join(missing[:5]), character_path))
    apply_action(character, action)
    for o in animation_objects:
        bpy.data.objects.remove(o, do_unlink=True)
    action.name = name
    scene = bpy.context.scene
    first, last = scene.frame_start, scene.frame_end
    line = "MOCAPSOLVE_APPLY bones=%d animated_bones=%d frames=%d" % (
        len(character.data.bones), len(animated_bones(action)), last - first + 1)

    if "compare" in options:
        full_path = options["compare"]
        full_objects, armatures, full_actions = import_gltf(full_path)
        full = one_armature(full_path, armatures)
        same = [a for a in full_actions if a.name == name + "_" + full.name]
        if len(same) != 1:
            fail("%s: has no animation named '%s'" % (full_path, name))
        full.animation_data.action = same[0]
        count = max(2, int(options.get("frames", "10")))
        frames = sorted(set(first + (last - first) * k // (count - 1) for k in range(count)))
        worst = 0.0
        moved = 0.0  # Control: how far the bones travel over these frames (a still pose compares as 0 too).
        start = None
        for f in frames:
            scene.frame_set(f)
            ours, theirs = bone_points(character), bone_points(full)
            if set(ours) != set(theirs):
                fail("the character's bones differ between %s and %s" % (character_path, full_path))
            start = start or ours
            for bone, (head, tail) in ours.items():
                worst = max(worst, (head - theirs[bone][0]).length, (tail - theirs[bone][1]).length)
                moved = max(moved, (tail - start[bone][1]).length)
        for o in full_objects:
            bpy.data.objects.remove(o, do_unlink=True)
        line += " compared_frames=%d max_travel_m=%.3g worst_m=%.3g" % (len(frames), moved, worst)

    if "render" in options:
        render(character, bpy.path.abspath(options["render"]), int(options.get("render_frame", first)))
    if "save" in options:
        bpy.ops.wm.save_as_mainfile(filepath=bpy.path.abspath(options["save"]))
    print(line)


main()
