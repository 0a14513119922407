import sys
from pathlib import Path

import pytest
from mpi4py import MPI

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(Path(__file__).resolve().parent))  # tests/reference


@pytest.fixture
def scenes_dir():
    return ROOT / "scenes"


@pytest.fixture
def out_dir(tmp_path_factory):
    """A results folder shared by all ranks."""
    comm = MPI.COMM_WORLD
    path = tmp_path_factory.mktemp("run") if comm.rank == 0 else None
    return Path(comm.bcast(str(path) if path else None, root=0))


def quiet(*args, **kwargs):
    pass


def pytest_configure(config):
    """Under mpirun each rank gets its own pytest temporary folder, so that
    ranks never race on creating or cleaning it; shared folders are made by
    rank 0 and broadcast (see ``out_dir``)."""
    comm = MPI.COMM_WORLD
    if comm.size > 1 and not config.option.basetemp:
        config.option.basetemp = f"/tmp/hypercontact-pytest-np{comm.size}-rank{comm.rank}"
