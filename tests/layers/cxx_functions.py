"""C++ function bodies found without a compiler, for check_sizes.py.

The text is read with comments, literals and preprocessor lines blanked (layers_common), then its
braces are walked with a stack. Each `{` outside a function is classified by its head, the text
since the previous `;`, `{` or `}`:
  namespace ... / extern "C"            -> a namespace: transparent
  class|struct|union|enum ... (no `)`)  -> a type body: transparent for its member functions
  ...) [const noexcept override final mutable -> T requires ...], or a constructor's
  ...) : member(x), member{y}           -> a function body, when the enclosing scope is a file,
                                           namespace or type body
  [captures](params) ... or [captures]  -> a lambda: a function body of its own outside functions
  anything else (= {, a variable's {...})-> an initialiser: not a function
Everything nested inside a function body (lambdas, blocks, local classes) counts toward it. Braces
that are part of a head (a member's {y} in a constructor's init list, a default argument's {})
leave the head going, so the body's `{` still sees the whole signature.
"""

import re
from dataclasses import dataclass

import layers_common as common

NOT_FUNCTIONS = {"if", "for", "while", "switch", "catch", "return", "sizeof", "alignof", "alignas", "decltype",
                 "noexcept", "requires", "static_assert", "typeid", "throw", "__attribute__", "asm", "new", "delete"}
TRAILING_WORDS = ("const", "volatile", "noexcept", "override", "final", "mutable", "constexpr", "consteval",
                  "try", "&&", "&")
ACCESS_LABELS = re.compile(r"^\s*(?:(?:public|private|protected|signals|slots)\s*:(?!:)\s*)+")
OPEN = {")": "(", "]": "[", "}": "{", ">": "<"}


@dataclass
class Function:
    name: str
    start_line: int     # where its signature starts
    brace_line: int     # its opening brace
    end_line: int       # its closing brace
    lambda_: bool = False

    @property
    def lines(self):
        return self.end_line - self.start_line + 1


def matching_open(text, close):
    """Index of the bracket that text[close] closes (brackets of that kind counted only)."""
    closer = text[close]
    opener = OPEN[closer]
    depth = 0
    for i in range(close, -1, -1):
        if text[i] == closer and not (closer == ">" and i > 0 and text[i - 1] == "-"):
            depth += 1
        elif text[i] == opener:
            depth -= 1
            if depth == 0:
                return i
    return -1


def top_level(text, pattern):
    """Start offsets of pattern's matches outside (), [] and {}."""
    depth = 0
    depth_at = []
    for c in text:
        if c in "([{":
            depth += 1
        elif c in ")]}":
            depth -= 1
        depth_at.append(depth if c not in "([{" else depth - 1)
    return [m.start() for m in re.finditer(pattern, text) if depth_at[m.start()] == 0]


def strip_qualifiers(t):
    """The signature without what may follow its parameter list: cv and ref qualifiers, noexcept,
    override, final, mutable, attributes, a trailing return type, a requires clause."""
    while True:
        t = t.rstrip()
        before = t
        for word in TRAILING_WORDS:
            whole_word = not word[0].isalpha() or not re.search(r"\w", t[-len(word) - 1:-len(word)] or " ")
            if t.endswith(word) and whole_word:
                t = t[: -len(word)]
                break
        else:
            if t.endswith("]]"):
                t = t[: t.rfind("[[")] if "[[" in t else t
            elif t.endswith(")"):
                o = matching_open(t, len(t) - 1)
                if o > 0 and re.search(r"\b(noexcept|throw|__attribute__)\s*$", t[:o]):
                    t = re.sub(r"\b(noexcept|throw|__attribute__)\s*$", "", t[:o])
            if t == before:
                for pattern in (r"->", r"\brequires\b"):
                    for at in reversed(top_level(t, pattern)):
                        if pattern == r"->" and t[:at].rstrip().endswith("operator"):
                            continue
                        head = strip_qualifiers(t[:at])
                        if head.endswith(")"):
                            t = head
                            break
                    if t != before:
                        break
        if t == before:
            return t


def lambda_introducer(t):
    """Offset of the `[` of the lambda whose parameters (or captures) end t, or -1."""
    if t.endswith(")"):
        before = t[: matching_open(t, len(t) - 1)].rstrip()
        m = re.search(r"\]\s*<[^;{}()]*>$", before)  # []<typename T>(T x)
        if m:
            before = before[: m.start() + 1]
    else:
        before = t
    if not before.endswith("]") or before.endswith("]]"):
        return -1
    o = matching_open(before, len(before) - 1)
    if o < 0:
        return -1
    prev = before[:o].rstrip()[-1:]
    return -1 if (prev.isalnum() or prev in "_)]") else o


