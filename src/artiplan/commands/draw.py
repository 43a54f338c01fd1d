"""``artiplan draw CONFIG.json [--target TARGET.json] -o out.png``: the object in 3D."""

from __future__ import annotations

import argparse
from pathlib import Path

from artiplan.errors import InputError
from artiplan.model import load_configuration


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("config", type=Path, help="configuration (JSON)")
    parser.add_argument("--target", type=Path, help="target configuration, drawn as a ghost")
    parser.add_argument("--title", help="figure title")
    parser.add_argument(
        "-o", "--out", type=Path, default=Path("configuration.png"), help="PNG to write"
    )


def run(args: argparse.Namespace) -> int:
    from artiplan.viz.draw import draw_configuration

    conf, obj = load_configuration(args.config)
    target = None
    if args.target is not None:
        target, tobj = load_configuration(args.target)
        if tobj.n_links != obj.n_links:
            raise InputError(f"{args.target}: {tobj.n_links} links, {args.config}: {obj.n_links}")
    path = draw_configuration(obj, conf, args.out, target=target, title=args.title)
    print(f"wrote {path}")
    return 0
