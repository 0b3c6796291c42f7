#!/usr/bin/env python3
"""Lists the longest functions of the library (every .cc below kinematics/ io/ viewer/
solvers/ signal/ problems/ settings/ pipeline/ batch/ tasks/, or the folders given), longest
first; and the command files apps/*_command.cc, which hold flag reading, one task call and
writing only.

A function is a definition that opens at the start of a line (clang-format's layout here)
and ends at the first line that is a lone '}' at the same indentation. With --max=N, exits
1 when any is longer than N lines (the library's goal: none over 150); with
--max_command_file=N, also when a command file is longer than N lines (the goal: 150).

usage: long_functions.py [--top=20] [--max=N] [--max_command_file=N] [FOLDER...]
"""
import argparse
import os
import re
import sys

LIBRARY = ["kinematics", "io", "viewer", "solvers", "signal", "problems", "settings", "pipeline", "batch", "tasks"]
NOT_FUNCTIONS = re.compile(r"^(namespace|struct|class|enum|union|extern|#|//|template\s*<[^>]*>\s*(struct|class))")


def functions(path):
    lines = open(path, encoding="utf-8", errors="replace").read().split("\n")
    found, start, signature = [], None, ""
    for number, line in enumerate(lines, 1):
        if start is None:
            if (signature or (line and not line[0].isspace())) and not NOT_FUNCTIONS.match(line.strip()):
                signature = signature + " " + line if signature else line
                if line.rstrip().endswith("{") and "(" in signature:
                    start = number
                    name = re.search(r"([\w:~<>]+)\s*\(", signature)
                    found.append([name.group(1) if name else signature[:40], number, None])
                    signature = ""
                elif line.rstrip().endswith((";", "}")):
                    signature = ""
            else:
                signature = ""
        elif line == "}":
            found[-1][2] = number
            start = None
    return [(name, first, last) for name, first, last in found if last is not None]


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--top", type=int, default=20)
    parser.add_argument("--max", type=int, default=0)
    parser.add_argument("--max_command_file", type=int, default=0)
    parser.add_argument("folders", nargs="*")
    args = parser.parse_args()
    root = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
    rows = []
    for folder in args.folders or LIBRARY:
        for directory, _, files in os.walk(os.path.join(root, folder)):
            for file_name in files:
                if not file_name.endswith(".cc"):
                    continue
                path = os.path.join(directory, file_name)
                for name, first, last in functions(path):
                    rows.append((last - first + 1, os.path.relpath(path, root), first, name))
    rows.sort(reverse=True)
    for length, path, first, name in rows[:args.top]:
        print("%5d  %s:%d  %s" % (length, path, first, name))
    over = [row for row in rows if args.max and row[0] > args.max]
    print("%d functions, %d over 150 lines" % (len(rows), sum(1 for row in rows if row[0] > 150)))
    apps = os.path.join(root, "apps")
    commands = sorted((sum(1 for _ in open(os.path.join(apps, f), encoding="utf-8")), "apps/" + f)
                      for f in os.listdir(apps) if f.endswith("_command.cc"))
    long_commands = [c for c in commands if args.max_command_file and c[0] > args.max_command_file]
    print("%d command files, the longest %s (%d lines)" % (len(commands), commands[-1][1], commands[-1][0]))
    for lines, path in long_commands:
        print("%5d  %s" % (lines, path))
    if over:
        sys.exit("%d functions are longer than %d lines" % (len(over), args.max))
    if long_commands:
        sys.exit("%d command files are longer than %d lines" % (len(long_commands), args.max_command_file))


if __name__ == "__main__":
    main()
