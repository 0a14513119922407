"""Command line of hypercontact.

    hypercontact run SCENE [--out DIR] [--set KEY=VALUE ...] [--np N] [--resume]
    hypercontact check SCENE [--set KEY=VALUE ...]
    hypercontact scenes          (or: hypercontact list)
    hypercontact study STUDY [--out DIR]

SCENE and STUDY are files or the names of built-in ones (the package data
hypercontact.scenes: the repository's scenes/ and scenes/studies/).

Exit codes: 0 completed, 2 invalid scene, 3 a load step failed (converged
steps are on disk), 130 interrupted (Ctrl-C; converged steps are on disk,
and ``--resume`` continues from the last of them).
"""
import argparse
import logging
import os
import shutil
import signal
import sys

from . import scene as scene_mod

#: The built-in scenes (installed with the package; the repository's scenes/ folder).
SCENES = scene_mod.SCENES


class Console:
    """What a run prints on rank 0: the simulation's lines, and once per
    burst of JIT compilations (a cold form cache) "compiling the forms …"
    closed with the seconds they took when the next line is printed. The
    stream is the stdout of its creation (FFCx redirects sys.stdout while
    it compiles)."""

    def __init__(self, rank=0):
        self.rank, self.seconds, self.open, self.out = rank, 0.0, False, sys.stdout

    def compiling(self):
        if self.rank == 0 and not self.open:
            print("hypercontact: compiling the forms (first run, cached afterwards)…", end="", file=self.out,
                  flush=True)
        self.open = True

    def compiled(self, seconds):
        self.seconds += seconds

    def close(self):
        if self.open and self.rank == 0:
            print(f" {self.seconds:.0f} s", file=self.out, flush=True)
        self.open, self.seconds = False, 0.0

    def say(self, *args, **kwargs):
        self.close()
        if self.rank == 0:
            print(*args, file=self.out, **kwargs)


def console_logging(console):
    """Only warnings of the libraries on the console; the C compiler's lines
    of a cold FFCx cache become the console's "compiling the forms" notice."""
    from . import _dolfinx

    logging.getLogger().setLevel(logging.WARNING)
    _dolfinx.watch_jit_compilation(console)
    return console


def _parser():
    p = argparse.ArgumentParser(prog="hypercontact", description="Hyperelastic bodies in contact.")
    sub = p.add_subparsers(dest="command", required=True)
    run = sub.add_parser("run", help="run a scene")
    check = sub.add_parser("check", help="validate a scene without running it")
    sub.add_parser("scenes", aliases=["list"], help="list the built-in scenes")
    study = sub.add_parser("study", help="run a sweep of settings: error against a reference vs wall time")
    study.add_argument("study", help="a study TOML file or a built-in study name (scenes/studies/)")
    study.add_argument("--out", default=None, help="results folder (default results/study_NAME)")
    for q in (run, check):
        q.add_argument("scene", help="scene file (TOML), or the name of a built-in scene")
        q.add_argument("--set", dest="overrides", action="append", default=[], metavar="KEY=VALUE",
                       help="override a scene value, e.g. --set mesh.n=32 (repeatable)")
    run.add_argument("--out", help="results folder (default: the scene's output.dir)")
    run.add_argument("--np", type=int, default=0, metavar="N", help="run on N MPI processes (mpirun)")
    run.add_argument("--resume", action="store_true",
                     help="continue from the last converged step checkpointed in the results folder")
    return p


def _study(args):
    console = console_logging(Console())
    from . import study as study_mod

    path = scene_mod.study_path(args.study)
    out = args.out or f"results/study_{path.stem}"
    try:
        _, ref = study_mod.run_study(path, out, log=console.say)
    except (scene_mod.SceneError, ValueError) as e:
        print(f"hypercontact: {e}", file=sys.stderr)
        return 2
    finally:  # as in main: the console's stream may close after the study (a caller's captured stdout)
        from . import _dolfinx

        _dolfinx.watch_jit_compilation(None)
    console.say(f"hypercontact: study written to {out} (study.csv, study.md, study.png)")
    return 0


def list_scenes(out=sys.stdout):
    for name, title in scene_mod.builtin.titles():
        print(f"{name:24s} {title}", file=out)


def _under_mpirun(argv, n):
    """Re-run this command under ``mpirun -n N`` (never returns)."""
    mpirun = shutil.which("mpirun")
    if mpirun is None:
        raise SystemExit("hypercontact: --np needs mpirun (Debian package openmpi-bin)")
    args, skip = [], False
    for a in argv:
        if skip:
            skip = False
        elif a == "--np":
            skip = True
        elif not a.startswith("--np="):
            args.append(a)
    cmd = [mpirun, "-n", str(n), "--oversubscribe"]
    if hasattr(os, "geteuid") and os.geteuid() == 0:
        cmd.append("--allow-run-as-root")
    cmd += [sys.executable, "-m", "hypercontact.cli", *args]
    os.execv(mpirun, cmd)


def main(argv=None):
    argv = list(sys.argv[1:] if argv is None else argv)
    args = _parser().parse_args(argv)
    if args.command in ("scenes", "list"):
        list_scenes()
        return 0
    if args.command == "study":
        return _study(args)
    launched = any(v in os.environ for v in ("OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_RANK"))
    if args.command == "run" and args.np > 1 and not launched:
        _under_mpirun(argv, args.np)  # before MPI is initialised here: a singleton cannot exec mpirun
    from mpi4py import MPI

    comm = MPI.COMM_WORLD
    console = Console(comm.rank)
    err = sys.stderr if comm.rank == 0 else open(os.devnull, "w")
    try:
        sc = scene_mod.load(scene_mod.scene_path(args.scene), args.overrides)
        if args.command == "check":
            if comm.rank == 0:
                print(f"{args.scene}: valid")
            return 0
        console_logging(console)
        from petsc4py import PETSc

        from .simulation import Simulation, StepFailure

        # MPI and PETSc install their own SIGINT handlers; Ctrl-C must reach
        # Python as KeyboardInterrupt so the run stops cleanly.
        signal.signal(signal.SIGINT, signal.default_int_handler)
        sim = Simulation(sc, comm, log=console.say)
        try:
            writer = sim.run(args.out, resume=args.resume)
        except StepFailure as failure:
            return _fail(console, err, f"hypercontact: {failure}", 3)
        except PETSc.Error as failure:
            # a PETSc option value that PETSc rejects only when it uses it
            return _fail(console, err, f"hypercontact: invalid scene: scene key 'solver.petsc': PETSc rejected one "
                         f"of {sc['solver']['petsc']} when it used it (error code {failure.ierr}); "
                         f"converged steps are on disk", 2)
        except KeyboardInterrupt:
            return _fail(console, err, "hypercontact: interrupted; converged steps are on disk (--resume continues)", 130)
        console.say(f"hypercontact: completed {len(writer.steps)} steps; results in {writer.out}")
        return 0
    except (scene_mod.SceneError, FileNotFoundError, ValueError) as e:
        prefix = "invalid scene: " if isinstance(e, scene_mod.SceneError) else ""
        return _fail(console, err, f"hypercontact: {prefix}{e}", 2)
    finally:  # the console's stream may close after main (a caller's captured stdout)
        from . import _dolfinx

        _dolfinx.watch_jit_compilation(None)


def _fail(console, err, message, code):
    """Close an open compiling line, print the message on err, return the exit code."""
    console.close()
    print(message, file=err)
    return code


if __name__ == "__main__":
    sys.exit(main())
