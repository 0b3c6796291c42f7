#!/usr/bin/python3
"""Compares two `mocapsolve pipeline` output folders numerically (BENCHMARKS.md, "Memory
against the take's length", third pass): solved.bvh by the world positions of its joints
(forward kinematics of both files), repaired.c3d sample by sample (float C3D), and a
character's GLB by its nodes' world positions from the new animation's float32 keys as
stored. Prints the largest difference of each, in mm.

    bench/tools/compare_take_outputs.py BEFORE_DIR AFTER_DIR MM_PER_BVH_UNIT [CHARACTER.glb ANIMATION]

MM_PER_BVH_UNIT: the subject's unit in mm (CMU ASF, length 0.45: 56.444). Needs numpy and
scipy (Debian: python3-numpy, python3-scipy).
"""
import json
import os
import struct
import sys

import numpy as np
from scipy.spatial.transform import Rotation

def read_bvh(path):
    joints, parents, offsets, channels = [], [], [], []
    stack, lines = [], open(path).read().split('\n')
    i = 0
    while not lines[i].strip().startswith('MOTION'):
        t = lines[i].split()
        if t and t[0] in ('ROOT', 'JOINT'):
            joints.append(t[1]); parents.append(stack[-1] if stack else -1); channels.append([]); offsets.append(None)
            cur = len(joints) - 1
        elif t and t[0] == 'End':
            joints.append(None); parents.append(stack[-1]); channels.append([]); offsets.append(None)
            cur = len(joints) - 1
        elif t and t[0] == '{':
            stack.append(cur)
        elif t and t[0] == '}':
            stack.pop()
        elif t and t[0] == 'OFFSET':
            offsets[cur] = np.array([float(x) for x in t[1:4]])
        elif t and t[0] == 'CHANNELS':
            channels[cur] = t[2:]
        i += 1
    frames = int(lines[i + 1].split()[1])
    data = np.array([[float(x) for x in l.split()] for l in lines[i + 3:i + 3 + frames]])
    return joints, parents, offsets, channels, data

def positions(path):
    joints, parents, offsets, channels, data = read_bvh(path)
    F, J = data.shape[0], len(joints)
    out = np.zeros((F, J, 3)); R = [None] * J
    col = 0; cols = []
    for c in channels:
        cols.append(col); col += len(c)
    for j in range(J):
        c = channels[j]; k = cols[j]
        t = np.tile(offsets[j], (F, 1))
        rot_names = [n for n in c if n.endswith('rotation')]
        for n_i, n in enumerate(c):
            if n.endswith('position'):
                t[:, 'XYZ'.index(n[0])] = data[:, k + n_i]
        if rot_names:
            order = ''.join(n[0] for n in rot_names)
            angles = np.stack([data[:, k + c.index(n)] for n in rot_names], axis=1)
            local = Rotation.from_euler(order.upper(), angles, degrees=True)
        else:
            local = Rotation.identity(F)
        p = parents[j]
        if p < 0:
            out[:, j] = t; R[j] = local
        else:
            out[:, j] = out[:, p] + R[p].apply(t); R[j] = R[p] * local
    return out

def read_c3d_float(path):
    b = open(path, 'rb').read()
    points = struct.unpack_from('<H', b, 2)[0]
    scale = struct.unpack_from('<f', b, 12)[0]
    start = struct.unpack_from('<H', b, 16)[0]
    assert scale < 0, 'integer C3D'
    off = (start - 1) * 512
    n = (len(b) - off) // (points * 16)
    a = np.frombuffer(b, dtype='<f4', count=n * points * 4, offset=off).reshape(n, points, 4)
    return a


def glb_accessor(doc, data, bin_offset, index):
    a = doc['accessors'][index]
    view = doc['bufferViews'][a['bufferView']]
    width = {'SCALAR': 1, 'VEC3': 3, 'VEC4': 4}[a['type']]
    assert a['componentType'] == 5126, 'not float keys'
    offset = bin_offset + view.get('byteOffset', 0) + a.get('byteOffset', 0)
    return np.frombuffer(data, dtype='<f4', count=a['count'] * width, offset=offset).reshape(a['count'], width)

def glb_positions(path, name):
    data = open(path, 'rb').read()
    json_length = struct.unpack_from('<I', data, 12)[0]
    doc = json.loads(data[20:20 + json_length])
    bin_offset = 20 + json_length + 8
    animation = [a for a in doc['animations'] if a.get('name') == name][0]
    nodes = doc['nodes']
    keys = {'translation': {}, 'rotation': {}}
    frames = 1
    for channel in animation['channels']:
        path_name = channel['target']['path']
        if path_name not in keys:
            continue
        out = glb_accessor(doc, data, bin_offset, animation['samplers'][channel['sampler']]['output'])
        keys[path_name][channel['target']['node']] = out.astype(np.float64)
        frames = max(frames, out.shape[0])
    parent = [-1] * len(nodes)
    for i, node in enumerate(nodes):
        for child in node.get('children', []):
            parent[child] = i
    order, seen = [], set()
    def visit(i):
        if i in seen:
            return
        if parent[i] >= 0:
            visit(parent[i])
        seen.add(i)
        order.append(i)
    for i in range(len(nodes)):
        visit(i)
    positions = np.zeros((frames, len(nodes), 3))
    world = [None] * len(nodes)
    for i in order:
        node = nodes[i]
        t = keys['translation'].get(i, np.array([node.get('translation', [0.0, 0.0, 0.0])]))
        r = keys['rotation'].get(i, np.array([node.get('rotation', [0.0, 0.0, 0.0, 1.0])]))
        t = np.tile(t, (frames, 1)) if t.shape[0] == 1 else t
        r = np.tile(r, (frames, 1)) if r.shape[0] == 1 else r
        scale = np.array(node.get('scale', [1.0, 1.0, 1.0]))  # Uniform scales (as the writer's rigs).
        local = Rotation.from_quat(r)
        if parent[i] < 0:
            positions[:, i] = t
            world[i] = (local, scale)
        else:
            parent_rotation, parent_scale = world[parent[i]]
            positions[:, i] = positions[:, parent[i]] + parent_rotation.apply(t * parent_scale)
            world[i] = (parent_rotation * local, parent_scale * scale)
    return positions

def main():
    if len(sys.argv) not in (4, 6):
        sys.exit(__doc__)
    before, after, mm_per_unit = sys.argv[1], sys.argv[2], float(sys.argv[3])
    a, b = positions(os.path.join(before, 'solved.bvh')), positions(os.path.join(after, 'solved.bvh'))
    print('solved.bvh: %d frames, joints within %.4f mm' % (a.shape[0], np.abs(a - b).max() * mm_per_unit))
    ca, cb = read_c3d_float(os.path.join(before, 'repaired.c3d')), read_c3d_float(os.path.join(after, 'repaired.c3d'))
    va, vb = ca[:, :, 3] >= 0, cb[:, :, 3] >= 0
    d = np.abs(ca[:, :, :3].astype(np.float64) - cb[:, :, :3])[va & vb].max()
    print('repaired.c3d: %d frames, same missing samples: %s, samples within %.4f (file units; mm for CMU)' %
          (ca.shape[0], bool((va == vb).all()), d))
    if len(sys.argv) == 6:
        glb, name = sys.argv[4], sys.argv[5]
        ga, gb = glb_positions(os.path.join(before, glb), name), glb_positions(os.path.join(after, glb), name)
        print('%s: %d frames, joints within %.4f mm' % (glb, ga.shape[0], np.abs(ga - gb).max() * 1000.0))

if __name__ == '__main__':
    main()
