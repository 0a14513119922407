"""What the Coulomb law keeps over converged steps, with a stand-in history
and kernel states worked by hand: dissipation sums, slip path lengths, stick
↔ slip flips and counts (contact/law.py), no mesh and no kernel."""
from types import SimpleNamespace

import numpy as np
from mpi4py import MPI

from hypercontact.contact import OPEN, SLIP, STICK
from hypercontact.contact.law import Coulomb


class History:
    def __init__(self, n):
        self.traction, self.stored = np.zeros((n, 3)), []

    def store(self, state, x):
        self.stored.append(state)

    def state_dict(self):
        return {}, {"traction": self.traction}

    def load_state_dict(self, meta, arrays):
        self.traction = arrays["traction"]


def state(status, slip, dissipation):
    return SimpleNamespace(state=np.array(status), slip_increment=np.array(slip, dtype=float),
                           dissipation=np.array(dissipation, dtype=float), traction=np.zeros((len(status), 3)))


def test_two_steps_accumulate_and_count_flips():
    law = Coulomb(0.3, 10.0, History(3), MPI.COMM_SELF)
    law.commit(state([STICK, SLIP, OPEN], [[0, 0, 0], [3, 4, 0], [0, 0, 0]], [0.0, 2.0, 0.0]), x=None)
    assert law.flips_step == 0  # from the initial all-open status: no stick ↔ slip flip
    assert law.stick_slip_counts() == (1, 1) and law.dissipation_step == 2.0
    law.commit(state([SLIP, STICK, STICK], [[0, 1, 0], [0, 0, 0], [0, 0, 0]], [0.5, 0.0, 0.0]), x=None)
    assert law.flips_step == 2  # node 0 stick → slip, node 1 slip → stick; node 2 open → stick is no flip
    assert law.dissipation == 2.5 and law.dissipation_step == 0.5
    assert np.array_equal(law.slip_accumulated, [1.0, 5.0, 0.0])  # |Δs| summed: |(3,4,0)| = 5
    assert np.array_equal(law.dissipation_points, [0.5, 2.0, 0.0])
    assert law.stick_slip_counts() == (2, 1) and len(law.history.stored) == 2
    obs = law.observables()
    assert (obs["stick_nodes"], obs["slip_nodes"], obs["stick_slip_flips"]) == (2, 1, 2)


def test_point_fields_per_unit_area_and_state_round_trip():
    law = Coulomb(0.3, 10.0, History(2), MPI.COMM_SELF)
    law.commit(state([SLIP, STICK], [[1, 0, 0], [0, 0, 0]], [4.0, 0.0]), x=None)
    fields = law.point_fields(np.array([2.0, 1.0]))
    assert np.array_equal(fields["dissipation"], [2.0, 0.0]) and np.array_equal(fields["status"], [2.0, 1.0])
    meta, arrays = law.state_dict()
    other = Coulomb(0.3, 10.0, History(2), MPI.COMM_SELF)
    other.load_state_dict(meta, arrays)
    assert other.dissipation == 4.0 and np.array_equal(other.slip_accumulated, law.slip_accumulated)
    assert np.array_equal(other.status_committed, [SLIP, STICK])
