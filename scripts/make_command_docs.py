#!/usr/bin/env python3
"""Writes docs/commands/: one page per command, made from `mocapsolve <command> --help`
(whose flags, defaults, units and texts come from the option declarations, settings/), and
an index. With --check, compares instead and exits 1 naming the pages that differ, so the
pages cannot drift from the code (ctest docs.commands).

usage: make_command_docs.py --cli=build/bin/mocapsolve [--out=docs/commands] [--check]
"""
import argparse
import os
import re
import subprocess
import sys


def run(cli, *args):
    return subprocess.run([cli, *args], capture_output=True, text=True, check=False).stdout


def commands(cli):
    listed, inside = [], False
    for line in run(cli, "--help").splitlines():
        if line == "commands:":
            inside = True
        elif inside and not line.strip():
            break
        elif inside:
            name, summary = line.strip().split(None, 1)
            listed.append((name, summary))
    return listed


def page(cli, name, summary):
    text = run(cli, name, "--help")
    usage, _, flag_text = text.partition("\nflags:\n")
    usage = usage[len("usage: "):] if usage.startswith("usage: ") else usage
    synopsis, _, explanation = usage.partition("\n\n")
    lines = ["# mocapsolve %s" % name, "", summary[0].upper() + summary[1:] + ".", "",
             "```", synopsis.strip(), "```", ""]
    if explanation.strip():
        lines += [explanation.strip(), ""]
    rows = re.findall(r"^  --(\S+) \((\w+)\) default: (.*)\n      (.*)$", flag_text, re.M)
    if rows:
        lines += ["| flag | type | default | unit | meaning |", "|---|---|---|---|---|"]
        for flag, kind, default, meaning in rows:
            unit = ""
            match = re.search(r" \[([^\]]+)\]$", meaning)
            if match:
                unit, meaning = match.group(1), meaning[:match.start()]
            cell = lambda s: s.replace("|", "\\|")
            lines.append("| `--%s` | %s | `%s` | %s | %s |" % (flag, kind, default, cell(unit), cell(meaning)))
        lines.append("")
    lines += ["Made by scripts/make_command_docs.py from `mocapsolve %s --help`; do not edit." % name, ""]
    return "\n".join(lines)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--cli", required=True)
    parser.add_argument("--out", default=os.path.join(os.path.dirname(__file__), "..", "docs", "commands"))
    parser.add_argument("--check", action="store_true")
    args = parser.parse_args()
    listed = commands(args.cli)
    if len(listed) < 10:
        sys.exit("make_command_docs: %s --help listed %d commands" % (args.cli, len(listed)))
    pages = {"README.md": "\n".join(
        ["# Commands", "", "One page per command, made from its `--help` (the option declarations); "
         "`mocapsolve <command> --help` prints the same.", "", "| command | what it does |", "|---|---|"] +
        ["| [%s](%s.md) | %s |" % (name, name, summary) for name, summary in listed] + [""])}
    for name, summary in listed:
        pages[name + ".md"] = page(args.cli, name, summary)
    stale = []
    for file_name, text in sorted(pages.items()):
        path = os.path.join(args.out, file_name)
        old = open(path).read() if os.path.exists(path) else None
        if old == text:
            continue
        if args.check:
            stale.append(file_name)
        else:
            with open(path, "w") as f:
                f.write(text)
    if args.check and stale:
        sys.exit("docs/commands is stale (%s); run scripts/make_command_docs.py --cli=build/bin/mocapsolve"
                 % ", ".join(stale))


if __name__ == "__main__":
    main()