def constructor_signature(h):
    """The part of h before a constructor's init-list colon, or None."""
    for at in top_level(h, r"(?<!:):(?!:)"):
        if strip_qualifiers(h[:at]).endswith(")"):
            return h[:at]
    return None


def function_name(signature):
    t = strip_qualifiers(signature)
    o = matching_open(t, len(t) - 1)
    before = t[:o].rstrip()
    m = re.search(r"((?:[\w~]+(?:<[^<>]*>)?\s*::\s*)*operator\b.*)$", before)
    if m:
        return re.sub(r"\s+", " ", m.group(1)).strip()
    i = len(before)
    while i > 0:
        c = before[i - 1]
        if c.isalnum() or c in "_~:":
            i -= 1
        elif c == ">":
            j = matching_open(before, i - 1)
            if j < 0:
                break
            i = j
        else:
            break
    name = before[i:].strip()
    if re.fullmatch(r"[A-Z][A-Z0-9_]+", name):  # a macro such as TEST(Suite, Name)
        name += re.sub(r"\s+", " ", t[o:])
    return name


def classify(head, scope):
    """('namespace'|'type'|'function'|'lambda'|'head'|'other', signature) for a `{` after head in a
    scope of kind 'file' (a file or namespace), 'type' or 'other' (an initialiser)."""
    h = ACCESS_LABELS.sub("", head).strip()
    if re.match(r"(inline\s+)?namespace\b", h) or re.fullmatch(r'extern\s*"[^"]*"', h):
        return "namespace", h
    t = strip_qualifiers(h)
    if lambda_introducer(t) >= 0:
        return "lambda", h
    if scope == "other":
        return "other", h
    if h.count("(") > h.count(")"):  # a brace inside parentheses: a default argument's {}
        return "head", h
    if re.search(r"\b(class|struct|union|enum)\b", h) and not t.endswith(")"):
        return "type", h
    ctor = constructor_signature(h)
    if ctor is not None:
        return ("function", ctor) if t.endswith((")", "}", "...")) else ("head", h)
    if t.endswith(")") and function_name(t).split("(")[0].split("::")[-1] not in NOT_FUNCTIONS:
        return "function", t
    return "other", h


def find_functions(text):
    """Every function body (and every lambda outside one) in C++ source text."""
    code = common.blank_preprocessor(common.blank_cxx(text))
    found = []
    stack = []          # (kind, head_start, signature start, brace, signature) per open brace
    head_start = 0
    in_function = 0     # open braces that belong to a function body
    for i, c in enumerate(code):
        if c == ";" and not in_function:
            head_start = i + 1
        elif c == "{":
            if in_function:
                in_function += 1
                stack.append(("block", head_start, 0, i, ""))
                continue
            scope = "file"
            for kind, *_ in reversed(stack):
                if kind in ("type", "other", "head"):
                    scope = "type" if kind == "type" else "other"
                    break
            head = code[head_start:i]
            kind, signature = classify(head, scope)
            if kind == "lambda":  # from its captures
                start = head_start + lambda_introducer(strip_qualifiers(head))
            else:  # from the first word of the signature
                label = ACCESS_LABELS.match(head)
                start = head_start + (label.end() if label else 0)
                start += len(code[start:i]) - len(code[start:i].lstrip())
            stack.append((kind, head_start, start, i, signature))
            if kind in ("function", "lambda"):
                in_function = 1
            head_start = i + 1
        elif c == "}" and stack:
            kind, saved_head, start, brace, signature = stack.pop()
            if in_function:
                in_function -= 1
                if in_function == 0:
                    found.append(_function(kind, signature, text, start, brace, i))
            if kind in ("head", "lambda"):
                head_start = saved_head  # the head goes on: `a_{x}, b_(y) {`, `= [] {...};`
            else:
                head_start = i + 1
    return found


def _function(kind, signature, text, start, brace, close):
    if kind == "lambda":
        before = signature[: lambda_introducer(strip_qualifiers(signature))]
        m = re.search(r"(\w+)\s*=\s*$", before)
        name = m.group(1) if m else "lambda"
    else:
        name = function_name(signature)
    return Function(name, common.line_of(text, start), common.line_of(text, brace), common.line_of(text, close),
                    kind == "lambda")
