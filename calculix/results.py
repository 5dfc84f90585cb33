"""Parse ccx's .dat output: *NODE PRINT U blocks -> displacement histories.

A block reads

     displacements (vx,vy,vz) for set S1 and time  0.1000000E+01

             123  1.234567E-03 -2.345678E-05  3.456789E-01

(one line per node of the set).  ccx prints a block per converged increment.
"""
import re
from pathlib import Path

HEADER = re.compile(r"^\s*displacements \(vx,vy,vz\) for set (\S+) and time\s+(\S+)\s*$")


def read_dat(path):
    """{set name: {node id: [(time, [ux, uy, uz]), ...]}} from a .dat file."""
    out = {}
    cur = None
    for line in Path(path).read_text(encoding="utf-8", errors="replace").splitlines():
        m = HEADER.match(line)
        if m:
            cur = (m.group(1).upper(), float(m.group(2)))
            out.setdefault(cur[0], {})
            continue
        parts = line.split()
        if cur is None or not parts:
            continue
        if len(parts) == 4 and parts[0].isdigit():
            try:
                u = [float(x) for x in parts[1:]]
            except ValueError:
                cur = None
                continue
            out[cur[0]].setdefault(int(parts[0]), []).append((cur[1], u))
        else:
            cur = None                      # another kind of block
    return out


def history(path, nset, node=None):
    """[(time, [ux, uy, uz])] of one node of a set (the only one if node is None), with
    the reference state (time 0, zero displacement) first."""
    data = read_dat(path)
    if nset.upper() not in data or not data[nset.upper()]:
        raise ValueError(f"{path}: no displacements printed for set {nset}")
    nodes = data[nset.upper()]
    if node is None:
        if len(nodes) != 1:
            raise ValueError(f"{path}: set {nset} has {len(nodes)} nodes; name one")
        node = next(iter(nodes))
    rows = nodes[node]
    if rows[0][0] > 0.0:
        rows = [(0.0, [0.0, 0.0, 0.0])] + rows
    return rows


def final(path, nset, node=None):
    """(time, [ux, uy, uz]) of the last increment."""
    return history(path, nset, node)[-1]
