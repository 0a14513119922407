"""Command line: ``hypercontact run SCENE [--out DIR] [--set key=value ...]``.

Exit codes: 0 completed, 2 invalid scene, 3 a load step failed (converged
steps are on disk), 130 interrupted (Ctrl-C; converged steps are on disk).
"""
import argparse
import sys

from . import scene as scene_mod


def _parser():
    p = argparse.ArgumentParser(prog="hypercontact", description=__doc__.splitlines()[0])
    sub = p.add_subparsers(dest="command", required=True)
    run = sub.add_parser("run", help="run a scene")
    check = sub.add_parser("check", help="validate a scene without running it")
    for q in (run, check):
        q.add_argument("scene", help="scene file (TOML)")
        q.add_argument("--set", dest="overrides", action="append", default=[], metavar="KEY=VALUE",
                       help="override a scene value, e.g. --set mesh.n=32 (repeatable)")
    run.add_argument("--out", help="results folder (default: the scene's output.dir)")
    return p


def main(argv=None):
    args = _parser().parse_args(argv)
    import logging

    logging.getLogger().setLevel(logging.WARNING)  # FFCx's JIT logs every compilation at INFO
    from mpi4py import MPI

    comm = MPI.COMM_WORLD
    err = sys.stderr if comm.rank == 0 else open("/dev/null", "w")
    try:
        sc = scene_mod.load(args.scene, args.overrides)
        if args.command == "check":
            if comm.rank == 0:
                print(f"{args.scene}: valid")
            return 0
        from .simulation import Simulation, StepFailure

        sim = Simulation(sc, comm)
        try:
            writer = sim.run(args.out)
        except StepFailure as failure:
            print(f"hypercontact: {failure}", file=err)
            return 3
        except KeyboardInterrupt:
            print("hypercontact: interrupted; converged steps are on disk", file=err)
            return 130
        if comm.rank == 0:
            print(f"hypercontact: completed {len(writer.steps)} steps; results in {writer.out}")
        return 0
    except scene_mod.SceneError as e:
        print(f"hypercontact: invalid scene: {e}", file=err)
        return 2
    except FileNotFoundError as e:
        print(f"hypercontact: {e}", file=err)
        return 2
    except ValueError as e:
        print(f"hypercontact: {e}", file=err)
        return 2


if __name__ == "__main__":
    sys.exit(main())
