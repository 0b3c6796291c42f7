#!/usr/bin/env python3
"""Writes a copy of a C3D file whose point labels carry no meaning: a take "from a new
protocol" for `pipeline --subject=auto` (BENCHMARKS.md, issue 32).

    rename_c3d_labels.py IN.c3d OUT.c3d [--prefix=M] [--seed=1]

Every label of POINT:LABELS (and LABELS2, LABELS3, ... for more than 255 points) becomes
PREFIX<k>, k a shuffled index (seeded), padded to the parameter's own width, so nothing
else in the file moves: the data, the other parameters and every byte offset stay as they
were. POINT:DESCRIPTIONS are blanked too (they often repeat the names). Prints the map
(new <- old) on stdout. Intel, DEC and SGI files alike (only the parameter section's
integers are read, in the file's byte order).
"""
import argparse
import random
import struct
import sys


def parameters(data):
    """Yields (group_name, name, offset_of_dims_byte, record) for each parameter."""
    start = (data[0] - 1) * 512
    processor = data[start + 3]
    endian = ">" if processor == 86 else "<"
    groups = {}
    pos = start + 4
    records = []
    while True:
        length = data[pos]
        if length == 0:
            break
        gid = struct.unpack("b", data[pos + 1:pos + 2])[0]
        name = data[pos + 2:pos + 2 + abs(length)].decode("ascii", "replace").upper()
        next_pos = pos + 2 + abs(length)
        offset = struct.unpack(endian + "h", data[next_pos:next_pos + 2])[0]
        if gid < 0:
            groups[-gid] = name
        else:
            body = next_pos + 2
            elem = struct.unpack("b", data[body:body + 1])[0]
            ndims = data[body + 1]
            dims = [data[body + 2 + i] for i in range(ndims)]
            values = body + 2 + ndims
            records.append((gid, name, elem, dims, values))
        if offset == 0:
            break
        pos = next_pos + offset
    for gid, name, elem, dims, values in records:
        yield groups.get(gid, ""), name, elem, dims, values


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("input")
    parser.add_argument("output")
    parser.add_argument("--prefix", default="M")
    parser.add_argument("--seed", type=int, default=1)
    args = parser.parse_args()
    data = bytearray(open(args.input, "rb").read())
    label_params, description_params = [], []
    for group, name, elem, dims, values in parameters(data):
        if group != "POINT" or elem != -1 or len(dims) != 2:
            continue
        if name == "LABELS" or (name.startswith("LABELS") and name[6:].isdigit()):
            label_params.append((name, dims, values))
        if name == "DESCRIPTIONS" or (name.startswith("DESCRIPTIONS") and name[12:].isdigit()):
            description_params.append((dims, values))
    if not label_params:
        sys.exit(f"{args.input}: no POINT:LABELS parameter")
    label_params.sort(key=lambda p: (len(p[0]), p[0]))  # LABELS, LABELS2, ..., LABELS10.
    slots = [(values + k * dims[0], dims[0]) for _, dims, values in label_params for k in range(dims[1])]
    order = list(range(len(slots)))
    random.Random(args.seed).shuffle(order)
    for k, (offset, width) in enumerate(slots):
        old = data[offset:offset + width].decode("ascii", "replace").strip()
        new = f"{args.prefix}{order[k]}"
        if len(new) > width:
            sys.exit(f"{args.input}: label width {width} too small for '{new}'")
        data[offset:offset + width] = new.ljust(width).encode("ascii")
        print(f"{new} <- {old}")
    for dims, values in description_params:
        data[values:values + dims[0] * dims[1]] = b" " * (dims[0] * dims[1])
    with open(args.output, "wb") as out:
        out.write(data)


if __name__ == "__main__":
    main()
