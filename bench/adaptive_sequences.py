"""The file of adaptive sequences fe_stage measured (tests/data/fe/adaptive_sequences.txt; its
header gives the format), read for bench/measure_presets.py (the recorded reference intervals)
and bench/adaptive_estimate_table.py (the meshes and their forces). Strict: the figures quoted
come from here, so a malformed line is an error naming the file and the line, not a block
skipped."""
import math

SEQUENCE_KEYS = ("sequence", "journal", "source", "reference", "checked", "mesh", "end")


class SequenceFileError(Exception):
    pass


def read_sequences(path):
    """The blocks, in the file's order: name → {name, line, journal, source, reference:
    (F_low, F_high), checked, N: [DoFs], F: [N]}."""
    seqs, cur = {}, None
    with open(path) as f:
        for number, raw in enumerate(f, 1):
            line = raw.strip()
            if not line or line.startswith("#"):
                continue
            key, _, rest = line.partition(" ")
            rest = rest.strip()
            at = f"{path}:{number}"
            if key not in SEQUENCE_KEYS:
                raise SequenceFileError(f"{at}: unknown key '{key}' (allowed: {', '.join(SEQUENCE_KEYS)})")
            if key == "sequence":
                if cur is not None:
                    raise SequenceFileError(f"{at}: 'sequence' before the 'end' of '{cur['name']}' "
                                            f"(line {cur['line']})")
                if not rest:
                    raise SequenceFileError(f"{at}: 'sequence' without a name")
                cur = {"name": rest, "line": number, "checked": 0, "N": [], "F": []}
                continue
            if cur is None:
                raise SequenceFileError(f"{at}: '{key}' outside a sequence block")
            if key == "end":
                if "reference" not in cur:
                    raise SequenceFileError(f"{path}: sequence '{cur['name']}' (line {cur['line']}) "
                                            f"has no 'reference F_low F_high' line")
                if cur["name"] in seqs:
                    raise SequenceFileError(f"{path}: sequence '{cur['name']}' (line {cur['line']}) "
                                            f"twice (first at line {seqs[cur['name']]['line']})")
                seqs[cur["name"]] = cur
                cur = None
            elif key == "reference":
                try:
                    lo, hi = (float(x) for x in rest.split())
                except ValueError:
                    raise SequenceFileError(f"{at}: 'reference {rest}': expected two numbers, F_low F_high [N]")
                if not (math.isfinite(lo) and math.isfinite(hi) and 0 < lo <= hi):
                    raise SequenceFileError(f"{at}: 'reference {rest}': expected 0 < F_low <= F_high [N]")
                cur["reference"] = (lo, hi)
            elif key == "journal":
                if rest not in ("rigid", "deformable"):
                    raise SequenceFileError(f"{at}: journal '{rest}' (allowed: rigid, deformable)")
                cur["journal"] = rest
            elif key == "mesh":
                try:
                    n, force = (float(x) for x in rest.split())
                except ValueError:
                    raise SequenceFileError(f"{at}: 'mesh {rest}': expected two numbers, DoFs and F [N]")
                cur["N"].append(n)
                cur["F"].append(force)
            elif key == "checked":
                try:
                    cur["checked"] = int(rest)
                except ValueError:
                    raise SequenceFileError(f"{at}: 'checked {rest}': expected a whole number")
            else:  # source
                cur["source"] = rest
    if cur is not None:
        raise SequenceFileError(f"{path}: sequence '{cur['name']}' (line {cur['line']}) has no 'end'")
    return seqs
