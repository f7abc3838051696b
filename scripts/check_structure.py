#!/usr/bin/env python3
"""Structure check for the Rust sources: file length, function length, module import cycles.

Usage: scripts/check_structure.py [ROOT ...]        (default: src prep/src ffi/src)

For every ROOT (a crate's source folder) it reports
  (a) files longer than MAX_FILE_LINES lines,
  (b) functions whose body (from the `fn` line to its closing brace) is longer than
      MAX_FN_LINES lines, found by counting braces in the text with strings, raw strings,
      character literals and comments blanked out,
  (c) import cycles between modules. A module is a top-level file or folder of ROOT (`network`,
      `planner`, ...); inside a folder, its `mod.rs` and each child file or folder is a module
      one level deeper (`planner::search`). Edges come from `use` trees and paths that start
      with `crate::`, `super::`, `self::` or a child module the file declares (`mod x;`, then
      `use x::Y` or `x::f()`). Cycles are looked for among the top-level
      modules (a folder's edges counted together) and among the child modules of each folder
      (its `mod.rs` contains them: a parent's declarations and re-exports of its children, and
      the children's `super::` uses of it, are not edges between modules).

Without arguments it also reports (d) mode presence checks (`terrain().is_some()`,
`landmark().is_none()`, `mode() ==`, ...) under src/, prep/src/, host-tests/src/ and
firmware-example/src/: the mode is dispatched with a `match` (docs/ADDING_A_MODE.md).

Exits 1 if anything is reported, 0 otherwise. Python 3 standard library only.
"""

import os
import re
import sys

MAX_FILE_LINES = 800
MAX_FN_LINES = 150
MAX_CYCLES_PER_GROUP = 50


def blank(text):
    """`text` with comments, string literals and character literals replaced by spaces
    (newlines kept), so that braces and keywords can be counted in what remains."""
    out = []
    i, n = 0, len(text)

    def keep_newlines(s):
        return "".join("\n" if c == "\n" else " " for c in s)

    while i < n:
        c = text[i]
        if text.startswith("//", i):
            j = text.find("\n", i)
            j = n if j < 0 else j
            out.append(" " * (j - i))
            i = j
        elif text.startswith("/*", i):
            depth, j = 1, i + 2
            while j < n and depth:
                if text.startswith("/*", j):
                    depth, j = depth + 1, j + 2
                elif text.startswith("*/", j):
                    depth, j = depth - 1, j + 2
                else:
                    j += 1
            out.append(keep_newlines(text[i:j]))
            i = j
        elif (c in "rb" and not (i > 0 and (text[i - 1].isalnum() or text[i - 1] == "_"))
              and re.match(r'(br|r)#*"', text[i:i + 260])):
            m = re.match(r'(br|r)(#*)"', text[i:])
            close = '"' + m.group(2)
            j = text.find(close, i + m.end())
            j = n if j < 0 else j + len(close)
            out.append(keep_newlines(text[i:j]))
            i = j
        elif c == '"':
            j = i + 1
            while j < n and text[j] != '"':
                j += 2 if text[j] == "\\" else 1
            j += 1
            out.append(keep_newlines(text[i:j]))
            i = j
        elif c == "'":
            # A character literal ('a', '\n', '\u{..}', '{') or a lifetime / label ('a).
            m = re.match(r"'(\\u\{[0-9a-fA-F]+\}|\\x[0-9a-fA-F]{2}|\\.|[^\\'\n])'", text[i:i + 12])
            if m:
                out.append(" " * m.end())
                i += m.end()
            else:
                out.append(c)
                i += 1
        else:
            out.append(c)
            i += 1
    return "".join(out)


def rust_files(root):
    for dirpath, dirnames, filenames in os.walk(root):
        dirnames.sort()
        for f in sorted(filenames):
            if f.endswith(".rs"):
                yield os.path.join(dirpath, f)


def line_of(text, pos):
    return text.count("\n", 0, pos) + 1


FN_RE = re.compile(r"\bfn\s+([A-Za-z_][A-Za-z0-9_]*)")


def long_functions(clean):
    """(name, first line, last line) of every function body longer than MAX_FN_LINES."""
    found = []
    for m in FN_RE.finditer(clean):
        # The body starts at the first `{` at nesting depth 0 of (), [] and <> after the
        # signature; a `;` first means a declaration without a body.
        depth, j = 0, m.end()
        while j < len(clean):
            ch = clean[j]
            if ch in "([":
                depth += 1
            elif ch in ")]":
                depth -= 1
            elif ch == ";" and depth == 0:
                j = -1
                break
            elif ch == "{" and depth == 0:
                break
            j += 1
        if j < 0 or j >= len(clean):
            continue
        level, k = 0, j
        while k < len(clean):
            if clean[k] == "{":
                level += 1
            elif clean[k] == "}":
                level -= 1
                if level == 0:
                    break
            k += 1
        first, last = line_of(clean, m.start()), line_of(clean, k)
        if last - first + 1 > MAX_FN_LINES:
            found.append((m.group(1), first, last))
    return found


