#!/usr/bin/env python3
"""Size discipline, held by a test: no function in src/ longer than 120 lines (C++ and Python), and every source
file over 400 lines says in its opening comment why it is one concept ("Over 400 lines because ...").

    python3 tests/check_sizes.py SRC_DIR        (exit 1 and the offenders listed when any)

C++ is read as text: comments, strings and character literals are blanked first, then every brace that opens a
function body (one that follows the ')' of a parameter list, not that of if, for, while, switch or catch) is
matched to its closing brace; a function's length runs from the line of its name to that brace. Lambdas and
local classes count towards the function that holds them."""
import ast
import os
import re
import sys

MAX_FUNCTION = 120
MAX_FILE = 400
CONTROL = {"if", "for", "while", "switch", "catch", "return", "sizeof", "decltype", "alignof", "static_assert"}


def blank_cpp(text):
    """The text with comments, string and character literals replaced by spaces (newlines kept)."""
    out, i, n = [], 0, len(text)
    while i < n:
        c = text[i]
        if text.startswith("//", i):
            j = text.find("\n", i)
            j = n if j < 0 else j
            out.append(" " * (j - i))
            i = j
        elif text.startswith("/*", i):
            j = text.find("*/", i + 2)
            j = n if j < 0 else j + 2
            out.append(re.sub(r"[^\n]", " ", text[i:j]))
            i = j
        elif c == "R" and text.startswith('R"', i) and (i == 0 or not (text[i - 1].isalnum() or text[i - 1] == "_")):
            open_paren = text.find("(", i)
            delim = text[i + 2:open_paren]
            j = text.find(")" + delim + '"', open_paren)
            j = n if j < 0 else j + len(delim) + 2
            out.append(re.sub(r"[^\n]", " ", text[i:j]))
            i = j
        elif c in "\"'":
            if c == "'" and i > 0 and text[i - 1].isalnum():  # a digit separator (1'000)
                out.append(" ")
                i += 1
                continue
            j = i + 1
            while j < n and text[j] != c:
                j += 2 if text[j] == "\\" else 1
            j = min(n, j + 1)
            out.append(re.sub(r"[^\n]", " ", text[i:j]))
            i = j
        else:
            out.append(c)
            i += 1
    return "".join(out)


def cpp_functions(text):
    """(name, first line, last line) of each outermost function body in C++ source."""
    code = blank_cpp(text)
    line_of = [0] * (len(code) + 1)
    line = 1
    for k, ch in enumerate(code):
        line_of[k] = line
        if ch == "\n":
            line += 1
    found, stack, k = [], [], 0  # stack: (kind, index) of open braces; kind "f" for function bodies
    while k < len(code):
        ch = code[k]
        if ch == "{":
            kind, start = "o", k
            if not any(s[0] == "f" for s in stack):
                head = code[max(0, k - 400):k]
                # Qualifiers between the parameter list and the body.
                m = re.search(r"\)\s*((const|override|final|noexcept|mutable|volatile|&|&&|->\s*[\w:<>,\s\*&]+)\s*)*$",
                              head)
                if m:
                    # The '(' matching that ')', and the word before it.
                    depth, j = 0, k - len(head) + m.start()
                    while j >= 0:
                        if code[j] == ")":
                            depth += 1
                        elif code[j] == "(":
                            depth -= 1
                            if depth == 0:
                                break
                        j -= 1
                    word = re.search(r"([\w:~]+)\s*$", code[max(0, j - 200):j])
                    name = word.group(1) if word else ""
                    if name.split("::")[-1] not in CONTROL and name:
                        # A constructor's initializer list: the name is before the first ':' of the head.
                        kind = "f"
                        start_line = line_of[j]
                        stack.append(("f", k, name, start_line))
                        k += 1
                        continue
            stack.append((kind, start))
        elif ch == "}" and stack:
            top = stack.pop()
            if top[0] == "f":
                found.append((top[2], top[3], line_of[k]))
        k += 1
    return found


def python_functions(text, path):
    out = []
    for node in ast.walk(ast.parse(text, path)):
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
            out.append((node.name, node.lineno, node.end_lineno))
    return out


def main(src):
    long_functions, unexplained = [], []
    for root, _dirs, files in os.walk(src):
        for name in sorted(files):
            path = os.path.join(root, name)
            rel = os.path.relpath(path, os.path.dirname(os.path.abspath(src)))
            if not name.endswith((".cpp", ".h", ".py")):
                continue
            text = open(path, encoding="utf-8").read()
            functions = python_functions(text, path) if name.endswith(".py") else cpp_functions(text)
            for fname, first, last in functions:
                if last - first + 1 > MAX_FUNCTION:
                    long_functions.append(f"{rel}:{first}: {fname} is {last - first + 1} lines")
            lines = text.count("\n")
            opening = "\n".join(text.splitlines()[:8]).lower()
            if lines > MAX_FILE and "400 lines" not in opening:
                unexplained.append(f"{rel}: {lines} lines, and its opening comment does not say why it is one "
                                   f"concept (\"Over 400 lines because ...\")")
    for item in long_functions:
        print(f"function over {MAX_FUNCTION} lines: {item} (split it by the steps it takes)")
    for item in unexplained:
        print(f"file over {MAX_FILE} lines: {item}")
    if long_functions or unexplained:
        sys.exit(1)
    print(f"sizes: no function over {MAX_FUNCTION} lines, every file over {MAX_FILE} lines says why")


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    main(sys.argv[1])
