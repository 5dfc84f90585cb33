"""The seed's cantilever Tables 2-6 (references/data/seed_cantilever_tables.csv,
copied from shared/reference/): published values by table, case, load and nu."""
import csv
from pathlib import Path

CSV = Path(__file__).resolve().parent / "data" / "seed_cantilever_tables.csv"
COLUMNS = ("abaqus_b32", "ancf_full", "ancf_deficient", "gef")


def rows():
    with open(CSV, newline="") as fh:
        lines = [l for l in fh if not l.startswith("#")]
    header = ["table", "case", "load", "nu", "elements", "quantity", "unit"] + list(COLUMNS)
    out = []
    for r in csv.reader(lines):
        d = dict(zip(header, r))
        for c in COLUMNS:
            d[c] = float(d[c]) if d[c] else None
        d["table"] = int(d["table"])
        d["nu"] = float(d["nu"])
        d["elements"] = int(d["elements"]) if d["elements"] else None
        out.append(d)
    return out


def value(table, load, nu, quantity, column, elements=None):
    for d in rows():
        if (d["table"] == table and d["load"] == load and d["nu"] == nu and d["quantity"] == quantity
                and (elements is None or d["elements"] == elements)):
            return d[column]
    raise KeyError((table, load, nu, quantity, elements))