def module_path(root, path):
    """The module path of a file, e.g. ['planner', 'search'] for planner/search.rs and
    ['planner'] for planner/mod.rs or planner.rs; [] for lib.rs / main.rs."""
    rel = os.path.relpath(path, root)[:-3].split(os.sep)
    if rel[-1] == "mod":
        rel = rel[:-1]
    if rel in (["lib"], ["main"]):
        return []
    return rel


def expand_use_tree(tree):
    """`a::{b, c::{d, e}}` -> ['a::b', 'a::c::d', 'a::c::e'] (whitespace removed)."""
    tree = re.sub(r"\s+", "", tree)
    tree = re.sub(r"\bas\w+", "", tree)  # `x as y` has lost its spaces: xasy is rare enough
    i = tree.find("{")
    if i < 0:
        return [tree]
    depth, j = 0, i
    while j < len(tree):
        if tree[j] == "{":
            depth += 1
        elif tree[j] == "}":
            depth -= 1
            if depth == 0:
                break
        j += 1
    prefix, inner = tree[:i], tree[i + 1:j]
    parts, depth, start = [], 0, 0
    for k, ch in enumerate(inner):
        if ch == "{":
            depth += 1
        elif ch == "}":
            depth -= 1
        elif ch == "," and depth == 0:
            parts.append(inner[start:k])
            start = k + 1
    parts.append(inner[start:])
    paths = []
    for p in parts:
        if p:
            paths.extend(prefix + q for q in expand_use_tree(p))
    return paths


USE_RE = re.compile(r"\buse\s+([^;]*);")
PATH_RE = re.compile(r"(?<![A-Za-z0-9_:])((?:crate|super|self)(?:::(?:super|[A-Za-z_][A-Za-z0-9_]*))+)")


def absolute(mod, path):
    """The absolute module path (a list) that `path` (crate::.., super::.., self::..) names,
    seen from the module `mod`, or None for paths that leave the crate."""
    segs = [s for s in path.split("::") if s]
    if not segs:
        return None
    if segs[0] == "crate":
        return segs[1:]
    base = list(mod)
    if segs[0] == "self":
        segs = segs[1:]
    while segs and segs[0] == "super":
        if not base:
            return None
        base.pop()
        segs = segs[1:]
    return base + segs


MOD_RE = re.compile(r"\bmod\s+([A-Za-z_][A-Za-z0-9_]*)\s*;")


def references(clean, mod):
    """(absolute path, position) of every crate-internal path in the blanked text: `use` trees
    and paths that start with `crate`, `super` or `self`, or with the name of a child module
    the file declares (`mod x;` then `use x::Y` or `x::f()`)."""
    children = set(MOD_RE.findall(clean))
    relative = re.compile(
        r"(?<![A-Za-z0-9_:])((?:%s)(?:::[A-Za-z_][A-Za-z0-9_]*)+)" % "|".join(sorted(children))
    ) if children else None
    inline = inline_modules(clean)

    def module_at(pos):
        # The file's module, plus the inline modules (`mod tests { ... }`) around `pos`.
        return list(mod) + [name for name, a, b in inline if a <= pos < b]

    refs = []
    for m in USE_RE.finditer(clean):
        for p in expand_use_tree(m.group(1)):
            if p.split("::")[0] in children:
                p = "self::" + p
            if p.startswith(("crate::", "super::", "self::")):
                a = absolute(module_at(m.start()), p)
                if a is not None:
                    refs.append((a, m.start()))
    body = USE_RE.sub(lambda m: " " * len(m.group(0)), clean)
    for m in PATH_RE.finditer(body):
        a = absolute(module_at(m.start()), m.group(1))
        if a is not None:
            refs.append((a, m.start()))
    if relative:
        for m in relative.finditer(body):
            a = absolute(module_at(m.start()), "self::" + m.group(1))
            if a is not None:
                refs.append((a, m.start()))
    return refs


INLINE_MOD_RE = re.compile(r"\bmod\s+([A-Za-z_][A-Za-z0-9_]*)\s*\{")


def inline_modules(clean):
    """(name, start, end) of every inline module body `mod name { ... }`, outermost first."""
    found = []
    for m in INLINE_MOD_RE.finditer(clean):
        level, k = 0, m.end() - 1
        while k < len(clean):
            if clean[k] == "{":
                level += 1
            elif clean[k] == "}":
                level -= 1
                if level == 0:
                    break
            k += 1
        found.append((m.group(1), m.end(), k))
    return found


