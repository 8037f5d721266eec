"""The text reports from Python are the command line's, character for character: each is one
library function that both call (`pounding run`'s summary, `modes`, `separation`, `laws`)."""

from __future__ import annotations

from pathlib import Path

import pytest

import pounding

SCENARIOS = ["paper-c.toml", "two-levels.toml", "shear-buildings.toml", "yielding-frames.toml"]


@pytest.mark.parametrize("name", SCENARIOS)
def test_summary_text_is_what_run_prints(cli, examples: Path, tmp_path: Path, name: str) -> None:
    p = cli("run", examples / name, "--out", tmp_path, "--no-plot", "--no-check")
    assert p.returncode == 0, p.stderr
    res = pounding.run(pounding.Scenario.from_file(examples / name), check=False)
    text = res.summary_text()
    # the command line prints the summary, a blank line, then the files it wrote
    assert p.stdout.startswith(text + "\nwrote "), (text, p.stdout)
    assert text.splitlines()[1] == f"  scenario: {examples / name}"


@pytest.mark.parametrize("name", SCENARIOS + ["design-spectrum.toml"])
def test_modes_and_separation_text_are_the_cli_tables(cli, examples: Path, name: str) -> None:
    sc = pounding.Scenario.from_file(examples / name)
    modes = cli("modes", examples / name)
    assert modes.returncode == 0, modes.stderr
    assert sc.modes_text() == modes.stdout
    sep = cli("separation", examples / name)
    assert sep.returncode == 0, sep.stderr
    assert sc.separation_text() == sep.stdout


def test_separation_text_takes_the_options_of_the_cli(cli, examples: Path) -> None:
    f = examples / "paper-c.toml"
    spectrum = "asce7:sds=1.0,sd1=0.6,tl=8"
    p = cli("separation", f, "--spectrum", spectrum)
    assert p.returncode == 0, p.stderr
    assert pounding.Scenario.from_file(f).separation_text(spectrum=spectrum) == p.stdout
    # a code the scenario gives no factors for: the command line's message, as ScenarioError
    bad = cli("separation", f, "--code", "asce7")
    assert bad.returncode != 0
    with pytest.raises(pounding.ScenarioError) as e:
        pounding.Scenario.from_file(f).separation_text(codes=["asce7"])
    assert bad.stderr.strip() == f"error: {e.value}"


def test_laws_text_is_the_cli_table(cli) -> None:
    for speed in ("0.5", "2"):
        p = cli("laws", "--speed", speed)
        assert p.returncode == 0, p.stderr
        assert pounding.laws_text(float(speed)) == p.stdout
    assert pounding.laws_text() == pounding.laws_text(0.5)
    with pytest.raises(ValueError):
        pounding.laws_text(-1.0)
