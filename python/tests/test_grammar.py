"""Grammars: text in each dialect, files, presets, derivation, and mistakes with their place."""

import pytest

import sylva


def test_a_grammar_derives_its_word():
    g = sylva.Grammar("axiom: A\nA -> F[+A][-A]")
    assert g.dialect == "sylva"
    assert g.generations == 4
    assert g.derive(1) == "F[+A][-A]"
    assert g.derive(2) == "F[+F[+A][-A]][-F[+A][-A]]"
    assert sylva.Grammar(str(g)).derive(3) == g.derive(3)


def test_cpfg_text_names_its_derivation_length_and_degrees():
    g = sylva.Grammar(
        "#define STEPS 3\nLsystem: 1\nderivation length: STEPS\nAxiom: A(0)\n"
        "A(n) : n < 2 --> F(sin(90)) [+A(n+1)] A(n+1)\nA(n) : n >= 2 --> *\nendlsystem",
    )
    assert g.dialect == "cpfg"
    assert g.generations == 3
    assert g.derive() == "F(1)[+F(1)[+]]F(1)[+]"


def test_a_stochastic_grammar_is_a_function_of_its_seed():
    g = sylva.Grammar("axiom: A\nA -> AB : 1\nA -> AC : 1")
    words = {g.derive(8, seed=s) for s in range(8)}
    assert len(words) > 1
    assert g.derive(8, seed=3) == g.derive(8, seed=3)


def test_a_mistake_names_its_line_and_column():
    with pytest.raises(sylva.ParseError) as caught:
        sylva.Grammar("axiom: A\nA -> B(1,")
    e = caught.value
    assert (e.line, e.column, e.path) == (2, 10, None)
    assert "expected" in e.reason
    assert str(e).startswith("line 2, column 10")
    assert isinstance(e, sylva.SylvaError)


def test_a_file_mistake_names_the_file(tmp_path):
    path = tmp_path / "broken.lsys"
    path.write_text("axiom: A\nA -> B(")
    with pytest.raises(sylva.ParseError) as caught:
        sylva.Grammar.from_file(path)
    assert caught.value.path == str(path)
    assert (caught.value.line, caught.value.column) == (2, 8)


def test_a_vlab_model_folder_reads_its_includes(tmp_path):
    (tmp_path / "constants.h").write_text("#define STEPS 3\n#define ANGLE 30\n")
    (tmp_path / "plant.l").write_text(
        '#include "constants.h"\nLsystem: 1\nderivation length: STEPS\naxiom: A\n'
        "A --> F[+(ANGLE)A]A\nendlsystem\n"
    )
    g = sylva.Grammar.from_file(tmp_path)
    assert g.generations == 3
    assert g.derive(1) == "F[+(30)A]A"


def test_presets_and_unknown_names():
    assert "abop-1.24a" in sylva.presets()
    g = sylva.Grammar.preset("abop-1.24a")
    assert "preset" in repr(g)
    assert len(g.derive(2)) > 10
    with pytest.raises(sylva.SylvaError, match="no preset"):
        sylva.Grammar.preset("baobab")
    with pytest.raises(sylva.SylvaError, match="dialect"):
        sylva.Grammar("axiom: A", dialect="fortran")


def test_a_runaway_derivation_is_refused_not_fatal():
    g = sylva.Grammar("axiom: A\nA -> AAAA")
    with pytest.raises(sylva.SylvaError):
        g.derive(40)
