#!/usr/bin/env python3
"""Finds import circles between the sibling modules of each crate.

A module uses another when its code names it by a `crate::`, `super::` or `self::` path, in
a `use` (grouped, nested, renamed, over several lines) or in an expression. Comments, string
literals and items under `#[cfg(test)]` do not count (`#[cfg(test)] mod foo;` leaves out
foo.rs and foo/ too); code after a `#[cfg(test)]` item does.

Two sibling modules are in a circle when each reaches the other, at any depth (`b::z` using
`crate::a::x` is `b` using `a`). A child using its parent's items is not a circle: that is
how Rust modules share a parent's private items. Each group of siblings in a circle is
reported once, with the uses (file and line) that make it.

usage: tools/import_cycles.py CRATE_SRC_DIR...   (exit status 1 when any circle is found)
"""
import os
import re
import sys
from collections import defaultdict

# One token at a time. Literals come before words so that `r"..."`, `b"..."` and `'"'` are
# read as literals (the `"` of a char literal would otherwise open a string).
TOKEN = re.compile(
    r"""(?P<space>\s+) | (?P<comment>//[^\n]*) | (?P<block>/\*)
    | (?P<raw>[bc]?r(?P<hashes>\#*)".*?"(?P=hashes))
    | (?P<str>[bc]?"(?:\\.|[^"\\])*")
    | (?P<char>b?'(?:\\(?:u\{[0-9a-fA-F_]*\}|x[0-9a-fA-F]{2}|.)|[^\\'\n])')
    | (?P<lifetime>'(?:r\#)?[A-Za-z_]\w*)
    | (?P<word>(?:r\#)?[A-Za-z_]\w*|[0-9]\w*)
    | (?P<punct>::|.)""",
    re.VERBOSE | re.DOTALL,
)
OPEN, CLOSE = {"(", "[", "{"}, {")", "]", "}"}
# `cfg(test)` and `cfg(all(..., test, ...))` are test-only; `cfg(any(test, ...))` is not.
TEST_CFG = re.compile(r"cfg\((?:all\((?:.*,)?)?test\b")
# Items that end at their closing brace (or `;`: `mod foo;`), and those that end at `;` only.
BRACED_ITEMS = {"fn", "impl", "mod", "trait", "struct", "enum", "union", "macro_rules"}
SEMICOLON_ITEMS = {"use", "let", "static", "type"}
FN_QUALIFIERS = {"fn", "unsafe", "async", "extern"}  # `const fn` is a function, not a const
PATH_HEADS = {"crate", "super", "self"}
is_word = re.compile(r"\w").match


def tokens(text):
    """The code of `text` as (token, line) pairs, then "<eof>" sentinels. Comments vanish
    and literals become `""`, so a path in prose or in a message is never taken for a use."""
    out, pos, line = [], 0, 1
    while pos < len(text):
        m = TOKEN.match(text, pos)
        kind, tok = m.lastgroup, m.group()
        if kind == "block":  # block comments nest in Rust: a regex cannot find their end
            depth, end = 1, pos + 2
            while depth and end < len(text):
                step = {"/*": 1, "*/": -1}.get(text[end : end + 2], 0)
                depth, end = depth + step, end + (2 if step else 1)
            tok = text[pos:end]
        elif kind in ("raw", "str", "char"):
            out.append(('""', line))
        elif kind in ("word", "punct"):
            out.append((tok, line))
        line += tok.count("\n")
        pos += len(tok)
    return out + [("<eof>", line)] * 3  # so that looking ahead never leaves the list


def closing(toks, i):
    """Index of the bracket that closes the one at toks[i]."""
    depth = 0
    for j in range(i, len(toks)):
        depth += (toks[j][0] in OPEN) - (toks[j][0] in CLOSE)
        if depth == 0:
            return j
    return len(toks) - 1


