#!/usr/bin/env python3
"""The reference of every command, made from the command line's own definitions (each command's --help, which
the binary builds from its table of commands): one Markdown page per command for the documentation site, one man
page per command, and the bash completion, so none can drift from the program.

    python3 docs/reference/make.py BINARY [--pages DIR] [--man DIR] [--completion FILE]

With no option it writes the pages into docs/reference/ (committed; a test makes them again and compares)."""
import argparse
import datetime
import os
import re
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))


def helptext(binary, words):
    out = subprocess.run([binary] + words + ["--help"], capture_output=True, text=True, check=True).stdout
    # The program's name as a reader types it, not the path it was run by.
    return re.sub(r"^Usage: \S*siloscope", "Usage: siloscope", out, flags=re.M)


def subcommands(text):
    """The names under 'Subcommands:' of a help text, with their one-line help."""
    out, inside = [], False
    for line in text.splitlines():
        if line.startswith("Subcommands:"):
            inside = True
            continue
        if inside:
            m = re.match(r"^  (\S+)\s+(.*)$", line)
            if not m:
                if line.strip() == "":
                    continue
                break
            out.append((m.group(1), m.group(2)))
    return out


def options(text):
    """The long options a help text lists (for the completion)."""
    return sorted(set(re.findall(r"(?<![\w-])(--[a-z][a-z0-9-]*)", text)))


def commands(binary):
    """[(words, one-line help, help text)] for every command and bench's own subcommands."""
    top = helptext(binary, [])
    found = []
    for name, summary in subcommands(top):
        text = helptext(binary, [name])
        found.append(([name], summary, text))
        for sub, sub_summary in subcommands(text):
            found.append(([name, sub], sub_summary, helptext(binary, [name, sub])))
    return top, found


def page(words, summary, text):
    title = "siloscope " + " ".join(words)
    return (f"# {title}\n\n{summary[0].upper() + summary[1:]}.\n\n"
            f"Made from `{title} --help` by `docs/reference/make.py`: it is what the program itself says.\n\n"
            f"```text\n{text.rstrip()}\n```\n")


def man(words, summary, text, version):
    name = "-".join(["siloscope"] + words)
    esc = lambda s: s.replace("\\", "\\\\").replace("-", "\\-")  # noqa: E731
    body = "\n".join(("\\&" + esc(line)) if line.startswith((".", "'")) else esc(line)
                     for line in text.rstrip().splitlines())
    return (f'.TH "{name.upper()}" 1 "{datetime.date(2026, 11, 28).isoformat()}" "siloscope {version}" '
            f'"siloscope manual"\n.SH NAME\n{esc(name)} \\- {esc(summary)}\n.SH SYNOPSIS\n.B {" ".join(["siloscope"] + words)}\n'
            f"[\\fIOPTIONS\\fR]\n.SH DESCRIPTION\n.nf\n{body}\n.fi\n.SH SEE ALSO\n.BR siloscope (1)\n")


def completion(top, found):
    cmds = " ".join(w[0] for w, _, _ in found if len(w) == 1)
    cases = []
    for words, _, text in found:
        if len(words) == 1:
            subs = " ".join(w[1] for w, _, _ in found if len(w) == 2 and w[0] == words[0])
            cases.append(f'    {words[0]}) opts="{" ".join(options(text))} {subs}" ;;')
    return f"""# bash completion for siloscope (made by docs/reference/make.py from the program's --help)
_siloscope() {{
  local cur=${{COMP_WORDS[COMP_CWORD]}} opts
  if [ "$COMP_CWORD" -eq 1 ]; then
    COMPREPLY=($(compgen -W "{cmds} --help --version" -- "$cur"))
    return
  fi
  case "${{COMP_WORDS[1]}}" in
{chr(10).join(cases)}
    *) opts="--help --version" ;;
  esac
  if [[ "$cur" == -* ]]; then
    COMPREPLY=($(compgen -W "$opts" -- "$cur"))
  else
    COMPREPLY=($(compgen -f -- "$cur"))
  fi
}}
complete -o filenames -F _siloscope siloscope
"""


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("binary")
    ap.add_argument("--pages")
    ap.add_argument("--man")
    ap.add_argument("--completion")
    a = ap.parse_args()
    if not (a.pages or a.man or a.completion):
        a.pages = HERE
    top, found = commands(a.binary)
    version = subprocess.run([a.binary, "--version"], capture_output=True, text=True).stdout.split()[0]
    if a.pages:
        os.makedirs(a.pages, exist_ok=True)
        rows = []
        for words, summary, text in found:
            name = "-".join(words)
            with open(os.path.join(a.pages, name + ".md"), "w") as f:
                f.write(page(words, summary, text))
            rows.append(f"| [`siloscope {' '.join(words)}`]({name}.md) | {summary} |")
        with open(os.path.join(a.pages, "index.md"), "w") as f:
            f.write("# Command reference\n\nEvery command, as its own `--help` describes it (made by "
                    "`docs/reference/make.py` from the program; the man pages of the Debian package come from the "
                    "same text).\n\n```text\n" + top.rstrip() + "\n```\n\n| command | what it does |\n|---|---|\n" +
                    "\n".join(rows) + "\n")
        # The site's navigation lists every page (mkdocs.yml, between its reference markers).
        yml = os.path.join(HERE, "..", "..", "mkdocs.yml")
        if os.path.abspath(a.pages) == HERE and os.path.exists(yml):
            text = open(yml).read()
            entries = "\n".join(f"      - siloscope {' '.join(w)}: reference/{'-'.join(w)}.md" for w, _, _ in found)
            block = ("  # reference:begin (written by docs/reference/make.py)\n  - Reference:\n      - Commands: "
                     f"reference/index.md\n{entries}\n  # reference:end")
            text = re.sub(r"  # reference:begin.*?# reference:end", lambda m: block, text, flags=re.S)
            with open(yml, "w") as f:
                f.write(text)
    if a.man:
        os.makedirs(a.man, exist_ok=True)
        with open(os.path.join(a.man, "siloscope.1"), "w") as f:
            f.write(man([], "simulate, film and measure clogging arches", top, version))
        for words, summary, text in found:
            with open(os.path.join(a.man, "siloscope-" + "-".join(words) + ".1"), "w") as f:
                f.write(man(words, summary, text, version))
    if a.completion:
        os.makedirs(os.path.dirname(os.path.abspath(a.completion)), exist_ok=True)
        with open(a.completion, "w") as f:
            f.write(completion(top, found))


if __name__ == "__main__":
    sys.exit(main())
