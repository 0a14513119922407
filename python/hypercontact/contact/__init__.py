"""Contact: a pair is geometry (rigid obstacle | deformable surface) × law
(frictionless | Coulomb) × enforcement (penalty | augmented Lagrangian) behind
one protocol (:class:`~.pair.Contact`); :func:`~.factory.build_contacts`
makes them from a scene. The C++ kernels are called from :mod:`.kernels` only."""
from .factory import ContactSettings, build_contacts
from .kernels import OPEN, SLIP, STICK
from .pair import Contact

__all__ = ["Contact", "ContactSettings", "build_contacts", "OPEN", "STICK", "SLIP"]
