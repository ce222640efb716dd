# SPDX-License-Identifier: GPL-3.0-or-later
# Where the pytest suite of `import sonargrid` finds the CLI and the bundled datasets: ctest sets
# SONARGRID_CLI and SONARGRID_DATASETS (tests/CMakeLists.txt); run by hand, the defaults are the
# source tree's datasets and build/app/cli/sonargrid-cli.
import json
import os
import pathlib
import subprocess

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]


@pytest.fixture(scope="session")
def datasets():
    return pathlib.Path(os.environ.get("SONARGRID_DATASETS", ROOT / "datasets"))


@pytest.fixture(scope="session")
def cli():
    path = os.environ.get("SONARGRID_CLI", str(ROOT / "build" / "app" / "cli" / "sonargrid-cli"))

    def run(*args, json_output=True):
        out = subprocess.run([path, *map(str, args)], check=True, capture_output=True, text=True)
        return json.loads(out.stdout) if json_output else out.stdout

    return run


@pytest.fixture(scope="session")
def room(datasets):
    import sonargrid

    return sonargrid.read_log(datasets / "room" / "room.sglog")
