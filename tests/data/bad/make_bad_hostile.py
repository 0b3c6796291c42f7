# Regenerates the hostile bad files of tests/data/bad (python3 make_bad_hostile.py): inputs
# that crashed, hung or were silently accepted before issue 15 (see the comment of each).
# Every one must give a one-line error naming the file, exit 1, within seconds
# (tests/apps/cli_test.cc runs every bad_* file; tests/io/*_test.cc check the messages).
import json, os, struct, sys
B = os.path.dirname(os.path.abspath(__file__)) + '/'
sys.path.insert(0, os.path.join(B, '..', '..', '..', 'fuzz'))
from c3d_min import c3d_bytes

def write(name, data):
    with open(B + name, 'wb') as f:
        f.write(data.encode() if isinstance(data, str) else data)

# glTF/GLB: `extras` nested 30,000 deep: tinygltf's recursive ParseJsonAsValue overflowed
# the stack (SIGSEGV). Now refused by the JSON depth pre-scan.
depth = 30000
js = ('{"asset":{"version":"2.0","extras":' + '[' * depth + ']' * depth + '}}').encode()
js += b' ' * ((4 - len(js) % 4) % 4)
write('bad_gltf_deep_extras.glb',
      struct.pack('<4sII', b'glTF', 2, 20 + len(js)) + struct.pack('<I4s', len(js), b'JSON') + js)

# ASCII FBX with 30,000 nested braces: assimp's parser recursed once per brace (SIGSEGV).
fbx = '; FBX 7.4.0 project file\nFBXHeaderExtension: {\n FBXVersion: 7400\n}\nObjects: {\n'
fbx += 'A:{' * depth + '}' * depth + '\n}\n'
write('bad_fbx_deep_braces.fbx', fbx)

# BVH with "Frame Time: 1e-320" (a finite denormal): the frame rate came out infinite.
bvh = ('HIERARCHY\nROOT Hips\n{\n\tOFFSET 0 0 0\n\tCHANNELS 3 Xposition Yposition Zposition\n'
       '\tEnd Site\n\t{\n\t\tOFFSET 0 1 0\n\t}\n}\nMOTION\nFrames: 1\nFrame Time: 1e-320\n0 0 0\n')
write('bad_frame_time_tiny.bvh', bvh)

# BVH nesting 2,000 joints (the file had 100,000: `convert` wrote depth-many tabs
# per line, quadratic, and ran past 40 s at 2 GB). Now Skeleton::Create refuses a chain
# deeper than kMaxSkeletonDepth = 1000, and the writer's indentation is capped.
n = 2000
bvh = 'HIERARCHY\nROOT j0\n{\nOFFSET 0 0 0\nCHANNELS 3 Xposition Yposition Zposition\n'
for i in range(1, n):
    bvh += 'JOINT j%d\n{\nOFFSET 0 1 0\n' % i
bvh += 'End Site\n{\nOFFSET 0 1 0\n}\n' + '}\n' * n + 'MOTION\nFrames: 1\nFrame Time: 0.01\n0 0 0\n'
write('bad_deep_nesting.bvh', bvh)

def trc(labels, rows, name):
    text = ('PathFileType\t4\t(X/Y/Z)\t%s\n'
            'DataRate\tCameraRate\tNumFrames\tNumMarkers\tUnits\tOrigDataRate\tOrigDataStartFrame\tOrigNumFrames\n'
            '100\t100\t%d\t%d\tmm\t100\t1\t%d\n' % (name, len(rows), len(labels), len(rows)))
    text += 'Frame#\tTime\t' + '\t\t\t'.join(labels) + '\t\t\n'
    text += '\t\t' + '\t'.join('X%d\tY%d\tZ%d' % (i + 1, i + 1, i + 1) for i in range(len(labels))) + '\n\n'
    for f, row in enumerate(rows):
        text += '\t'.join(['%d' % (f + 1), '%g' % (f / 100.0)] + row) + '\n'
    return text

# TRC coordinate 1e308: `filter` exited 0 with "rms change nan mm" and wrote 5e306.
write('bad_huge_coordinate.trc', trc(['LASI', 'RASI'], [
    ['100', '200', '900', '-100', '200', '900'],
    ['101', '1e308', '900', '-99', '200', '900'],
    ['102', '200', '900', '-98', '200', '900']], 'bad_huge_coordinate.trc'))
# TRC with a label used twice: accepted, and `solve` failed much later ("no column for").
write('bad_duplicate_labels.trc', trc(['LBWT', 'RBWT', 'LBWT'], [
    ['1', '2', '3', '4', '5', '6', '7', '8', '9']], 'bad_duplicate_labels.trc'))

# C3D POINT:RATE of NaN, 0 and -120: the header's rate was used without a word.
frames = [[(1.0, 2.0, 3.0), (4.0, 5.0, 6.0)]]
for name, rate in (('nan', float('nan')), ('zero', 0.0), ('negative', -120.0)):
    write('bad_c3d_rate_%s.c3d' % name, c3d_bytes(['LBWT', 'RBWT'], frames, point_rate=rate))
