#!/usr/bin/python3
"""Checks the links between the project's Markdown documents.

For every link target that is not a URL (http:, https:, mailto:): the file must exist
(relative to the linking document), and an anchor (#...) must be the GitHub anchor of a
heading in the target document. GitHub anchors: the heading's text without Markdown
(code spans, links, emphasis), lower-case, every character but letters, digits, spaces,
'-' and '_' dropped, spaces turned into '-'; a repeated anchor gets -1, -2, ...
Headings and links inside fenced code blocks are ignored.

Usage: scripts/check_doc_links.py [FILE.md ...]   (default: BENCHMARKS.md README.md docs/*.md)
       --anchors FILE.md   prints the anchors of FILE.md's headings
Exit status 1 when a link is broken, each printed as FILE:LINE: TARGET: why.
"""
import glob
import os
import re
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
LINK = re.compile(r"!?\[(?:[^\[\]]|\[[^\]]*\])*\]\(\s*<?([^)\s>]+)>?(?:\s+\"[^\"]*\")?\s*\)")


def strip_code(lines):
    """Yields (line number, line) outside fenced code blocks."""
    fence = None
    for number, line in enumerate(lines, 1):
        match = re.match(r"^\s*(```+|~~~+)", line)
        if match:
            marker = match.group(1)
            if fence is None:
                fence = marker[0] * 3
            elif marker.startswith(fence):
                fence = None
            continue
        if fence is None:
            yield number, line


def slug(text):
    text = re.sub(r"!?\[([^\]]*)\]\([^)]*\)", r"\1", text)  # links and images: their text
    text = re.sub(r"<[^>]+>", "", text)  # inline HTML
    text = text.replace("`", "").replace("*", "")
    text = re.sub(r"(?<!\w)_+|_+(?!\w)", "", text)  # emphasis underscores, not snake_case
    text = text.strip().lower()
    return "".join(c for c in text if c.isalnum() or c in " -_").replace(" ", "-")


def anchors(path):
    seen = {}
    result = []
    with open(path, encoding="utf-8") as f:
        lines = f.read().split("\n")
    for _, line in strip_code(lines):
        match = re.match(r"^#{1,6}\s+(.*?)\s*#*\s*$", line)
        if not match:
            continue
        base = slug(match.group(1))
        count = seen.get(base, 0)
        seen[base] = count + 1
        result.append(base if count == 0 else "%s-%d" % (base, count))
    return result


def check(path, cache):
    problems = []
    links = 0
    with open(path, encoding="utf-8") as f:
        lines = f.read().split("\n")
    for number, line in strip_code(lines):
        line = re.sub(r"`[^`]*`", "", line)  # links inside code spans are not links
        for match in LINK.finditer(line):
            target = match.group(1)
            if re.match(r"^[a-z][a-z0-9+.-]*:", target, re.I):
                continue
            links += 1
            file_part, _, anchor = target.partition("#")
            target_path = os.path.normpath(os.path.join(os.path.dirname(path), file_part)) if file_part else path
            where = "%s:%d: %s" % (os.path.relpath(path, ROOT), number, target)
            if not os.path.exists(target_path):
                problems.append("%s: no such file" % where)
                continue
            if anchor:
                if not target_path.endswith(".md"):
                    problems.append("%s: anchor into a file that is not Markdown" % where)
                    continue
                if target_path not in cache:
                    cache[target_path] = set(anchors(target_path))
                if anchor not in cache[target_path]:
                    problems.append("%s: no heading with this anchor" % where)
    return links, problems


def main(argv):
    if len(argv) == 3 and argv[1] == "--anchors":
        for a in anchors(argv[2]):
            print("#" + a)
        return 0
    files = argv[1:] or [os.path.join(ROOT, "BENCHMARKS.md"), os.path.join(ROOT, "README.md")] + sorted(
        glob.glob(os.path.join(ROOT, "docs", "*.md")))
    cache = {}
    total = 0
    problems = []
    for path in files:
        links, found = check(os.path.abspath(path), cache)
        total += links
        problems += found
    for problem in problems:
        print(problem)
    print("%d files, %d relative links, %d broken" % (len(files), total, len(problems)))
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
