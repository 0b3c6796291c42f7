#!/usr/bin/env python3
"""Writes docs/commands/: one page per command, made from `mocapsolve <command> --help`
(whose flags, defaults, units and texts come from the option declarations, settings/), and
an index; and docs/schemas/options/<command>.schema.json: the JSON Schema of the "options"
block of the command's --report (every flag but --report, with its type and default). With
--check, compares instead and exits 1 naming the files that differ, so neither can drift
from the code (ctest docs.commands).

usage: make_command_docs.py --cli=build/bin/mocapsolve [--out=docs/commands] [--check]
"""
import argparse
import json
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


FLAG_ROW = r"^  --(\S+) \((\w+)\) default: (.*)\n      (.*)$"
JSON_TYPES = {"bool": "boolean", "int32": "integer", "int64": "integer", "uint32": "integer", "uint64": "integer",
              "double": "number", "string": "string"}


def options_schema(cli, name):
    """The schema of the command's report's "options": its flags (not --report), typed."""
    flag_text = run(cli, name, "--help").partition("\nflags:\n")[2]
    properties = {}
    for flag, kind, default, meaning in re.findall(FLAG_ROW, flag_text, re.M):
        if flag == "report":
            continue
        value = json.loads(default) if kind == "string" else {"true": True, "false": False}.get(default)
        if value is None:
            value = float(default) if kind == "double" else int(default)
        properties[flag] = {"type": JSON_TYPES[kind], "default": value, "description": meaning}
    schema = {"$schema": "http://json-schema.org/draft-07/schema#",
              "$id": "options/%s.schema.json" % name,
              "title": "mocapsolve %s --report: options" % name,
              "description": "The options in force, as the report records them: every flag of the command but "
                             "--report. Made by scripts/make_command_docs.py from `mocapsolve %s --help` (the "
                             "option declarations); do not edit." % name,
              "type": "object", "properties": properties, "required": sorted(properties),
              "additionalProperties": False}
    return json.dumps(schema, indent=2) + "\n"


def page(cli, name, summary):
    text = run(cli, name, "--help")
    usage, _, flag_text = text.partition("\nflags:\n")
    usage = usage[len("usage: "):] if usage.startswith("usage: ") else usage
    synopsis, _, explanation = usage.partition("\n\n")
    lines = ["# mocapsolve %s" % name, "", summary[0].upper() + summary[1:] + ".", "",
             "```", synopsis.strip(), "```", ""]
    if explanation.strip():
        lines += [explanation.strip(), ""]
    rows = re.findall(FLAG_ROW, flag_text, re.M)
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
    docs = os.path.join(os.path.dirname(__file__), "..", "docs")
    parser.add_argument("--out", default=os.path.join(docs, "commands"))
    parser.add_argument("--schemas", default=os.path.join(docs, "schemas", "options"))
    parser.add_argument("--check", action="store_true")
    args = parser.parse_args()
    listed = commands(args.cli)
    if len(listed) < 10:
        sys.exit("make_command_docs: %s --help listed %d commands" % (args.cli, len(listed)))
    pages = {"README.md": "\n".join(
        ["# Commands", "", "One page per command, made from its `--help` (the option declarations); "
         "`mocapsolve <command> --help` prints the same.", "", "| command | what it does |", "|---|---|"] +
        ["| [%s](%s.md) | %s |" % (name, name, summary) for name, summary in listed] + [""])}
    pages = {os.path.join(args.out, file_name): text for file_name, text in pages.items()}
    for name, summary in listed:
        pages[os.path.join(args.out, name + ".md")] = page(args.cli, name, summary)
        pages[os.path.join(args.schemas, name + ".schema.json")] = options_schema(args.cli, name)
    os.makedirs(args.schemas, exist_ok=True)
    stale = []
    for path, text in sorted(pages.items()):
        file_name = os.path.relpath(path, docs)
        old = open(path).read() if os.path.exists(path) else None
        if old == text:
            continue
        if args.check:
            stale.append(file_name)
        else:
            with open(path, "w") as f:
                f.write(text)
    if args.check and stale:
        sys.exit("docs/commands or docs/schemas/options is stale (%s); run scripts/make_command_docs.py "
                 "--cli=build/bin/mocapsolve"
                 % ", ".join(stale))


if __name__ == "__main__":
    main()
