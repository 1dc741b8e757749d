"""Helpers shared by the plot kinds: reading clearjoint CSV files (with '# units:' lines)."""
import csv


def read_table(path):
    """Returns (columns, units, rows as dict of lists of float) from a clearjoint CSV."""
    columns, units, data = None, None, None
    with open(path) as f:
        for line in f:
            s = line.strip()
            if not s:
                continue
            if s.startswith("#"):
                c = s[1:].strip()
                if c.startswith("units:"):
                    units = [u.strip() for u in c[6:].split(",")]
                continue
            fields = [x.strip() for x in s.split(",")] if "," in s else s.split()
            if columns is None:
                columns = fields
                data = {c: [] for c in columns}
                continue
            for c, v in zip(columns, fields):
                data[c].append(float(v))
    if columns is None:
        raise ValueError(f"{path}: no header line")
    if units is None:
        units = [""] * len(columns)
    return columns, dict(zip(columns, units)), data
