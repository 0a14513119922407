"""Checkpoint files on their own: what is saved is what is loaded, a write
is atomic, and a missing checkpoint names the folder and the rank count."""
import numpy as np
import pytest
from mpi4py import MPI

from hypercontact.solve.checkpoint import Checkpoint


def test_round_trip(tmp_path):
    cp = Checkpoint(tmp_path / "checkpoint", MPI.COMM_SELF)
    state = {"lam": 0.25, "dlam": 0.125, "steps": [{"step": 1}], "contacts": {"base": {"law": {}}}}
    w = np.linspace(0.0, 1.0, 7)
    cp.save(state, w=w, **{"base.traction": np.eye(3)})
    loaded, arrays = cp.load()
    assert loaded == state
    assert np.array_equal(arrays["w"], w) and np.array_equal(arrays["base.traction"], np.eye(3))
    assert [p.name for p in (tmp_path / "checkpoint").iterdir()] == ["rank0-of-1.npz"]  # no temporary left


def test_a_second_save_replaces_the_first(tmp_path):
    cp = Checkpoint(tmp_path, MPI.COMM_SELF)
    cp.save({"steps": [1]}, w=np.zeros(2))
    cp.save({"steps": [1, 2]}, w=np.ones(2))
    state, arrays = cp.load()
    assert state["steps"] == [1, 2] and np.array_equal(arrays["w"], np.ones(2))


def test_missing_checkpoint_names_folder_and_ranks(tmp_path):
    with pytest.raises(FileNotFoundError, match=r"no checkpoint for 1 rank\(s\) in '.*nowhere'"):
        Checkpoint(tmp_path / "nowhere", MPI.COMM_SELF).load()
