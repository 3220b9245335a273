"""Tests of tools/import_cycles.py on the small fake crates in fixtures/.

Run from the repository root with `python3 -m unittest discover -s tools/tests`, or as
`python3 tools/tests/test_import_cycles.py`.
"""
import glob
import os
import subprocess
import sys
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
TOOLS = os.path.dirname(HERE)
REPO = os.path.dirname(TOOLS)
SCRIPT = os.path.join(TOOLS, "import_cycles.py")
sys.path.insert(0, TOOLS)

import import_cycles  # noqa: E402  (found through the path set just above)


def fixture(name):
    return os.path.join(HERE, "fixtures", name, "src")


def groups(name):
    """The circles found in a fixture crate, each as its sorted module names ("a::b")."""
    _, circles = import_cycles.crate_circles(fixture(name))
    return [["::".join(m) for m in group] for _, group, _ in circles]


def edges(name):
    """{(user, used): {"file:line": [text, ...]}} over every circle of a fixture crate."""
    _, circles = import_cycles.crate_circles(fixture(name))
    src = fixture(name)
    return {
        ("::".join(a), "::".join(b)): {os.path.relpath(w, src): t for w, t in uses.items()}
        for _, _, circle_edges in circles
        for (a, b), uses in circle_edges.items()
    }


def run(*dirs):
    return subprocess.run(
        [sys.executable, SCRIPT, *dirs], capture_output=True, text=True, cwd=REPO, timeout=120
    )


class Circles(unittest.TestCase):
    def test_grouped_import_circle_is_found(self):
        # scene -> cells only through `pub(crate) use crate::{ cells::{ Cells as Grid, self } }`
        # over several lines, cells -> scene only through `use super::{scene::{self as sc, ..}}`.
        self.assertEqual(groups("grouped"), [["cells", "scene"]])
        found = edges("grouped")
        self.assertEqual(set(found), {("cells", "scene"), ("scene", "cells")})
        self.assertEqual(found[("scene", "cells")]["scene.rs:3"], ["use crate::cells::Cells"])
        self.assertEqual(found[("scene", "cells")]["scene.rs:4"], ["use crate::cells"])

    def test_grouped_import_of_two_siblings_is_read(self):
        # window uses both through `use crate::{scene::Scene, cells::{Cell, Cells}};` but is
        # used by neither: it reaches the circle without being part of it.
        _, uses = import_cycles.crate_modules(fixture("grouped"))
        window = sorted(text for module, _, _, text in uses if module == ("window",))
        self.assertEqual(
            window,
            ["use crate::cells::Cell", "use crate::cells::Cells", "use crate::scene::Scene"],
        )

    def test_circle_after_a_cfg_test_impl_is_found(self):
        self.assertEqual(groups("cfg_test_impl"), [["turntable", "world"]])
        self.assertEqual(
            edges("cfg_test_impl")[("world", "turntable")],
            {"world.rs:22": ["crate::turntable::patches"]},
        )

    def test_back_edge_only_in_test_code_is_not_a_circle(self):
        # `#[cfg(test)]` on a use, a fn, `mod tests { ... }` and `mod helper;` (a file), and
        # `#![cfg(test)]` atop b/checks.rs.
        self.assertEqual(groups("tests_only"), [])
        modules, _ = import_cycles.crate_modules(fixture("tests_only"))
        self.assertEqual(modules, {(), ("a",), ("b",)})

    def test_back_edge_only_in_comments_and_strings_is_not_a_circle(self):
        self.assertEqual(groups("comments_only"), [])
        _, uses = import_cycles.crate_modules(fixture("comments_only"))
        self.assertEqual([text for module, _, _, text in uses if module == ("b",)], [])

    def test_child_using_its_parent_is_not_a_circle(self):
        self.assertEqual(groups("parent_child"), [])

    def test_three_module_circle_is_one_group(self):
        # a -> b by an expression path, b -> c by `use super::c`, c -> a through a::deep.
        self.assertEqual(groups("three"), [["a", "b", "c"]])
        self.assertEqual(set(edges("three")), {("a", "b"), ("b", "c"), ("c", "a")})

    def test_circle_between_nested_siblings_names_their_parent(self):
        _, circles = import_cycles.crate_circles(fixture("nested"))
        self.assertEqual(
            [(parent, group) for parent, group, _ in circles],
            [(("engine",), [("engine", "block"), ("engine", "compile")])],
        )

    def test_circle_between_inline_modules_is_found(self):
        self.assertEqual(groups("inline"), [["a", "b"]])


class Tokens(unittest.TestCase):
    def words(self, text):
        return [tok for tok, _ in import_cycles.tokens(text) if tok != "<eof>"]

    def test_char_quote_does_not_open_a_string(self):
        self.assertEqual(
            self.words("let q = '\"'; crate::a"), ["let", "q", "=", '""', ";", "crate", "::", "a"]
        )

    def test_lifetimes_and_nested_comments(self):
        self.assertEqual(self.words("&'a str /* x /* y */ crate::b */ 'b'"), ["&", "str", '""'])

    def test_lines_are_counted_through_comments_and_strings(self):
        toks = import_cycles.tokens('/* a\n b */ "c\nd"\n// e\nx')
        self.assertEqual(toks[:2], [('""', 2), ("x", 5)])


class CommandLine(unittest.TestCase):
    def test_exit_status_is_1_with_a_circle(self):
        result = run(fixture("grouped"))
        self.assertEqual(result.returncode, 1, result.stderr)
        self.assertIn("grouped: cells -> scene", result.stdout)
        self.assertIn("grouped/src/cells.rs:3: use super::scene", result.stdout)

    def test_exit_status_is_0_without_circles(self):
        result = run(fixture("parent_child"), fixture("tests_only"), fixture("comments_only"))
        self.assertEqual(result.returncode, 0, result.stdout + result.stderr)
        self.assertEqual(result.stdout, "no import circles in 3 crates (10 modules)\n")

    def test_usage_without_crates(self):
        self.assertEqual(run().returncode, 2)

    def test_runs_on_the_real_repository(self):
        crates = sorted(glob.glob(os.path.join(REPO, "*", "src")))
        if not crates:
            self.skipTest("no */src next to tools/")
        result = run(*[os.path.relpath(c, REPO) for c in crates])
        self.assertIn(result.returncode, (0, 1), result.stderr)
        self.assertEqual(result.stderr, "")


if __name__ == "__main__":
    unittest.main()
