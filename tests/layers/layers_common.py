"""What the layer checks share: where the repository is, which files it has, and C++ text with its
comments and literals blanked out, so that a rule matches code and not the prose about it.

Blanking keeps every character's offset and every newline, so a match's line number in the blanked
text is its line number in the file.
"""

import os
import re
import subprocess

# tests/layers/<this file> -> the repository's root
REPO_ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))

CXX_EXTENSIONS = (".cpp", ".cc", ".cxx", ".hpp", ".hh", ".hxx", ".h", ".ipp", ".inl")


def add_root_argument(parser):
    parser.add_argument("--root", default=REPO_ROOT,
                        help="the repository to check (default: the one this script is in)")


def require_root(parser, root, folders=(), any_of=False):
    """Stops with a usage error unless root is a folder with the given folders (all, or any_of
    them): a check run on the wrong folder must not pass for having found nothing to check."""
    if not os.path.isdir(root):
        parser.error(f"--root {root}: not a folder")
    present = [f for f in folders if os.path.isdir(os.path.join(root, f))]
    if folders and not (present if any_of else len(present) == len(folders)):
        parser.error(f"--root {root}: no {' or '.join(folders) if any_of else ', '.join(folders)} folder")


def walk_files(root, top_dirs, accept):
    """Relative paths of the files under root/<top> for each top in top_dirs that accept(path)
    likes, sorted; hidden folders and build folders are not entered."""
    found = []
    for top in top_dirs:
        base = os.path.join(root, top)
        for dirpath, dirnames, filenames in os.walk(base):
            dirnames[:] = sorted(d for d in dirnames if not d.startswith(".") and not d.startswith("build"))
            for name in filenames:
                rel = os.path.relpath(os.path.join(dirpath, name), root).replace(os.sep, "/")
                if accept(rel):
                    found.append(rel)
    return sorted(found)


def repo_files(root):
    """The files git knows of (tracked, plus untracked ones it does not ignore) when root is a git
    work tree's top; otherwise (a test tree) every file under root outside hidden and build folders.
    Files deleted from the work tree but still in the index are left out."""
    try:
        top = subprocess.run(["git", "-C", root, "rev-parse", "--show-toplevel"],
                             capture_output=True, text=True, check=True).stdout.strip()
    except (OSError, subprocess.CalledProcessError):
        top = None
    if top and os.path.realpath(top) == os.path.realpath(root):
        out = subprocess.run(["git", "-C", root, "ls-files", "-z", "--cached", "--others", "--exclude-standard"],
                             capture_output=True, text=True, check=True).stdout
        names = sorted(set(p for p in out.split("\0") if p))
        return [p for p in names if os.path.isfile(os.path.join(root, p))]
    return walk_files(root, ["."], lambda rel: True)


def read_text(path):
    with open(path, encoding="utf-8", errors="replace") as f:
        return f.read()


def _blank(chars, start, end):
    for i in range(start, end):
        if chars[i] != "\n":
            chars[i] = " "


_RAW_PREFIX = re.compile(r"(?:u8|u|U|L)?R$")


def blank_cxx(text, strings=True):
    """text with comments blanked out, and with strings=True the insides of string and character
    literals too (their quotes stay, so `extern "C"` still reads as extern "..."). Handles raw
    strings R"x(...)x" and digit separators (1'000 is a number, not a character literal)."""
    chars = list(text)
    n = len(text)
    i = 0
    while i < n:
        c = text[i]
        if c == "/" and i + 1 < n and text[i + 1] == "/":
            j = i
            while j < n and text[j] != "\n":
                # a line comment ending in a backslash continues on the next line
                if text[j] == "\\" and j + 1 < n and text[j + 1] == "\n":
                    j += 1
                j += 1
            _blank(chars, i, j)
            i = j
        elif c == "/" and i + 1 < n and text[i + 1] == "*":
            j = text.find("*/", i + 2)
            j = n if j < 0 else j + 2
            _blank(chars, i, j)
            i = j
        elif c == '"':
            prefix = _identifier_before(text, i)
            if _RAW_PREFIX.match(prefix):
                open_paren = text.find("(", i + 1)
                delimiter = text[i + 1:open_paren] if open_paren >= 0 else ""
                close = text.find(")" + delimiter + '"', open_paren + 1) if open_paren >= 0 else -1
                j = n if close < 0 else close + len(delimiter) + 2
                if strings:
                    _blank(chars, i + 1, j - 1)
                i = j
            else:
                j = _literal_end(text, i, '"')
                if strings:
                    _blank(chars, i + 1, j - 1)
                i = j
        elif c == "'":
            token = _pp_token_before(text, i)
            if token[:1].isdigit():  # a digit separator: 1'000'000
                i += 1
            else:
                j = _literal_end(text, i, "'")
                if strings:
                    _blank(chars, i + 1, j - 1)
                i = j
        else:
            i += 1
    return "".join(chars)


def _identifier_before(text, i):
    j = i
    while j > 0 and (text[j - 1].isalnum() or text[j - 1] == "_"):
        j -= 1
    return text[j:i]


def _pp_token_before(text, i):
    j = i
    while j > 0 and (text[j - 1].isalnum() or text[j - 1] in "_.'"):
        j -= 1
    return text[j:i]


def _literal_end(text, i, quote):
    """Index just past the literal that opens at text[i] (a line break ends a broken one)."""
    j = i + 1
    n = len(text)
    while j < n:
        if text[j] == "\\":
            j += 2
            continue
        if text[j] == quote:
            return j + 1
        if text[j] == "\n":
            return j
        j += 1
    return n


def blank_preprocessor(text):
    """Blanks preprocessor lines (with their continuations) of already comment-blanked text, and
    the #else/#elif branches of conditionals: one branch is read, so braces stay balanced."""
    lines = text.split("\n")
    out = []
    depth = 0           # nesting of #if at this point
    skip_from = None    # depth whose #else branch is being skipped
    continued = False
    for line in lines:
        stripped = line.lstrip()
        directive = continued or stripped.startswith("#")
        if directive and not continued:
            word = re.match(r"#\s*(\w*)", stripped).group(1)
            if word in ("if", "ifdef", "ifndef"):
                depth += 1
            elif word in ("else", "elif") and skip_from is None:
                skip_from = depth
            elif word == "endif":
                if skip_from == depth:
                    skip_from = None
                depth -= 1
        continued = directive and line.rstrip().endswith("\\")
        out.append(" " * len(line) if directive or skip_from is not None else line)
    return "\n".join(out)


def line_of(text, offset):
    return text.count("\n", 0, offset) + 1


def report(check, violations, checked, what="violation(s)"):
    """Prints every violation, then one summary line; the exit status: 1 when any, else 0."""
    for v in violations:
        print(v)
    if violations:
        print(f"{check}: {len(violations)} {what} in {checked}")
        return 1
    print(f"{check}: OK, {checked}")
    return 0
