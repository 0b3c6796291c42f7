# Writes the seed corpora of the fuzz targets (python3 fuzz/make_seeds.py OUT_DIR): small
# valid and nearly valid files of each format, made here (never copies of real captures).
# OUT_DIR/<target>/<name>: bvh, asf, amc, c3d, trc, json, gltf, fbx, manifest.
import base64, json, os, struct, sys
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from c3d_min import c3d_bytes

out = sys.argv[1] if len(sys.argv) > 1 else 'build-fuzz/seeds'

def put(target, name, data):
    d = os.path.join(out, target)
    os.makedirs(d, exist_ok=True)
    with open(os.path.join(d, name), 'wb') as f:
        f.write(data.encode() if isinstance(data, str) else data)

BVH = """HIERARCHY
ROOT Hips
{
\tOFFSET 0 0 0
\tCHANNELS 6 Xposition Yposition Zposition Zrotation Xrotation Yrotation
\tJOINT LeftUpLeg
\t{
\t\tOFFSET 10 0 0
\t\tCHANNELS 3 Zrotation Xrotation Yrotation
\t\tEnd Site
\t\t{
\t\t\tOFFSET 0 -40 0
\t\t}
\t}
\tJOINT Spine
\t{
\t\tOFFSET 0 10 0
\t\tCHANNELS 3 Zrotation Xrotation Yrotation
\t\tEnd Site
\t\t{
\t\t\tOFFSET 0 30 0
\t\t}
\t}
}
MOTION
Frames: 3
Frame Time: 0.0333333
0 90 0 0 0 0 10 0 0 0 5 0
1 90 0 5 0 0 12 0 0 0 6 0
2 91 0 10 0 0 14 0 0 0 7 0
"""
put('bvh', 'small.bvh', BVH)
put('bvh', 'crlf.bvh', BVH.replace('\n', '\r\n'))
put('bvh', 'no_motion.bvh', BVH.replace('Frames: 3', 'Frames: 0').split('0 90')[0])

ASF = """:version 1.10
:name seed
:units
  mass 1.0
  length 0.45
  angle deg
:root
   order TX TY TZ RX RY RZ
   axis XYZ
   position 0 0 0
   orientation 0 0 0
:bonedata
  begin
     id 1
     name hip
     direction 1 0 0
     length 2
     axis 0 0 0 XYZ
  end
  begin
     id 2
     name thigh
     direction 0 -1 0
     length 7
     axis 0 0 20 XYZ
    dof rx ry rz
    limits (-160.0 20.0)
           (-70.0 70.0)
           (-60.0 70.0)
  end
:hierarchy
  begin
    root hip
    hip thigh
  end
"""
put('asf', 'small.asf', ASF)
AMC = """:FULLY-SPECIFIED
:DEGREES
1
root 0 17 0 0 0 0
thigh 10 0 5
2
root 0.1 17 0.2 0 1 0
thigh 12 0 5
"""
put('amc', 'small.amc', AMC)  # The amc target reads against the same skeleton.

labels = ['LFWT', 'RFWT', 'LBWT', 'RBWT']
frames = [[(100.0 * m, 10.0 * f, 900.0) for m in range(4)] for f in range(3)]
frames[1][2] = None
put('c3d', 'small.c3d', c3d_bytes(labels, frames))
put('c3d', 'one_marker.c3d', c3d_bytes(['A'], [[(1.0, 2.0, 3.0)]]))

def trc(labels, rows, rate=120.0):
    head = ('PathFileType\t4\t(X/Y/Z)\tseed.trc\n'
            'DataRate\tCameraRate\tNumFrames\tNumMarkers\tUnits\tOrigDataRate\tOrigDataStartFrame\tOrigNumFrames\n'
            '%g\t%g\t%d\t%d\tmm\t%g\t1\t%d\n' % (rate, rate, len(rows), len(labels), rate, len(rows)))
    head += 'Frame#\tTime\t' + '\t\t\t'.join(labels) + '\n'
    head += '\t\t' + '\t'.join('X%d\tY%d\tZ%d' % (i + 1, i + 1, i + 1) for i in range(len(labels))) + '\n\n'
    for f, row in enumerate(rows):
        cells = ['%d' % (f + 1), '%g' % (f / rate)]
        for p in row:
            cells += ['', '', ''] if p is None else ['%g' % v for v in p]
        head += '\t'.join(cells) + '\n'
    return head