def cycles(nodes, edges):
    """Every elementary cycle of the directed graph (at most MAX_CYCLES_PER_GROUP), each as a
    list of nodes starting from its smallest one."""
    found = []
    order = sorted(nodes)
    for s_index, s in enumerate(order):
        allowed = set(order[s_index:])
        stack = [(s, [s])]
        while stack and len(found) < MAX_CYCLES_PER_GROUP:
            v, path = stack.pop()
            for w in sorted(edges.get(v, ())):
                if w == s:
                    found.append(path)
                elif w in allowed and w not in path:
                    stack.append((w, path + [w]))
    return found


def check(root):
    problems = []
    files = list(rust_files(root))
    texts = {}
    for path in files:
        with open(path, encoding="utf-8") as f:
            texts[path] = f.read()

    for path in files:
        lines = texts[path].count("\n") + (0 if texts[path].endswith("\n") else 1)
        if lines > MAX_FILE_LINES:
            problems.append(f"{path}: file has {lines} lines (limit {MAX_FILE_LINES})")
    for path in files:
        for name, first, last in long_functions(blank(texts[path])):
            problems.append(
                f"{path}:{first}: fn {name} has {last - first + 1} lines "
                f"(lines {first}-{last}, limit {MAX_FN_LINES})"
            )

    # Modules: the module of a file is its path cut to two levels.
    mods = {path: module_path(root, path) for path in files}
    known = {tuple(m[:2]) for m in mods.values() if m} | {tuple(m[:1]) for m in mods.values() if m}

    def node(abs_path):
        for depth in (2, 1):
            key = tuple(abs_path[:depth])
            if len(abs_path) >= depth and key in known:
                return key
        return None

    # Edges at both levels, with where each was first seen.
    edges = {}
    for path in files:
        src = tuple(mods[path][:2])
        if not src:
            continue
        clean = blank(texts[path])
        for abs_path, pos in references(clean, mods[path]):
            dst = node(abs_path)
            if dst is None or dst == src:
                continue
            edges.setdefault((src, dst), f"{path}:{line_of(clean, pos)}")

    groups = {}  # group name -> (nodes, adjacency, edge witnesses)
    for (a, b), where in edges.items():
        if a[0] != b[0]:
            g = "<top level>"
            na, nb = a[0], b[0]
        elif len(a) == 2 and len(b) == 2:
            # Siblings in one folder. The folder's own `mod.rs` contains its children: its
            # `mod`/`pub use` of them and their `super::` uses of it are not edges between
            # modules, so cycles are looked for among the children.
            g = a[0] + "/"
            na, nb = "::".join(a), "::".join(b)
        else:
            continue
        nodes, adj, wit = groups.setdefault(g, (set(), {}, {}))
        nodes.update((na, nb))
        adj.setdefault(na, set()).add(nb)
        wit.setdefault((na, nb), where)

    for g in sorted(groups):
        nodes, adj, wit = groups[g]
        for cyc in cycles(nodes, adj):
            ring = cyc + [cyc[0]]
            hops = ", ".join(f"{x} -> {y} ({wit[(x, y)]})" for x, y in zip(ring, ring[1:]))
            problems.append(f"{root}: import cycle among {g} modules: "
                            f"{' -> '.join(ring)}; {hops}")
        if len(cycles(nodes, adj)) >= MAX_CYCLES_PER_GROUP:
            problems.append(f"{root}: {g}: more than {MAX_CYCLES_PER_GROUP} cycles, "
                            "the rest not listed")
    return problems


# Mode presence checks: the mode is dispatched by a `match` (docs/ADDING_A_MODE.md).
PRESENCE = re.compile(r"\b(terrain|landmark)\(\)\s*\.\s*is_(some|none)\(\)|\bmode\(\)\s*[!=]=")
PRESENCE_ROOTS = ["src", "prep/src", "host-tests/src", "firmware-example/src"]


def presence_checks(repo):
    """Every `terrain().is_some()`, `landmark().is_none()`, `mode() ==` ... outside comments
    and strings under PRESENCE_ROOTS."""
    problems = []
    for root in PRESENCE_ROOTS:
        for path in rust_files(os.path.join(repo, root)):
            with open(path, encoding="utf-8") as f:
                clean = blank(f.read())
            for m in PRESENCE.finditer(clean):
                problems.append(f"{os.path.relpath(path, repo)}:{line_of(clean, m.start())}: "
                                f"mode presence check `{m.group(0)}` (dispatch with a match)")
    return problems


def main(argv):
    here = os.path.dirname(os.path.abspath(__file__))
    repo = os.path.dirname(here)
    roots = argv[1:] or [os.path.join(repo, "src"), os.path.join(repo, "prep", "src"), os.path.join(repo, "ffi", "src")]
    total = 0
    for root in roots:
        root = os.path.relpath(root)
        problems = check(root)
        for p in problems:
            print(p)
        print(f"{root}: {len(problems)} problem(s)")
        total += len(problems)
    if not argv[1:]:
        problems = presence_checks(repo)
        for p in problems:
            print(p)
        print(f"mode presence checks: {len(problems)}")
        total += len(problems)
    return 1 if total else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
