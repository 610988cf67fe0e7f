#!/usr/bin/env python3
"""README and docs/ say what is true now: a short README, no commit hashes, links that resolve."""
import os
import re
import sys

README_MAX_LINES = 220
# A run of 7-40 hex digits with a digit and a letter among them reads as a commit hash.
HASH = re.compile(r"(?<![0-9A-Za-z_./#-])[0-9a-f]{7,40}(?![0-9A-Za-z_])")
LINK = re.compile(r"\]\(([^)#\s]+)(#[^)\s]*)?\)")


def main():
    root = sys.argv[1] if len(sys.argv) > 1 else "."
    pages = ["README.md"] + sorted(
        os.path.join("docs", p) for p in os.listdir(os.path.join(root, "docs")) if p.endswith(".md"))
    problems = []
    with open(os.path.join(root, "README.md"), encoding="utf-8") as f:
        n = sum(1 for _ in f)
    if n > README_MAX_LINES:
        problems.append(f"README.md: {n} lines, more than {README_MAX_LINES}")
    for page in pages:
        with open(os.path.join(root, page), encoding="utf-8") as f:
            for number, line in enumerate(f, 1):
                for m in HASH.finditer(line):
                    word = m.group(0)
                    if re.search(r"[0-9]", word) and re.search(r"[a-f]", word):
                        problems.append(f"{page}:{number}: '{word}' reads as a commit hash")
                for m in LINK.finditer(line):
                    target = m.group(1)
                    if re.match(r"^[a-z]+:", target):
                        continue
                    path = os.path.normpath(os.path.join(root, os.path.dirname(page), target))
                    if not os.path.exists(path):
                        problems.append(f"{page}:{number}: link to '{target}', which does not exist")
    for p in problems:
        print(p)
    print(f"{len(pages)} pages read, {len(problems)} problems")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
