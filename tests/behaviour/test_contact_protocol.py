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
    ("punch.toml", ("assemble_rigid_residual",)),
    ("punch_mu0.3_0.toml", ("assemble_rigid_residual", "assemble_rigid_friction_residual")),
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
    frictional = sum(c.frictional for c in sim.contacts)
    assert calls["assemble_rigid_residual"] == len(sim.contacts) * (residuals[0] + steps)
    if "assemble_rigid_friction_residual" in kernels:  # once more in the same evaluation, frictional ones only
        assert frictional == 1 and calls["assemble_rigid_friction_residual"] == residuals[0] + steps