# A quirk, not an error: real Motion Analysis files repeat labels; read with them numbered.
write('quirk_c3d_duplicate_labels.c3d', c3d_bytes(['LBWT', 'RBWT', 'LBWT'], [frames[0] + [(7.0, 8.0, 9.0)]]))

# Marker sets whose joint names hold an escaped newline / 20,000 characters: the error
# printed on two lines / echoed the whole name. Now quoted, escaped and cut at 64 bytes.
def markerset(joint):
    return json.dumps({"format": "mocapsolve.markerset", "version": 1, "units": "cm",
                       "markers": [{"label": "LFWT", "attachments": [{"joint": joint, "offset": [0, 0, 0]}]}]},
                      indent=1) + '\n'
write('bad_markerset_newline_name.json', markerset('Hips\nSpine'))
write('bad_markerset_long_name.json', markerset('J' * 20000))

# An ASCII FBX whose AnimationStack and AnimationLayer share the object id 3000: assimp
# leaks the first object (found by the fbx fuzzer; suppressed in fuzz/lsan.supp) and the
# clip ends up without an animation, which the reader reports.
fbx = """; FBX 7.4.0 project file
FBXHeaderExtension:  {
\tFBXHeaderVersion: 1003
\tFBXVersion: 7400
}
Objects:  {
\tModel: 1000, "Model::Hips", "LimbNode" {
\t\tVersion: 232
\t}
\tAnimationStack: 3000, "AnimStack::Take", "" {
\t}
\tAnimationLayer: 3000, "AnimLayer::Base", "" {
\t}
\tAnimationCurveNode: 3002, "AnimCurveNode::R", "" {
\t}
\tAnimationCurve: 3004, "AnimCurve::", "" {
\t\tKeyTime: *2 {
\t\t\ta: 0,1539538600
\t\t}
\t\tKeyValueFloat: *2 {
\t\t\ta: 0,10
\t\t}
\t}
}
Connections:  {
\tC: "OO",1000,0
\tC: "OO",3002,3000
\tC: "OP",3002,1000, "Lcl Rotation"
\tC: "OP",3004,3002, "d|X"
}
"""
write('bad_fbx_duplicate_object_id.fbx', fbx)

# glTF whose animation keys are 1e-39 s apart (found by the gltf fuzzer): the key rate
# came out 1e39 fps and the frame count overflowed int (UBSan). The seed character of
# fuzz/make_seeds.py with its second key time replaced.
import base64, subprocess, tempfile
with tempfile.TemporaryDirectory() as tmp:
    subprocess.check_call([sys.executable, os.path.join(B, '..', '..', '..', 'fuzz', 'make_seeds.py'), tmp])
    doc = json.load(open(os.path.join(tmp, 'gltf', 'skinned.gltf')))
prefix = 'data:application/octet-stream;base64,'
b = bytearray(base64.b64decode(doc['buffers'][0]['uri'][len(prefix):]))
times_offset = doc['bufferViews'][doc['accessors'][4]['bufferView']]['byteOffset']
struct.pack_into('<f', b, times_offset + 4, 1e-39)
doc['buffers'][0]['uri'] = prefix + base64.b64encode(bytes(b)).decode()
doc['accessors'][4]['max'] = [1e-39]
write('bad_gltf_key_rate.gltf', json.dumps(doc) + '\n')

# C3D of 0 points whose TRIAL fields claim frames 1..2^31-1 (1 KB): `info` passed, then
# convert, corrupt and view aborted with std::bad_alloc and filter ran until killed.
# Frames of no points take no bytes, so the data cannot bound their count: kMaxFrames
# (io/input_limits.h) does.
write('bad_c3d_no_points_huge_frames.c3d', c3d_bytes([], [], trial_end=2**31 - 1))

# Numbers a writer cannot represent (io/input_limits.h): a TRC rate of 1e308 was written
# to C3D as a float inf (read back NaN) and one of 1e-310 as 0; a BVH frame time of 1e308
# became a glTF time accessor with "max": [null]; a BVH root at 1e308 was read and
# `markers` wrote its frame as missing.
write('bad_trc_rate_huge.trc', trc(['LASI'], [['1', '2', '3']], 'bad_trc_rate_huge.trc').replace('100\t100\t1', '1e308\t1e308\t1', 1))
write('bad_trc_rate_denormal.trc', trc(['LASI'], [['1', '2', '3']], 'bad_trc_rate_denormal.trc').replace('100\t100\t1', '1e-310\t1e-310\t1', 1))
bvh = ('HIERARCHY\nROOT Hips\n{\n\tOFFSET 0 0 0\n\tCHANNELS 3 Xposition Yposition Zposition\n'
       '\tEnd Site\n\t{\n\t\tOFFSET 0 1 0\n\t}\n}\nMOTION\nFrames: 2\nFrame Time: %s\n0 0 0\n%s 0 0\n')
write('bad_frame_time_huge.bvh', bvh % ('1e308', '0'))
write('bad_root_position_huge.bvh', bvh % ('0.01', '1e308'))
