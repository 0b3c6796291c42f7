# Renders one frame of a character delivered as GLB and as FBX, both imported into one
# Blender scene side by side (GLB left, FBX right, 1.2 m apart), with the workbench engine:
#   blender -b --factory-startup --python scripts/render_fbx_beside_glb.py -- IN.glb IN.fbx FRAME OUT.png
# The FBX is imported first, so the scene takes its frame rate and the glTF importer places
# the GLB's keys at the same times. The README's image: CMU 16_15 retargeted onto Xbot
# (`retarget --out=X.glb` and `--out=X.fbx`), frame 60, 480 x 360.
import math
import sys

import bpy
import numpy
from mathutils import Vector

# Debian 12's Blender 3.4 glTF add-on uses numpy.bool, which numpy 1.24 removed; it meant
# the builtin (as scripts/apply_animation_gltf.py does).
if "bool" not in numpy.__dict__:
    numpy.bool = bool

glb_path, fbx_path, frame, out_path = sys.argv[sys.argv.index("--") + 1:][:4]
bpy.ops.wm.read_factory_settings(use_empty=True)
scene = bpy.context.scene


def import_file(path, importer, offset_x, label):
    before = set(scene.objects)
    importer(filepath=path)
    new = [o for o in scene.objects if o not in before]
    for o in new:
        if o.parent is None:
            o.location.x += offset_x
    text_data = bpy.data.curves.new(label, "FONT")
    text_data.body = label
    text_data.align_x = "CENTER"
    text_data.size = 0.18
    text = bpy.data.objects.new(label, text_data)
    text.location = (offset_x, 0.0, 1.85)
    text.rotation_euler = (math.radians(90), 0, 0)
    scene.collection.objects.link(text)


import_file(fbx_path, bpy.ops.import_scene.fbx, 0.6, "FBX")
import_file(glb_path, bpy.ops.import_scene.gltf, -0.6, "GLB")
scene.frame_set(int(frame))

camera_data = bpy.data.cameras.new("camera")
camera_data.lens = 35
camera = bpy.data.objects.new("camera", camera_data)
scene.collection.objects.link(camera)
camera.location = (0.0, -3.4, 1.0)
direction = Vector((0.0, 0.0, 0.85)) - camera.location
camera.rotation_euler = direction.to_track_quat("-Z", "Y").to_euler()
scene.camera = camera

scene.render.engine = "BLENDER_WORKBENCH"
scene.display.shading.light = "STUDIO"
scene.display.shading.color_type = "OBJECT"
scene.display.shading.show_shadows = True
scene.display.shading.show_cavity = True
for o in scene.objects:
    if o.type == "MESH":
        o.color = (0.55, 0.65, 0.8, 1.0) if o.matrix_world.translation.x > 0 else (0.8, 0.65, 0.5, 1.0)
    if o.type == "FONT":
        o.color = (0.1, 0.1, 0.1, 1.0)
scene.render.resolution_x, scene.render.resolution_y = 480, 360
scene.render.resolution_percentage = 100
scene.render.film_transparent = False
scene.world = bpy.data.worlds.new("world")
scene.world.color = (1.0, 1.0, 1.0)
scene.render.image_settings.file_format = "PNG"
scene.render.image_settings.color_mode = "RGB"
scene.render.image_settings.compression = 100
scene.render.filepath = out_path
bpy.ops.render.render(write_still=True)
