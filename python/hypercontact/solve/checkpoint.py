"""Checkpoints: the state after the last converged step, so that a run that
was stopped or killed resumes from it (``hypercontact run ... --resume``) and
ends with the same results as an uninterrupted run.

One file per rank (``checkpoint/rank<r>-of-<n>.npz``): the process-local
solution array, the step controller's state and the results so far. A run
resumes on as many ranks as it ran, so that every rank reads back exactly
its own part of the distributed arrays.
"""
import json
import os
from pathlib import Path

import numpy as np
from mpi4py import MPI


class Checkpoint:
    def __init__(self, folder, comm):
        self.folder, self.comm = Path(folder), comm
        self.path = self.folder / f"rank{comm.rank}-of-{comm.size}.npz"

    def save(self, state, **arrays):
        """Write atomically (a kill mid-write leaves the previous checkpoint)."""
        if self.comm.rank == 0:
            self.folder.mkdir(parents=True, exist_ok=True)
        self.comm.barrier()
        tmp = self.path.with_name(self.path.stem + ".tmp.npz")
        np.savez(tmp, state=np.array(json.dumps(state)), **arrays)
        os.replace(tmp, self.path)
        self.comm.barrier()

    def load(self):
        """(state, arrays) of the last checkpoint; FileNotFoundError if none."""
        found = self.comm.allreduce(int(self.path.is_file()), op=MPI.MIN)
        if not found:
            raise FileNotFoundError(
                f"no checkpoint for {self.comm.size} rank(s) in '{self.folder}' to resume from "
                f"(a run resumes in its own results folder, on as many ranks as it ran)")
        with np.load(self.path) as data:
            state = json.loads(str(data["state"]))
            arrays = {k: data[k] for k in data.files if k != "state"}
        steps = self.comm.allgather(len(state["steps"]))
        if min(steps) != max(steps):
            raise ValueError(f"checkpoint files in '{self.folder}' are from different steps {steps}")
        return state, arrays