put('trc', 'small.trc', trc(labels, frames))

put('json', 'markerset.json', json.dumps({
    "format": "mocapsolve.markerset", "version": 1, "units": "cm",
    "markers": [{"label": "LFWT", "attachments": [{"joint": "Hips", "offset": [10, 0, 5]}]},
                {"label": "LKNE", "attachments": [{"joint": "LeftUpLeg", "weight": 2, "offset": [0, -20, 4]},
                                                  {"joint": "Spine", "offset": [0, 1, 0]}]}]}, indent=1))
put('json', 'edit.json', json.dumps({
    "format": "mocapsolve.edit", "version": 1, "frame": 0,
    "joints": {"Spine": {"rotation_offset_deg": [0, 10, 0]}}, "root_translation_offset": [0, 1, 0]}, indent=1))
put('json', 'edits.json', json.dumps({
    "edits": [{"frame": 0, "joints": {"LeftUpLeg": {"rotation_offset_deg": [5, 0, 0]}}}]}))
put('json', 'values.json', '{"a": [1, 2.5e3, -0.0, true, false, null, "s\\u00e9\\n"], "b": {}}')

# Batch manifests (fuzz/manifest_fuzzer.cc knows the options filter_levels, gate_torso_deg,
# reference, animation_only).
put('manifest', 'manifest.json', json.dumps({
    "defaults": {"subject": "S.json", "characters": ["Xbot.glb"], "filter_levels": 1},
    "takes": [{"name": "02_05", "markers": "c3d/02_05.c3d"},
              {"markers": "/data/t2.trc", "subject": "S2.json", "characters": [], "reference": "plain",
               "animation_only": True}]}, indent=1))
put('manifest', 'names.json', json.dumps({
    "takes": [{"name": "javascript:alert(1)", "markers": "a.c3d", "subject": "S.json"},
              {"name": "a\u0000b", "markers": "b.c3d", "subject": "S.json"},
              {"name": "summary.html", "markers": "c.c3d", "subject": "S.json"}]}))
put('manifest', 'duplicate.json', '{"takes": [{"markers": "a.c3d", "subject": "S.json"}, '
    '{"markers": "x/a.c3d", "subject": "S.json"}]}')
put('manifest', 'types.json', '{"defaults": {"filter_levels": "1"}, "takes": [{"markers": 3}]}')

# glTF: a two-joint skinned triangle with a one-channel animation, as .gltf and .glb.
def gltf_doc(embed_uri=True):
    ibm = struct.pack('<32f', *([1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1] * 2))
    pos = struct.pack('<9f', 0, 0, 0, 1, 0, 0, 0, 1, 0)
    jnt = bytes([0, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0])
    wts = struct.pack('<12f', 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0)
    times = struct.pack('<2f', 0, 1)
    rots = struct.pack('<8f', 0, 0, 0, 1, 0, 0.7071, 0, 0.7071)
    b = ibm + pos + jnt + wts + times + rots
    views, off = [], 0
    for n in (128, 36, 12, 48, 8, 32):
        views.append({"buffer": 0, "byteOffset": off, "byteLength": n}); off += n
    acc = [{"bufferView": 0, "componentType": 5126, "count": 2, "type": "MAT4"},
           {"bufferView": 1, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]},
           {"bufferView": 2, "componentType": 5121, "count": 3, "type": "VEC4"},
           {"bufferView": 3, "componentType": 5126, "count": 3, "type": "VEC4"},
           {"bufferView": 4, "componentType": 5126, "count": 2, "type": "SCALAR", "min": [0], "max": [1]},
           {"bufferView": 5, "componentType": 5126, "count": 2, "type": "VEC4"}]
    buf = {"byteLength": len(b)}
    if embed_uri:
        buf["uri"] = "data:application/octet-stream;base64," + base64.b64encode(b).decode()
    doc = {"asset": {"version": "2.0", "extras": {"seed": [1, {"x": 2}]}}, "scene": 0,
           "scenes": [{"nodes": [0, 2]}],
           "nodes": [{"name": "root", "children": [1]}, {"name": "child", "translation": [0, 1, 0]},
                     {"name": "body", "mesh": 0, "skin": 0}],
           "meshes": [{"primitives": [{"attributes": {"POSITION": 1, "JOINTS_0": 2, "WEIGHTS_0": 3}}]}],
           "skins": [{"joints": [0, 1], "inverseBindMatrices": 0}],
           "animations": [{"name": "wave", "samplers": [{"input": 4, "output": 5}],
                           "channels": [{"sampler": 0, "target": {"node": 1, "path": "rotation"}}]}],
           "buffers": [buf], "bufferViews": views, "accessors": acc}
    return doc, b

