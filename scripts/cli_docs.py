#!/usr/bin/env python3
"""Writes throng's man pages and its bash and zsh completions from the program's own command line
(`throng describe-cli`, JSON: the descriptions, footers and option texts that --help prints), so both follow every subcommand
and flag the program has. Run at build time (apps/throng/CMakeLists.txt); docs/install.md.

usage: cli_docs.py --throng PATH --out DIR
writes DIR/man/throng.1 and DIR/man/throng-CMD.1 (with .gz copies for installing),
       DIR/completions/throng (bash) and DIR/completions/_throng (zsh)
"""
import argparse
import gzip
import json
import os
import re
import subprocess

FILE_LABEL = re.compile(r"(FILE|PATH|\.json|\.sqlite|\.gltf|\.glb)", re.IGNORECASE)


def value_kind(option):
    """How a value is completed: ("choices", [...]), ("dir",), ("file", glob) or ("none",)."""
    label = option["type"]
    choices = re.search(r"\{([^{}]*)\}", label)
    if choices:
        return ("choices", [c.strip() for c in choices.group(1).split(",") if c.strip()])
    plain = label.split(":")[0]
    if "DIR" in plain:
        return ("dir",)
    if FILE_LABEL.search(plain) or (option["positional"] and plain.upper() == plain and plain):
        ext = re.search(r"\.(json|sqlite|gltf|glb)\b", plain, re.IGNORECASE)
        return ("file", f"*.{ext.group(1)}" if ext else "*")
    return ("none",)


def flags(command):
    return [o for o in command["options"] if not o["positional"]]


def positionals(command):
    return [o for o in command["options"] if o["positional"]]


# ---------------------------------------------------------------------------------------------
# man pages

def roff(text):
    """Plain text as roff: backslashes and hyphens escaped, no line starting with a control char."""
    text = text.replace("\\", "\\e").replace("-", "\\-")
    lines = []
    for line in text.split("\n"):
        if line.startswith((".", "'")):
            line = "\\&" + line
        lines.append(line)
    return "\n".join(lines)


def paragraphs(text):
    """Help-text paragraphs (blank-line separated) as roff paragraphs; lines kept as written."""
    out = []
    for block in re.split(r"\n\s*\n", text.strip()):
        if block.strip():
            out.append(".PP\n.nf\n" + roff(block.rstrip()) + "\n.fi")
    return "\n".join(out)


def option_item(option):
    label = option["type"].split(":")[0] or option["name"]
    names = ", ".join(f"\\fB{roff(n)}\\fR" for n in option["names"]) or f"\\fI{roff(label)}\\fR"
    label = option["type"]
    if option["takes_value"] and not option["positional"] and label:
        names += f" \\fI{roff(label)}\\fR"
    desc = option["description"] or ""
    if option["default"]:
        desc += f" (default: {option['default']})"
    return f".TP\n{names}\n{roff(desc)}"


def man_page(name, title_name, summary, synopsis, description, options, version, see_also):
    parts = [f'.TH {title_name.upper()} 1 "" "throng {version}" "User Commands"',
             ".SH NAME", f"{roff(name)} \\- {roff(summary)}",
             ".SH SYNOPSIS", synopsis,
             ".SH DESCRIPTION", description]
    if options:
        parts += [".SH OPTIONS"] + [option_item(o) for o in options]
    parts += [".SH EXIT STATUS",
              "0 success, 1 bad input or failure, 2 bad flags or unknown command, 130 interrupted.",
              ".SH SEE ALSO", ",\n".join(f".BR {s} (1)" for s in see_also)]
    return "\n".join(parts) + "\n"


def synopsis_line(words, command):
    args = " ".join(f"\\fI{roff(p['type'].split(':')[0] or p['name'])}\\fR" for p in positionals(command))
    return f".B {words}\n[\\fIOPTIONS\\fR] {args}".rstrip()


def write_man(app, out_dir):
    version = app["version"]
    names = [c["name"] for c in app["commands"]]
    pages = {}
    command_list = "\n".join(f".TP\n\\fBthrong {c['name']}\\fR\n{roff(c['description'])}" for c in app["commands"])
    pages["throng"] = man_page(
        "throng", "throng", app["description"].split("\n")[0].split(" \u2014 ")[-1].rstrip("."),
        ".B throng\n\\fICOMMAND\\fR [\\fIOPTIONS\\fR]",
        paragraphs(app["description"]) + "\n.SH COMMANDS\n" + command_list + "\n" + paragraphs(app["footer"]),
        flags(app), version, [f"throng\\-{n}" for n in names])
    for command in app["commands"]:
        n = command["name"]
        description = paragraphs(command["description"]) + "\n" + paragraphs(command["footer"])
        pages[f"throng-{n}"] = man_page(
            f"throng-{n}", f"throng-{n}", command["description"], synopsis_line(f"throng {n}", command),
            description, command["options"], version, ["throng"])
    os.makedirs(out_dir, exist_ok=True)
    for page, text in pages.items():
        path = os.path.join(out_dir, f"{page}.1")
        with open(path, "w", encoding="utf-8") as f:
            f.write(text)
        # Debian installs man pages compressed (gzip -9n: no name, no time stamp).
        with open(path + ".gz", "wb") as raw, gzip.GzipFile(filename="", mode="wb", fileobj=raw, compresslevel=9,
                                                             mtime=0) as gz:
            gz.write(text.encode("utf-8"))
    return sorted(pages)


# ---------------------------------------------------------------------------------------------
# bash

