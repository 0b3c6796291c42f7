# Regenerates the hand-made bad glTF/GLB files of tests/data/bad (python3 make_bad_gltf.py).
# Each carries its expected error in asset.extras["expect-error"] (tests/io/gltf_reader_test.cc
# checks that reading it fails with one line naming the file and containing that text).
import base64, json, os, struct
B=os.path.dirname(os.path.abspath(__file__))+'/'
def buf(floats):
    return struct.pack('<%df'%len(floats), *floats)
ident=[1,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,0,1]
def base(expect, bin_bytes, accessors, views, skins, meshes=None, nodes=None):
    doc={"asset":{"version":"2.0","generator":"mocapsolve tests (hand-made bad file)","extras":{"expect-error":expect}},
         "scene":0,"scenes":[{"nodes":[0]}],
         "nodes": nodes or [{"name":"root","children":[1]},{"name":"child","translation":[0,1,0]}],
         "buffers":[{"byteLength":len(bin_bytes),"uri":"data:application/octet-stream;base64,"+base64.b64encode(bin_bytes).decode()}],
         "bufferViews":views,"accessors":accessors,"skins":skins}
    if meshes: doc["meshes"]=meshes
    return doc
# 1. accessor reaching past its buffer view.
b=buf(ident*2)
d=base("inverseBindMatrices: accessor 0: needs 192 bytes of bufferView 0, which has 128",
       b,[{"bufferView":0,"componentType":5126,"count":3,"type":"MAT4"}],
       [{"buffer":0,"byteOffset":0,"byteLength":128}],[{"joints":[0,1],"inverseBindMatrices":0}])
open(B+'bad_gltf_accessor_range.gltf','w').write(json.dumps(d,indent=1)+"\n")
# 2. skin joint index out of range.
d=base("skin 0: joint 1: node 7 out of range (2 nodes)",b,
       [{"bufferView":0,"componentType":5126,"count":2,"type":"MAT4"}],
       [{"buffer":0,"byteOffset":0,"byteLength":128}],[{"joints":[0,7],"inverseBindMatrices":0}])
open(B+'bad_gltf_skin_joint.gltf','w').write(json.dumps(d,indent=1)+"\n")
# 3. too few inverse bind matrices.
d=base("skin 0: inverseBindMatrices accessor 0 has 1 matrices for 2 joints",b,
       [{"bufferView":0,"componentType":5126,"count":1,"type":"MAT4"}],
       [{"buffer":0,"byteOffset":0,"byteLength":128}],[{"joints":[0,1],"inverseBindMatrices":0}])
open(B+'bad_gltf_ibm_count.gltf','w').write(json.dumps(d,indent=1)+"\n")
# 4. vertex weighted to a joint the skin does not have (JOINTS_0 = 5 of 2).
pos=struct.pack('<9f',0,0,0,1,0,0,0,1,0)
jnt=bytes([0,0,0,0, 5,0,0,0, 1,0,0,0])
wts=struct.pack('<12f',1,0,0,0, 1,0,0,0, 1,0,0,0)
b2=b+pos+jnt+wts
views=[{"buffer":0,"byteOffset":0,"byteLength":128},{"buffer":0,"byteOffset":128,"byteLength":36},
       {"buffer":0,"byteOffset":164,"byteLength":12},{"buffer":0,"byteOffset":176,"byteLength":48}]
acc=[{"bufferView":0,"componentType":5126,"count":2,"type":"MAT4"},
     {"bufferView":1,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[1,1,0]},
     {"bufferView":2,"componentType":5121,"count":3,"type":"VEC4"},
     {"bufferView":3,"componentType":5126,"count":3,"type":"VEC4"}]
nodes=[{"name":"root","children":[1]},{"name":"child","translation":[0,1,0]},{"name":"body","mesh":0,"skin":0}]
d=base("JOINTS_0: vertex 1: joint 5 out of range (skin 0 has 2 joints)",b2,acc,views,[{"joints":[0,1],"inverseBindMatrices":0}],
       meshes=[{"primitives":[{"attributes":{"POSITION":1,"JOINTS_0":2,"WEIGHTS_0":3}}]}],nodes=nodes)
d["scenes"][0]["nodes"]=[0,2]
open(B+'bad_gltf_weight_joint.gltf','w').write(json.dumps(d,indent=1)+"\n")
# 5. truncated GLB: a valid file (the previous one, with a BIN chunk) cut in its BIN chunk.
d=base("GLB",b2,acc,views,[{"joints":[0,1],"inverseBindMatrices":0}],
       meshes=[{"primitives":[{"attributes":{"POSITION":1,"JOINTS_0":2,"WEIGHTS_0":3}}]}],nodes=nodes)
d["asset"]["extras"]["expect-error"]="GLB: header declares 1228 bytes, the file has 1128 (truncated)"
del d["buffers"][0]["uri"]
# the joint index fixed so that only the truncation is wrong
b3=b+pos+bytes([0,0,0,0, 1,0,0,0, 1,0,0,0])+wts
js=json.dumps(d,separators=(',',':')).encode()
js+=b' '*((4-len(js)%4)%4)
binc=b3+b'\0'*((4-len(b3)%4)%4)
total=12+8+len(js)+8+len(binc)
glb=struct.pack('<4sII',b'glTF',2,total)+struct.pack('<I4s',len(js),b'JSON')+js+struct.pack('<I4s',len(binc),b'BIN\0')+binc
open(B+'bad_gltf_truncated.glb','wb').write(glb[:len(glb)-100])
# 6. GLB whose header states version 7: tinygltf read it as glTF 2 (`info` and `convert`
# exited 0). The same valid file, whole, with only the version changed.
d["asset"]["extras"]["expect-error"]="GLB: header version 7, expected 2 (glTF 2.0)"
js=json.dumps(d,separators=(',',':')).encode()
js+=b' '*((4-len(js)%4)%4)
total=12+8+len(js)+8+len(binc)
glb=struct.pack('<4sII',b'glTF',7,total)+struct.pack('<I4s',len(js),b'JSON')+js+struct.pack('<I4s',len(binc),b'BIN\0')+binc
open(B+'bad_gltf_version.glb','wb').write(glb)
# 7. a node that is its own child, and 8. two nodes each the other's child: hierarchies
# with a cycle, refused where the node graph is built (as ASF's :hierarchy is).
skin=[{"joints":[0,1],"inverseBindMatrices":0}]
ibm=[{"bufferView":0,"componentType":5126,"count":2,"type":"MAT4"}]
ibm_view=[{"buffer":0,"byteOffset":0,"byteLength":128}]
d=base("node 1 'child': is its own child",b,ibm,ibm_view,skin,
       nodes=[{"name":"root","children":[1]},{"name":"child","children":[1]}])
open(B+'bad_gltf_self_child.gltf','w').write(json.dumps(d,indent=1)+"\n")
d=base("is in a cycle of children",b,ibm,ibm_view,skin,
       nodes=[{"name":"root"},{"name":"a","children":[2]},{"name":"b","children":[1]}])
open(B+'bad_gltf_node_cycle.gltf','w').write(json.dumps(d,indent=1)+"\n")