def item_end(toks, i):
    """Index just past the item (or statement, field, variant) that starts at toks[i].

    `fn`, `impl`, `mod`... end at their closing brace, `use`, `let`, `const`... at `;`, the
    rest (fields, variants) at `,` or `;`; none runs past the brace closing its block.
    """
    depth, kind = 0, None
    for j in range(i, len(toks) - 1):
        t = toks[j][0]
        if depth == 0 and kind is None:
            if t in BRACED_ITEMS or t == "{":  # `#[cfg(test)] { ... }` is a block too
                kind = "braced"
            elif t in SEMICOLON_ITEMS or (t == "const" and toks[j + 1][0] not in FN_QUALIFIERS):
                kind = "statement"
        if t in OPEN:
            depth += 1
        elif t in CLOSE:
            depth -= 1
            if depth < 0:
                return j
            if depth == 0 and t == "}" and kind == "braced":
                return j + 1
        elif depth == 0 and (t == ";" or (t == "," and kind is None)):
            return j + 1
    return len(toks) - 1


def use_tree(toks, i, prefix):
    """Reads the use tree at toks[i] (`a::{b, c::{self, D as E}}`): (leaves, next index).

    A leaf is (segments, line): the whole path it imports, `a::self` and `a::*` as `a`.
    """
    path, leaves = list(prefix), []
    while True:
        t, line = toks[i]
        if t == "{":
            i += 1
            while toks[i][0] not in ("}", "<eof>"):
                start = i
                sub, i = use_tree(toks, i, path)
                leaves += sub
                i += toks[i][0] == "," or i == start  # always move on, even past nonsense
            return leaves, i + 1
        if t == "*":
            return leaves + [(path, line)], i + 1
        if not is_word(t):
            return leaves, i
        path.append(t)
        i += 1 + 2 * (toks[i + 1][0] == "as")  # a rename changes nothing of what is used
        if toks[i][0] != "::":
            return leaves + [(path[:-1] if path[1:] and path[-1] == "self" else path, line)], i
        i += 1


def read_module(path, module):
    """The uses in one file: (uses, inline modules, test-only modules).

    A use is (module, segments, line, text), `module` being the inline `mod name { ... }`
    it sits in, if any. `#![cfg(test)]` at the top makes the whole file a test module.
    """
    with open(path, encoding="utf-8") as f:
        toks = tokens(f.read())
    uses, inline, tests = [], [], []
    scopes = [(module, -1)]  # (module, brace depth that closes it)
    depth, i = 0, 0
    while toks[i][0] != "<eof>":
        t, line = toks[i]
        here, inner = scopes[-1][0], toks[i + 1][0] == "!"
        if t == "#" and toks[i + 1 + inner][0] == "[":
            end = closing(toks, i + 1 + inner)
            if TEST_CFG.match("".join(tok for tok, _ in toks[i + 2 + inner : end])):
                if inner and len(scopes) == 1:
                    return [], [], [module]
                start = end + 1
                while toks[start][0] == "#":  # the item's other attributes
                    start = closing(toks, start + 1) + 1
                end = item_end(toks, start)
                item = [tok for tok, _ in toks[start:end]]
                if "mod" in item:  # its file (and folder) is test code as well
                    tests.append(here + (item[item.index("mod") + 1],))
                i = end
                continue
        if t == "mod" and toks[i + 2][0] == "{":
            scopes.append((here + (toks[i + 1][0],), depth))
            inline.append(scopes[-1][0])
        elif t == "{":
            depth += 1
        elif t == "}":
            depth -= 1
            if depth == scopes[-1][1]:
                scopes.pop()
        elif t == "use" and (toks[i + 1][0] in ("::", "{") or is_word(toks[i + 1][0])):
            leaves, i = use_tree(toks, i + 1 + (toks[i + 1][0] == "::"), [])
            uses += [(here, s, n, "use " + "::".join(s)) for s, n in leaves if s[0] in PATH_HEADS]
            continue
        elif t in PATH_HEADS and toks[i + 1][0] == "::" and toks[i - 1][0] != "::":
            segments = [t]
            while toks[i + 1][0] == "::" and is_word(toks[i + 2][0]):
                segments.append(toks[i + 2][0])
                i += 2
            uses.append((here, segments, line, "::".join(segments)))
        i += 1
    return uses, inline, tests


