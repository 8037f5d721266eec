"""Shared fixtures: the repository's examples and the `pounding` binary of the same sources.

The binary is `$POUNDING_BIN` (set by .ci/run), else `target/release/pounding` of the
repository. Under CI (`CI=true`) a missing binary fails the tests that need it; elsewhere they
are skipped with the reason.
"""

from __future__ import annotations

import os
import subprocess
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[2]
EXAMPLES = REPO / "examples"


def _binary() -> Path | None:
    env = os.environ.get("POUNDING_BIN")
    p = Path(env) if env else REPO / "target" / "release" / "pounding"
    return p if p.is_file() and os.access(p, os.X_OK) else None


@pytest.fixture(scope="session")
def examples() -> Path:
    return EXAMPLES


@pytest.fixture(scope="session")
def cli():
    """Run the `pounding` binary: cli(*args) -> CompletedProcess (text)."""
    exe = _binary()
    if exe is None:
        msg = "no pounding binary: set POUNDING_BIN or build it with `cargo build --release`"
        if os.environ.get("CI") == "true":
            pytest.fail(msg)
        pytest.skip(msg)

    def run(*args: object) -> subprocess.CompletedProcess[str]:
        return subprocess.run(
            [str(exe), *map(str, args)], capture_output=True, text=True, timeout=600
        )

    return run


def need(module: str):
    """Import an optional dependency of a test (pandas, dask.distributed): skipped without it,
    except under CI (`CI=true`), where its absence is a failure."""
    if os.environ.get("CI") == "true":
        import importlib

        return importlib.import_module(module)
    return pytest.importorskip(module)
