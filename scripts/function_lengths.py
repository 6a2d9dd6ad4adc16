#!/usr/bin/env python3
"""Lists functions longer than a limit in throng's libraries and apps (issue 16: none over 100
lines, flat decoder switches excepted). Function extents come from Universal Ctags
(`--fields=+ne`). Exit status 1 when a function not on the allow-list is over the limit.

    scripts/function_lengths.py [--max 100] [--top 20] [--json] [--root DIR]
"""
import argparse
import json
import os
import shutil
import subprocess
import sys

# Flat `switch` decoders over message types: one short case per type, split only by hiding it.
ALLOWED = {
    ("libs/protocol/src/messages.cpp", "decodeBody"),
}


def functions(root):
    ctags = shutil.which("ctags")
    if ctags is None:
        sys.exit("function_lengths: Universal Ctags not found (apt-get install universal-ctags)")
    out = subprocess.run(
        [ctags, "-R", "--languages=C++", "--kinds-C++=f", "--fields=+ne", "--output-format=json", "-o", "-", "libs", "apps"],
        cwd=root, check=True, capture_output=True, text=True).stdout
    found = []
    for line in out.splitlines():
        tag = json.loads(line)
        if "end" not in tag or tag.get("_type") != "tag":
            continue
        name = tag["name"]
        if name.startswith("__anon"):
            name = "lambda at line %d" % tag["line"]
        found.append({"path": tag["path"], "name": name, "line": tag["line"], "lines": tag["end"] - tag["line"] + 1})
    return sorted(found, key=lambda f: (-f["lines"], f["path"], f["line"]))


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--max", type=int, default=100, help="longest function allowed [lines] (default 100)")
    parser.add_argument("--top", type=int, default=0, help="also list the N longest functions")
    parser.add_argument("--json", action="store_true", help="print one JSON object")
    parser.add_argument("--root", default=os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    args = parser.parse_args()
    found = functions(args.root)
    over = [f for f in found if f["lines"] > args.max and (f["path"], f["name"]) not in ALLOWED]
    if args.json:
        print(json.dumps({"max": args.max, "functions": len(found), "over": over, "longest": found[:args.top]}))
    else:
        for f in found[:args.top]:
            print("%4d  %s:%d %s" % (f["lines"], f["path"], f["line"], f["name"]))
        for f in over:
            print("%s:%d: %s is %d lines long; expected at most %d (split it into named steps)"
                  % (f["path"], f["line"], f["name"], f["lines"], args.max))
        print("%d functions in libs/ and apps/, %d over %d lines" % (len(found), len(over), args.max))
    return 1 if over else 0


if __name__ == "__main__":
    sys.exit(main())