def resolve(modules, module, segments):
    """The module a path used in `module` lands in: the longest module its path names."""
    base, rest = (() if segments[0] == "crate" else module), list(segments)
    if rest[0] in ("crate", "self"):
        rest = rest[1:]
    while rest and rest[0] == "super":
        base, rest = base[:-1], rest[1:]
    full = base + tuple(rest)
    return next(full[:n] for n in range(len(full), -1, -1) if full[:n] in modules or n == 0)


def crate_modules(src):
    """The modules of the crate at `src` (a set of paths, () the root) and their uses.

    A use is (module, segments, "file:line", text); test modules and their uses are left out.
    """
    modules, uses, tests = set(), [], set()
    for folder, dirs, names in os.walk(src):
        dirs.sort()
        for name in sorted(n for n in names if n.endswith(".rs")):
            path = os.path.join(folder, name)
            parts = tuple(os.path.relpath(path, src)[:-3].split(os.sep))
            if parts[-1] == "mod" or (len(parts) == 1 and parts[0] in ("lib", "main")):
                parts = parts[:-1]
            found, inline, test_mods = read_module(path, parts)
            modules.update([parts] + inline)
            tests.update(test_mods)
            uses += [(m, s, f"{path}:{n}", text) for m, s, n, text in found]
    modules = {m for m in modules if not any(m[:n] in tests for n in range(1, len(m) + 1))}
    return modules, [u for u in uses if u[0] in modules]


def crate_circles(src):
    """(modules, circles) of the crate at `src`.

    A circle is (parent, sibling group, {(a, b): {"file:line": [text, ...]}}): a strongly
    connected group of `parent`'s children and, per edge inside it, the uses that make it.
    """
    modules, uses = crate_modules(src)
    edges = defaultdict(lambda: defaultdict(list))  # (sibling, sibling) -> where -> texts
    for module, segments, where, text in uses:
        target = resolve(modules, module, segments)
        n = 0
        while n < min(len(module), len(target)) and module[n] == target[n]:
            n += 1
        if n < len(module) and n < len(target):  # neither holds the other: siblings
            edges[(module[: n + 1], target[: n + 1])][where].append(text)
    graph, reach = defaultdict(set), {}
    for a, b in edges:
        graph[a].add(b)
    for start in list(graph):
        seen, todo = set(), [start]
        while todo:
            new = graph.get(todo.pop(), set()) - seen
            seen |= new
            todo += new
        reach[start] = seen
    # A module's group: the siblings it reaches that reach it back.
    groups = {frozenset({n} | {m for m in reach[n] if n in reach.get(m, ())}) for n in reach}
    circles = []
    for group in sorted(sorted(g) for g in groups if len(g) > 1):
        inside = {e: edges[e] for e in sorted(edges) if e[0] in group and e[1] in group}
        circles.append((group[0][:-1], group, inside))
    return modules, circles


def merged(texts):
    """`use a::b::{C, D}` for the uses `use a::b::C` and `use a::b::D` of one line."""
    heads = {t.rsplit("::", 1)[0] for t in texts}
    if len(texts) == 1 or len(heads) > 1:
        return "; ".join(texts)
    return f"{heads.pop()}::{{{', '.join(t.rsplit('::', 1)[1] for t in texts)}}}"


def main(dirs):
    if not dirs or not all(os.path.isdir(d) for d in dirs):
        print(__doc__.strip().splitlines()[-1], file=sys.stderr)
        return 2
    count, found = 0, False
    for src in dirs:
        modules, circles = crate_circles(src)
        count += len(modules)
        full = os.path.normpath(os.path.abspath(src))  # `viewer/src` is crate `viewer`
        name = os.path.basename(os.path.dirname(full) if full.endswith(os.sep + "src") else full)
        for parent, group, edges in circles:
            found = True
            under = "::".join(parent) or "the crate root"
            print(f"{name}: circle of {len(group)} modules under {under}: "
                  + ", ".join(m[-1] for m in group))
            for (a, b), used in edges.items():
                print(f"  {name}: {'::'.join(a)} -> {'::'.join(b)}")
                for where, texts in used.items():
                    print(f"      {where}: {merged(texts)}")
    if not found:
        print(f"no import circles in {len(dirs)} crates ({count} modules)")
    return 1 if found else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
