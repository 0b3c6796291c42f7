#!/usr/bin/env python3
"""Writes a SPARSE gait-lab take from a full-body one (issue 32): only the markers of a
lower-body or Helen Hayes / Davis protocol, under that protocol's labels.

    sparse_protocol.py IN.trc OUT.trc --protocol=pig_lower|davis_bts

IN is a TRC of the 53-marker Vicon set (squat, nick_freeform_001) or of the AIS set
(JA1Gait35), as `mocapsolve convert TAKE.c3d TAKE.trc` writes it; OUT keeps the protocol's
markers only, renamed (a label "A+B" is the mean of two of IN's markers: a sacrum between
the two PSIS). Turn OUT into a C3D with `mocapsolve convert OUT.trc OUT.c3d`. Nothing of the
shared data goes into the repository; bench/sparse_protocols.sh drives it.
"""
import argparse
import sys

# Plug-in Gait lower body (16 markers), per source set: protocol label -> source label(s).
PIG_LOWER = {
    "vicon53": dict(LASI="LFWT", RASI="RFWT", LPSI="LBWT", RPSI="RBWT", LTHI="LHIP", RTHI="RHIP",
                    LKNE="LKNE", RKNE="RKNE", LTIB="LSHN", RTIB="RSHN", LANK="LANK", RANK="RANK",
                    LHEE="LHEL", RHEE="RHEL", LTOE="LTOE", RTOE="RTOE"),
    "ais": dict(LASI="LASI", RASI="RASI", LPSI="P1", RPSI="P2", LTHI="LTHLP", RTHI="RTHLP",
                LKNE="LLEPI", RKNE="RLEPI", LTIB="LTILAT", RTIB="RTILAT", LANK="LLMAL", RANK="RLMAL",
                LHEE="LHEEL", RHEE="RHEEL", LTOE="LTOE", RTOE="RTOE"),
}
# BTS DAVIS (Helen Hayes / Davis, 18 markers): C7, shoulders, sacrum, ASIS, thigh and tibia
# wands, lateral knee, malleolus, heel, 5th metatarsal head.
DAVIS_BTS = {
    "vicon53": {"c7": "C7", "r should": "RFSH", "l should": "LFSH", "sacrum": "LBWT+RBWT",
                "r asis": "RFWT", "l asis": "LFWT", "r bway": "RHIP", "l bway": "LHIP",
                "r knee 1": "RKNE", "l knee 1": "LKNE", "r tibia wand": "RSHN", "l tibia wand": "LSHN",
                "r mall": "RANK", "l mall": "LANK", "r heel": "RHEL", "l heel": "LHEL",
                "r met": "RMT5", "l met": "LMT5"},
    "ais": {"c7": "C7", "r should": "RSH", "l should": "LSH", "sacrum": "SACR",
            "r asis": "RASI", "l asis": "LASI", "r bway": "RTHLP", "l bway": "LTHLP",
            "r knee 1": "RLEPI", "l knee 1": "LLEPI", "r tibia wand": "RTILAT", "l tibia wand": "LTILAT",
            "r mall": "RLMAL", "l mall": "LLMAL", "r heel": "RHEEL", "l heel": "LHEEL",
            "r met": "RP5MT", "l met": "LP5MT"},
}
PROTOCOLS = {"pig_lower": PIG_LOWER, "davis_bts": DAVIS_BTS}


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("input")
    parser.add_argument("output")
    parser.add_argument("--protocol", choices=sorted(PROTOCOLS), required=True)
    args = parser.parse_args()
    lines = open(args.input).read().split("\n")
    header = lines[:3]
    names = [n.split(":")[-1] for n in lines[3].split("\t")[2::3]]
    source_set = "ais" if "LLEPI" in names else "vicon53"
    table = PROTOCOLS[args.protocol][source_set]
    column = {n: 2 + 3 * i for i, n in enumerate(names)}
    for sources in table.values():
        for s in sources.split("+"):
            if s not in column:
                sys.exit("%s: no marker %s (protocol %s)" % (args.input, s, args.protocol))
    out = []
    for line in lines[5:]:
        if not line.strip():
            continue
        f = line.split("\t")
        row = f[:2]
        for sources in table.values():
            parts = [f[column[s]:column[s] + 3] for s in sources.split("+")]
            if any(len(p) < 3 or "" in p for p in parts):
                row += ["", "", ""]
                continue
            row += ["%.6g" % (sum(float(p[k]) for p in parts) / len(parts)) for k in range(3)]
        out.append("\t".join(row))
    meta = header[2].split("\t")
    meta[3] = str(len(table))
    labels = ["Frame#", "Time"] + sum([[n, "", ""] for n in table], [])
    axes = ["", ""] + sum([["X%d" % (i + 1), "Y%d" % (i + 1), "Z%d" % (i + 1)] for i in range(len(table))], [])
    with open(args.output, "w") as fh:
        fh.write("\n".join([header[0], header[1], "\t".join(meta), "\t".join(labels), "\t".join(axes), ""] + out) + "\n")
    print("%s: %d of %d markers (%s from the %s set)" % (args.output, len(table), len(names), args.protocol, source_set))


if __name__ == "__main__":
    main()
