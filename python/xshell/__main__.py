"""python3 -m xshell relax CONFIG.json [--solver S] [--out DIR] [--init STATE.json]
[--quiet | --verbose]: the command line's `xshell relax` through the Python
module, with its outputs, its messages on stderr and its exit statuses
(README, "Exit statuses"). Ctrl-C stops the solve at its next iteration,
writes the interrupted run's outputs and exits with status 130."""

import argparse
import sys

from . import _core, _run


def main(argv=None):
    parser = argparse.ArgumentParser(prog="python3 -m xshell", description=__doc__)
    commands = parser.add_subparsers(dest="command", required=True)
    relax = commands.add_parser("relax", help="Find the static equilibrium of a linkage")
    relax.add_argument("config", help="Configuration (JSON)")
    relax.add_argument("--solver", help="newton | dynamics | kinetic-damping")
    relax.add_argument("--out", help="Output directory (overrides output.directory)")
    relax.add_argument("--init", help="Start from a state.json written by an earlier run")
    relax.add_argument("--quiet", action="store_true", help="No progress lines")
    relax.add_argument("--verbose", action="store_true", help="Progress lines always")
    args = parser.parse_args(argv)
    lines = "off" if args.quiet else "on" if args.verbose else "auto"
    try:
        status, error, summary, _ = _run(
            args.config, args.solver, True, args.out, args.init, None, lines, log=True
        )
    except KeyboardInterrupt:
        print("xshell: interrupted", file=sys.stderr)
        return _core.EXIT_INTERRUPTED
    if error:
        print("xshell: error: " + error, file=sys.stderr)
    elif summary is not None:
        import json

        s = json.loads(summary)
        print(
            "xshell: %s after %d %s: %s; energy %.10e"
            % (
                s["status"],
                s["iterations"],
                "steps" if s["solver"] == "dynamics" else "iterations",
                s["reason"],
                s["energy"]["total"],
            ),
            file=sys.stderr,
        )
    return status


if __name__ == "__main__":
    sys.exit(main())
