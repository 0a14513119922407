"""solver.petsc: PETSc options passed through, checked as far as PETSc can
be asked without solving: option names without '-', scalar values, known
names of the type-selecting options, factorisations MUMPS has."""
import difflib
import functools
import re

from .errors import Invalid, describe
from .fields import is_finite


@functools.lru_cache(maxsize=1)
def petsc_types():
    """Known values of the PETSc options that select a type."""
    try:
        from petsc4py import PETSc
    except ImportError:  # pragma: no cover - petsc4py is a dependency
        return {}

    def names(cls):
        return {v for k, v in vars(cls).items() if not k.startswith("_") and isinstance(v, str)}

    return {
        "ksp_type": names(PETSc.KSP.Type), "pc_type": names(PETSc.PC.Type),
        "snes_type": names(PETSc.SNES.Type), "pc_factor_mat_solver_type": names(PETSc.Mat.SolverType),
        "snes_linesearch_type": {"basic", "bt", "l2", "cp", "nleqerr", "shell"},
    }


def check_petsc_options(options):
    """``options`` (option name without '-' → value) or Invalid naming the option."""
    for key, value in options.items():
        if not re.fullmatch(r"[A-Za-z][A-Za-z0-9_]*", key):
            hint = " (without the leading '-')" if key.startswith("-") else ""
            raise Invalid(f"expected a PETSc option name{hint}", key)
        if not (isinstance(value, (str, bool)) or is_finite(value)):
            raise Invalid(f"expected a string, a finite number or true/false, found {describe(value)}", key)
        types = petsc_types().get(key)
        if types is not None and value not in types:
            close = difflib.get_close_matches(str(value), sorted(types), n=1)
            hint = f"; did you mean '{close[0]}'?" if close else ""
            raise Invalid(f"expected a PETSc {key.replace('_', ' ')}, found {describe(value)}{hint}", key)
    if options.get("pc_type") in ("ilu", "icc") and options.get("pc_factor_mat_solver_type", "mumps") == "mumps":
        raise Invalid(f"{options['pc_type']!r} needs pc_factor_mat_solver_type = \"petsc\" (the default, mumps, has "
                      "no incomplete factorisations)", "pc_type")
    return options