def bash_value_case(command):
    lines = []
    for o in flags(command):
        if not o["takes_value"]:
            continue
        kind = value_kind(o)
        pattern = "|".join(o["names"])
        if kind[0] == "choices":
            action = f"COMPREPLY=($(compgen -W '{' '.join(kind[1])}' -- \"$cur\"))"
        elif kind[0] == "dir":
            action = "COMPREPLY=($(compgen -d -- \"$cur\"))"
        elif kind[0] == "file":
            action = "COMPREPLY=($(compgen -f -- \"$cur\"))"
        else:
            action = "COMPREPLY=()"
        lines.append(f"        {pattern}) {action}; return ;;")
    return "\n".join(lines)


def bash_script(app):
    names = " ".join(c["name"] for c in app["commands"])
    top_flags = " ".join(n for o in flags(app) for n in o["names"])
    cases = []
    for c in app["commands"]:
        words = " ".join(n for o in flags(c) for n in o["names"])
        values = bash_value_case(c)
        pos = positionals(c)
        kind = value_kind(pos[0]) if pos else ("none",)
        positional = {"dir": "COMPREPLY=($(compgen -d -- \"$cur\"))",
                      "file": "COMPREPLY=($(compgen -f -- \"$cur\"))"}.get(kind[0], "COMPREPLY=()")
        if kind[0] == "choices":
            positional = f"COMPREPLY=($(compgen -W '{' '.join(kind[1])}' -- \"$cur\"))"
        cases.append(f"""    {c['name']})
      case "$prev" in
{values}
      esac
      if [[ "$cur" == -* ]]; then
        COMPREPLY=($(compgen -W '{words}' -- "$cur"))
      else
        {positional}
      fi
      ;;""")
    body = "\n".join(cases)
    return f"""# bash completion for throng {app['version']} — generated by scripts/cli_docs.py from the program's command line
_throng() {{
  local cur="${{COMP_WORDS[COMP_CWORD]}}" prev="${{COMP_WORDS[COMP_CWORD-1]}}" command="" i
  for ((i = 1; i < COMP_CWORD; i++)); do
    if [[ "${{COMP_WORDS[i]}}" != -* ]]; then command="${{COMP_WORDS[i]}}"; break; fi
  done
  case "$command" in
    "")
      COMPREPLY=($(compgen -W '{names} {top_flags}' -- "$cur"))
      ;;
{body}
  esac
  # File names: directories get no trailing space.
  compopt -o filenames 2>/dev/null || true
}}
complete -F _throng throng
"""


# ---------------------------------------------------------------------------------------------
# zsh

def zsh_quote(text):
    return "'" + text.replace("'", "'\\''") + "'"


def zsh_desc(text):
    first = text.split("\n")[0]
    first = re.split(r"(?<=[a-z\)])\. ", first)[0]
    if len(first) > 100:
        first = first[:97] + "..."
    return first.replace("\\", "\\\\").replace("[", "\\[").replace("]", "\\]").replace(":", "\\:")


def zsh_action(option):
    kind = value_kind(option)
    label = (option["type"].split(":")[0] or option["name"]).replace(":", "\\:")
    if kind[0] == "choices":
        return f"{label}:({' '.join(kind[1])})"
    if kind[0] == "dir":
        return f"{label}:_files -/"
    if kind[0] == "file":
        return f"{label}:_files" + (f" -g \"{kind[1]}\"" if kind[1] != "*" else "")
    return f"{label}: "


def zsh_specs(command):
    specs = []
    for o in flags(command):
        desc = zsh_desc(o["description"])
        value = ":" + zsh_action(o) if o["takes_value"] else ""
        if len(o["names"]) > 1:
            exclusive = " ".join(o["names"])
            specs.append(zsh_quote(f"({exclusive})" + "{" + ",".join(o["names"]) + "}" + f"[{desc}]{value}"))
        else:
            specs.append(zsh_quote(f"{o['names'][0]}[{desc}]{value}"))
    for i, p in enumerate(positionals(command), start=1):
        specs.append(zsh_quote(f"{i}:{zsh_action(p)}"))
    return specs


def zsh_script(app):
    commands = "\n".join("    " + zsh_quote(f"{c['name']}:{zsh_desc(c['description'])}") for c in app["commands"])
    cases = []
    for c in app["commands"]:
        specs = " \\\n          ".join(zsh_specs(c))
        cases.append(f"        {c['name']})\n          _arguments -s \\\n          {specs}\n          ;;")
    top = " \\\n    ".join(zsh_specs(app))
    body = "\n".join(cases)
    return f"""#compdef throng
# zsh completion for throng {app['version']} — generated by scripts/cli_docs.py from the program's command line
_throng() {{
  local -a commands
  commands=(
{commands}
  )
  local curcontext="$curcontext" state line
  _arguments -C \\
    {top} \\
    '1: :->command' \\
    '*:: :->args'
  case $state in
    command) _describe -t commands 'throng command' commands ;;
    args)
      case $line[1] in
{body}
      esac
      ;;
  esac
}}
_throng "$@"
"""


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--throng", required=True, help="the throng program")
    ap.add_argument("--out", required=True, help="output directory")
    args = ap.parse_args()
    app = json.loads(subprocess.run([args.throng, "describe-cli"], check=True, capture_output=True, text=True).stdout)
    write_man(app, os.path.join(args.out, "man"))
    completions = os.path.join(args.out, "completions")
    os.makedirs(completions, exist_ok=True)
    with open(os.path.join(completions, "throng"), "w", encoding="utf-8") as f:
        f.write(bash_script(app))
    with open(os.path.join(completions, "_throng"), "w", encoding="utf-8") as f:
        f.write(zsh_script(app))


if __name__ == "__main__":
    main()