doc, _ = gltf_doc()
put('gltf', 'skinned.gltf', json.dumps(doc))

def glb(doc, b):
    js = json.dumps(doc, separators=(',', ':')).encode()
    js += b' ' * ((4 - len(js) % 4) % 4)
    binc = b + b'\0' * ((4 - len(b) % 4) % 4)
    total = 12 + 8 + len(js) + 8 + len(binc)
    return (struct.pack('<4sII', b'glTF', 2, total) + struct.pack('<I4s', len(js), b'JSON') + js +
            struct.pack('<I4s', len(binc), b'BIN\0') + binc)
doc, b = gltf_doc(embed_uri=False)
put('gltf', 'skinned.glb', glb(doc, b))

FBX = """; FBX 7.4.0 project file
FBXHeaderExtension:  {
\tFBXHeaderVersion: 1003
\tFBXVersion: 7400
}
GlobalSettings:  {
\tVersion: 1000
\tProperties70:  {
\t\tP: "UnitScaleFactor", "double", "Number", "",1
\t}
}
Objects:  {
\tModel: 1000, "Model::Hips", "LimbNode" {
\t\tVersion: 232
\t\tProperties70:  {
\t\t\tP: "Lcl Translation", "Lcl Translation", "", "A",0,90,0
\t\t}
\t}
\tModel: 1001, "Model::Spine", "LimbNode" {
\t\tVersion: 232
\t\tProperties70:  {
\t\t\tP: "Lcl Translation", "Lcl Translation", "", "A",0,10,0
\t\t}
\t}
\tAnimationStack: 3000, "AnimStack::Take", "" {
\t}
\tAnimationLayer: 3001, "AnimLayer::Base", "" {
\t}
\tAnimationCurveNode: 3002, "AnimCurveNode::R", "" {
\t\tProperties70:  {
\t\t\tP: "d|X", "Number", "", "A",0
\t\t\tP: "d|Y", "Number", "", "A",0
\t\t\tP: "d|Z", "Number", "", "A",0
\t\t}
\t}
\tAnimationCurve: 3004, "AnimCurve::", "" {
\t\tDefault: 0
\t\tKeyVer: 4008
\t\tKeyTime: *3 {
\t\t\ta: 0,1539538600,3079077200
\t\t}
\t\tKeyValueFloat: *3 {
\t\t\ta: 0,10,20
\t\t}
\t\tKeyAttrFlags: *1 {
\t\t\ta: 24836
\t\t}
\t\tKeyAttrDataFloat: *4 {
\t\t\ta: 0,0,255790911,0
\t\t}
\t\tKeyAttrRefCount: *1 {
\t\t\ta: 3
\t\t}
\t}
}
Connections:  {
\tC: "OO",1000,0
\tC: "OO",1001,1000
\tC: "OO",3001,3000
\tC: "OO",3002,3001
\tC: "OP",3002,1001, "Lcl Rotation"
\tC: "OP",3004,3002, "d|X"
}
"""
put('fbx', 'small.fbx', FBX)
