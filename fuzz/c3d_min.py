# A minimal C3D writer (Intel, float storage, points only) for the fuzz seeds and the
# hand-made bad files: enough parameters for io/c3d_reader.cc, nothing else.
import struct

def _param(group_id, name, ptype, dims, data):
    body = struct.pack('<bB', ptype, len(dims)) + bytes(dims) + data + b'\0'
    name_b = name.encode()
    return struct.pack('<bb', len(name_b), group_id) + name_b + struct.pack('<h', 2 + len(body)) + body

def _group(group_id, name):
    name_b = name.encode()
    return struct.pack('<bb', len(name_b), -group_id) + name_b + struct.pack('<h', 3) + b'\0'

def _floats(values):
    return struct.pack('<%df' % len(values), *values)

def c3d_bytes(labels, frames, rate=120.0, point_rate=None, units='mm', header_rate=None, trial_end=None):
    """frames: list of frames, each a list of (x, y, z) or None (missing) per label.
    trial_end: if given, TRIAL:ACTUAL_START_FIELD 1 and ACTUAL_END_FIELD trial_end (32 bits)."""
    n = len(labels)
    width = max([4] + [len(l) for l in labels])
    label_data = b''.join(l.encode().ljust(width) for l in labels)
    params = _group(1, 'POINT')
    params += _param(1, 'USED', 2, [], struct.pack('<h', n))
    params += _param(1, 'SCALE', 4, [], _floats([-0.1]))
    params += _param(1, 'RATE', 4, [], _floats([rate if point_rate is None else point_rate]))
    params += _param(1, 'DATA_START', 2, [], struct.pack('<h', 3))
    params += _param(1, 'LABELS', -1, [width, n], label_data)
    params += _param(1, 'UNITS', -1, [len(units)], units.encode())
    if trial_end is not None:
        params += _group(3, 'TRIAL')
        params += _param(3, 'ACTUAL_START_FIELD', 2, [2], struct.pack('<HH', 1, 0))
        params += _param(3, 'ACTUAL_END_FIELD', 2, [2], struct.pack('<HH', trial_end & 0xffff, trial_end >> 16))
    params += b'\0\0'  # End: an entry with an empty name.
    param_block = struct.pack('<BBBB', 1, 0x50, 1, 84) + params
    assert len(param_block) <= 512, 'parameters exceed one block'
    param_block = param_block.ljust(512, b'\0')
    header = bytearray(512)
    struct.pack_into('<BB', header, 0, 2, 0x50)
    struct.pack_into('<HHHHH', header, 2, n, 0, 1, max(len(frames), 1), 0)
    struct.pack_into('<f', header, 12, -0.1)
    struct.pack_into('<H', header, 16, 3)
    struct.pack_into('<H', header, 18, 0)
    struct.pack_into('<f', header, 20, rate if header_rate is None else header_rate)
    data = b''
    for frame in frames:
        for p in frame:
            data += _floats(list(p) + [0.0]) if p is not None else _floats([0, 0, 0, -1.0])
    return bytes(header) + param_block + data
