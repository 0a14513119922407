"""The contact protocol's promise: a Newton iterate evaluates each contact
once — residual, tangent, monitor, commit and results read that evaluation —
and the only further evaluation is the one of each converged state."""
import pytest
from conftest import ROOT, quiet
from mpi4py import MPI

from hypercontact import _cpp, scene
from hypercontact.simulation import Simulation
from hypercontact.solve.newton import Problem


@pytest.mark.parametrize("name, kernels", [
    ("punch.toml", ("evaluate_rigid_contact", "evaluate_rigid_friction")),
    ("punch_mu0.3_0.toml", ("evaluate_rigid_contact", "evaluate_rigid_friction")),
])
def test_one_contact_evaluation_per_residual_and_per_converged_step(tmp_path, monkeypatch, name, kernels):
    sc = scene.load(ROOT / "scenes" / name, ["mesh.n=4", "mesh.m=1", f"output.dir={tmp_path}",
                                              "output.xdmf=false"])
    calls = {k: 0 for k in kernels}
    residuals = [0]
    for k in kernels:
        kernel = getattr(_cpp, k)

        def counted(*args, _k=k, _kernel=kernel, **kwargs):
            calls[_k] += 1
            return _kernel(*args, **kwargs)

        monkeypatch.setattr(_cpp, k, counted)
    residual = Problem.residual

    def counted_residual(self, snes, x, b, with_contacts=True):
        residuals[0] += with_contacts
        return residual(self, snes, x, b, with_contacts)

    monkeypatch.setattr(Problem, "residual", counted_residual)
    sim = Simulation(sc, MPI.COMM_SELF, log=quiet)
    writer = sim.run()
    steps = len(writer.steps)
    assert steps > 1 and residuals[0] > steps
    # per contact one evaluation (frictional contacts: the normal and friction one) per residual
    # callback and one per converged state; the tangent, monitor and output add none
    frictional = sum(c.frictional for c in sim.contacts)
    assert frictional == (1 if "mu0.3" in name else 0)
    assert calls["evaluate_rigid_friction"] == frictional * (residuals[0] + steps)
    assert calls["evaluate_rigid_contact"] == (len(sim.contacts) - frictional) * (residuals[0] + steps)
