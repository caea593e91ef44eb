#!/usr/bin/env python3
"""Prints an experiment file with some of its values replaced: the harness's reduced copy of a
shipped file (fewer runs and evaluations), everything else exactly as shipped.

    reduce.py FILE KEY=VALUE...

KEY is a dotted path (`runs`, `stop.evaluations`, `genotype.ppo.iterations`): the last part is the
key, the rest its table's header. VALUE is TOML as written in the file; an empty VALUE removes the
key. The edit is made on the text, line by line, so comments, inline tables and sweeps stay as
they are."""
import re
import sys


def header_of(line):
    m = re.match(r"\s*\[([^\[\]]+)\]\s*(#.*)?$", line)
    return m.group(1).strip() if m else None


def replace(lines, table, key, value):
    # the table's lines: from its header (or the top of the file) to the next header
    start = 0
    if table:
        headers = [i for i, l in enumerate(lines) if header_of(l) == table]
        if not headers:
            if value:
                lines.extend(["", f"[{table}]", f"{key} = {value}"])
            return
        start = headers[0] + 1
    end = next((i for i in range(start, len(lines)) if header_of(lines[i]) is not None), len(lines))
    pattern = re.compile(rf"\s*{re.escape(key)}\s*=")
    at = next((i for i in range(start, end) if pattern.match(lines[i])), None)
    if at is not None and value:
        lines[at] = f"{key} = {value}"
    elif at is not None:
        del lines[at]
    elif value:
        lines.insert(start, f"{key} = {value}")


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    lines = open(sys.argv[1], encoding="utf-8").read().split("\n")
    for setting in sys.argv[2:]:
        path, _, value = setting.partition("=")
        table, _, key = path.rpartition(".")
        replace(lines, table, key, value)
    sys.stdout.write("\n".join(lines))


main()
