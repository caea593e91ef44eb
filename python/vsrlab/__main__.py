"""``python -m vsrlab run CONFIG --out DIR [--ray ADDRESS] [--resume] [--solver S]``: an experiment from Python,
its evaluations optionally on a Ray cluster (docs/cluster.md); ``python -m vsrlab campaign FILES…
--out DIR [--ray ADDRESS] [--resume] [--solver S]``: many files' settings and runs side by side. Every other
command is the ``vsrlab`` binary's."""

from __future__ import annotations

import argparse
import json
import sys

from . import campaign, run


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(prog="python -m vsrlab")
    commands = parser.add_subparsers(dest="command", required=True)
    r = commands.add_parser("run", help="run an experiment file, optionally on a Ray cluster")
    r.add_argument("config", help="experiment file (TOML)")
    r.add_argument("--out", required=True, help="output folder")
    r.add_argument("--ray", metavar="ADDRESS", help="'auto', 'local' or HOST:PORT of a Ray cluster")
    r.add_argument("--resume", action="store_true", help="continue from the checkpoints")
    r.add_argument("--threads", type=int, default=0, help="local worker threads (0: every core)")
    r.add_argument("--quiet", action="store_true", help="no progress lines")
    r.add_argument("--solver", help="2D physics solver replacing the files': soft-substeps or sequential-impulses")
    c = commands.add_parser("campaign", help="run many experiment files side by side, optionally on Ray")
    c.add_argument("files", nargs="+", help="experiment files (TOML); a sweep gives each setting")
    c.add_argument("--out", required=True, help="output folder: one folder per setting in it")
    c.add_argument("--ray", metavar="ADDRESS", help="'auto', 'local' or HOST:PORT of a Ray cluster")
    c.add_argument("--resume", action="store_true", help="continue every unfinished run")
    c.add_argument("--threads", type=int, default=0, help="local worker threads (0: every core)")
    c.add_argument("--quiet", action="store_true", help="no progress lines")
    c.add_argument("--solver", help="2D physics solver replacing the files': soft-substeps or sequential-impulses")
    args = parser.parse_args(argv)
    options = dict(resume=args.resume, threads=args.threads, ray=args.ray, verbose=not args.quiet, solver=args.solver)
    try:
        if args.command == "campaign":
            print(campaign(args.files, args.out, **options)["table"], end="")
            return 0
        summaries = run(args.config, args.out, **options)
    except ValueError as e:
        print(f"error: {e}", file=sys.stderr)
        return 1
    for s in summaries:
        print(json.dumps({k: s[k] for k in ("run", "evaluations", "best_fitness", "stop_reason") if k in s}))
    return 0


if __name__ == "__main__":
    sys.exit(main())
