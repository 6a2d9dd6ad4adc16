#!/usr/bin/env python3
"""ctest cli_docs: the generated man pages and completions (scripts/cli_docs.py, built into
BUILD/cli-docs) cover the whole command line, read from the program's --help output itself (not
from the describe-cli JSON they were made from), and the man pages render without warnings.
  - every subcommand listed by `throng --help` has a man page throng-CMD.1, is offered by the bash
    completion with no word typed and is in the zsh completion's command list;
  - every flag printed by `throng CMD --help` (short and long) is in throng-CMD.1, among the bash
    completion's words for CMD and in the zsh completion's specs for CMD;
  - `man --warnings -l` renders every page with nothing on stderr (groff's warnings), and
    `bash -n` / `zsh -n` accept the completion scripts;
  - the hidden describe-cli is in no completion and no page (it is not a user command).
usage: cli_docs_test.py THRONG DOCS_DIR
"""
import os
import re
import subprocess
import sys

THRONG, DOCS = sys.argv[1], sys.argv[2]
failures = []


def fail(message):
    failures.append(message)
    print("FAIL:", message)


def help_text(*args):
    return subprocess.run([THRONG, *args, "--help"], check=True, capture_output=True, text=True).stdout


def section(text, title):
    """The lines of a CLI11 help section ("Options:", "Subcommands:") up to the next blank line."""
    lines = text.split("\n")
    start = lines.index(title) + 1
    end = next((i for i in range(start, len(lines)) if not lines[i].strip()), len(lines))
    return lines[start:end]


def commands():
    return [line.split()[0] for line in section(help_text(), "Subcommands:") if line.startswith("  ")]


def flags_of(command):
    found = []
    for line in section(help_text(command), "Options:"):
        head = line.strip().split("  ")[0]
        if head.startswith("-"):
            found += re.findall(r"(?<![\w-])(--?[A-Za-z][\w-]*)", head.split(" ")[0])
    return found


def bash_words(words):
    script = os.path.join(DOCS, "completions", "throng")
    array = " ".join(f"'{w}'" for w in words)
    out = subprocess.run(["bash", "-c", f'source "{script}"; COMP_WORDS=({array}); COMP_CWORD={len(words) - 1}; '
                                        '_throng; printf "%s\\n" "${COMPREPLY[@]}"'],
                         check=True, capture_output=True, text=True, cwd="/").stdout
    return set(out.split())


def zsh_block(zsh, command):
    """The _arguments specs of `command` in the zsh completion."""
    match = re.search(rf"^ +{re.escape(command)}\)\n(.*?)^ +;;", zsh, re.S | re.M)
    return match.group(1) if match else ""


def man_mentions(page_text, flag):
    return flag.replace("-", "\\-") in page_text


def check_renders(page):
    env = dict(os.environ, LC_ALL="C.UTF-8", MANWIDTH="80", MANROFFSEQ="")
    run = subprocess.run(["man", "--warnings", "-E", "UTF-8", "-l", page], capture_output=True, text=True, env=env)
    if run.returncode != 0 or run.stderr.strip():
        fail(f"man -l {os.path.basename(page)}: exit {run.returncode}: {run.stderr.strip()[:500]}")
    elif len(run.stdout.split("\n")) < 10:
        fail(f"man -l {os.path.basename(page)} rendered almost nothing")


def main():
    man_dir = os.path.join(DOCS, "man")
    with open(os.path.join(DOCS, "completions", "_throng"), encoding="utf-8") as f:
        zsh = f.read()
    cmds = commands()
    if len(cmds) < 10:
        fail(f"throng --help lists only {cmds}")
    offered = bash_words(["throng", ""])
    for command in cmds:
        page = os.path.join(man_dir, f"throng-{command}.1")
        if not os.path.isfile(page):
            fail(f"no man page {page}")
            continue
        with open(page, encoding="utf-8") as f:
            page_text = f.read()
        check_renders(page)
        if command not in offered:
            fail(f"bash completion does not offer '{command}'")
        if not re.search(rf"^ +'{re.escape(command)}:", zsh, re.M):
            fail(f"zsh completion's command list lacks '{command}'")
        bash_flags = bash_words(["throng", command, "-"])
        block = zsh_block(zsh, command)
        flags = flags_of(command)
        if "--help" not in flags or len(flags) < 2:
            fail(f"throng {command} --help: flags not found in {flags}")
        for flag in flags:
            if not man_mentions(page_text, flag):
                fail(f"throng-{command}.1 does not describe {flag}")
            if flag not in bash_flags:
                fail(f"bash completion of 'throng {command} -' lacks {flag}")
            if not re.search(rf"[{{,'\[(]{re.escape(flag)}[\[,}}) ]", block):
                fail(f"zsh completion of 'throng {command}' lacks {flag}")
        print(f"ok: {command}: man page, bash and zsh completion with {len(flags)} flags")
    main_page = os.path.join(man_dir, "throng.1")
    check_renders(main_page)
    with open(main_page, encoding="utf-8") as f:
        text = f.read()
    for command in cmds:
        if f"throng\\-{command}" not in text:
            fail(f"throng.1 does not refer to throng-{command}(1)")
    for flag in ("--help", "--version"):
        if not man_mentions(text, flag) or flag not in offered:
            fail(f"throng.1 or the bash completion lacks {flag}")
    if "describe-cli" in offered or "describe-cli" in zsh or any("describe" in p for p in os.listdir(man_dir)):
        fail("the hidden describe-cli is offered as a command")
    for shell, script in (("bash", "throng"), ("zsh", "_throng")):
        run = subprocess.run([shell, "-n", os.path.join(DOCS, "completions", script)], capture_output=True, text=True)
        if run.returncode != 0:
            fail(f"{shell} -n {script}: {run.stderr.strip()}")
    if failures:
        print(f"{len(failures)} failure(s)")
        return 1
    print(f"ok: {len(cmds)} commands documented and completed")
    return 0


if __name__ == "__main__":
    sys.exit(main())
