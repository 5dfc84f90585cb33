"""Docs that run (issue 39 point 7): the scenes and commands the tutorial and the
how-to guides mark as runnable are run, and the results they state are checked;
every relative link of README.md and docs/ leads to a file (and heading) that
exists.

Markers (docs/reference/commands.md, "Runnable documentation"):
* a fenced block opened with ```toml scene=NAME is written to NAME.toml in the
  page's working directory, one opened with ```LANG file=PATH to PATH;
* a fenced block opened with ```sh run is run line by line there (a line ending
  in a backslash continues; `CMD > FILE` writes the command's output to FILE),
  ./build.sh and bin/beamkit being the repository's; /usr/bin/python3 runs in
  the repository's top folder without PYTHONPATH (as a user types it there);
* a page with a ```sh run copy block (a recipe that edits the code, the
  tutorial's setup, commands that read the repository's own files such as
  models/data/) runs, all of it, in a scratch copy of the repository: its
  working directory is the copy's top, file=PATH blocks write into the copy,
  ./build.sh is the copy's;
* a ```sh run long block (and the expect lines after it, up to the next run
  block) runs only in the long mode, BK_DOCS_LONG=1: a block that costs more
  than the CI can give it (LONG lists each with its measured time), run by
  test_long_blocks_run, which is skipped without BK_DOCS_LONG;
* a line `> expect: FILE KEY = VALUE ± TOL` states a result: KEY is a path into
  the JSON file FILE (dots, [i] for list items, ["a.b"] for a key with dots,
  len(KEY) for a list's length), or into the CSV file FILE ([i]["column"]: row
  i's value), TOL an absolute value or a percentage of VALUE;
* a line `> expect file: PATH` states that a run wrote PATH;
* a line `> expect table: FILE: N rows of COL, COL, ...` states a CSV file's
  header and its number of rows;
* a line `> expect output: TEXT` states what the last command printed (a line
  of its standard output starts with TEXT; "..." in TEXT stands for any
  characters).
Each page runs in a fresh temporary directory, its blocks in order.  Every
fenced block of the tutorial and the how-to guides is run (or written) by one
of these markers, or is one this file lists as shown only, with the reason.

Long mode: `BK_DOCS_LONG=1 ./build.sh test -k docs_run -n 2` runs the long
blocks too (LONG below: their times)."""
import csv
import io
import json
import os
import re
import shlex
import subprocess
import unicodedata
from pathlib import Path

import pytest

from util import ENV, ROOT, scratch_copy

def _marked(path):
    return "```sh run" in path.read_text()


LONG_MODE = os.environ.get("BK_DOCS_LONG", "") not in ("", "0")


def _slow(page):
    """Pages that follow a recipe in a scratch copy (a generator run, a build
    and a nested test run): more than 30 s.  (The tutorial and the calibration
    page also run in a copy, in 10-15 s: not slow.)"""
    return in_copy((ROOT / page).read_text()) and any(
        s[0] == "sh" and re.match(r"\./build\.sh (gen|test)\b", s[1]) for s in steps((ROOT / page).read_text()))


# Pages that another test follows, with checks of its own in the same copy.
FOLLOWED_ELSEWHERE = {"docs/howto/add-material.md": "tests/test_material_recipe.py"}

# The tutorial and every how-to guide with runnable blocks.
RUN_PAGES = ["docs/tutorial.md"] + sorted(
    str(p.relative_to(ROOT)) for p in (ROOT / "docs" / "howto").glob("*.md")
    if _marked(p) and str(p.relative_to(ROOT)) not in FOLLOWED_ELSEWHERE)

# An indented fence (in a list item) counts; its text is dedented.
FENCE = re.compile(r"^( *)```([^\n]*)\n(.*?)^\1```", re.S | re.M)
EXPECT = re.compile(r"^ *> expect: `?(\S+?)`? `?(\S+?)`? = `?([-+0-9.eE]+)`? ± `?([0-9.eE+-]+)`? ?(%?)", re.M)
EXPECT_FILE = re.compile(r"^ *> expect file: `?([^`\s]+)`?", re.M)
EXPECT_TABLE = re.compile(r"^ *> expect table: `?([^`\s]+?)`?: (\d+) rows? of (.+)$", re.M)
EXPECT_OUTPUT = re.compile(r"^ *> expect output: `(.+)`\s*$", re.M)


def _blocks(text):
    """(offset, info words, dedented text) of every fenced block."""
    out = []
    for m in FENCE.finditer(text):
        ind = len(m.group(1))
        body = "".join(line[ind:] if line[:ind].strip() == "" else line
                       for line in m.group(3).splitlines(keepends=True))
        out.append((m.start(), m.group(2).split(), body))
    return out


def steps(text, long=False):
    """The runnable steps of a page, in the order they appear: ('scene', name,
    text), ('sh', command), ('expect', file, key, value, tol, relative),
    ('file', path), ('table', file, rows, [columns]), ('output', text).  Without
    long, the steps of ```sh run long blocks (the block's commands and the
    expect lines after it, up to the next run block) are left out."""
    items = []
    for pos, info, body in _blocks(text):
        if info[:1] == ["toml"] and any(w.startswith("scene=") for w in info):
            name = next(w for w in info if w.startswith("scene="))[6:]
            items.append((pos, ("scene", name + ".toml", body)))
        elif any(w.startswith("file=") for w in info[1:]):
            name = next(w for w in info if w.startswith("file="))[5:]
            items.append((pos, ("scene", name, body)))
        elif info[:2] == ["sh", "run"]:
            items.append((pos, ("block", "long" in info[2:])))
            for cmd in _commands(body):
                items.append((pos, ("sh", cmd)))
    for m in EXPECT.finditer(text):
        f, key, val, tol, pct = m.groups()
        items.append((m.start(), ("expect", f, key, float(val), float(tol), pct == "%")))
    for m in EXPECT_FILE.finditer(text):
        items.append((m.start(), ("file", m.group(1))))
    for m in EXPECT_TABLE.finditer(text):
        items.append((m.start(), ("table", m.group(1), int(m.group(2)), [c.strip() for c in m.group(3).split(",")])))
    for m in EXPECT_OUTPUT.finditer(text):
        items.append((m.start(), ("output", m.group(1))))
    out, in_long = [], False
    for _, st in sorted(items, key=lambda t: t[0]):
        if st[0] == "block":
            in_long = st[1]
        elif long or not in_long:
            out.append(st)
    return out


def has_long(text):
    """True for a page with a ```sh run long block."""
    return any(info[:3] == ["sh", "run", "long"] for _, info, _ in _blocks(text))


def _commands(block):
    out, cur = [], ""
    for line in block.splitlines():
        s = line.rstrip()
        if not cur and (not s.strip() or s.lstrip().startswith("#")):
            continue
        if s.endswith("\\"):
            cur += s[:-1].strip() + " "
            continue
        out.append(cur + s.strip())
        cur = ""
    return out


def _lookup(data, key):
    if key.startswith("len(") and key.endswith(")"):
        return len(_lookup(data, key[4:-1]) if key[4:-1] else data)
    for part in re.findall(r'\["[^"]+"\]|\[\d+\]|[^.\[\]]+', key):
        if part.startswith('["'):
            data = data[part[2:-2]]
        elif part.startswith("["):
            data = data[int(part[1:-1])]
        else:
            data = data[part]
    return data


def _load(path):
    """A JSON file's data, or a CSV file's rows as dicts."""
    text = path.read_text()
    if path.suffix == ".csv":
        return list(csv.DictReader(io.StringIO("".join(l for l in text.splitlines(True) if not l.startswith("#")))))
    return json.loads(text)


def _output_pattern(text):
    """The regular expression of an `> expect output:` text ("..." any characters)."""
    return re.compile(".*?".join(re.escape(p) for p in text.split("...")))


def in_copy(text):
    """True for a page that runs in a scratch copy of the repository."""
    return re.search(r"^ *```sh run copy\s*$", text, re.M) is not None


def _redirect(argv):
    """(the command, the file its output goes to or None) of `CMD > FILE`."""
    if len(argv) > 2 and argv[-2] == ">":
        return argv[:-2], argv[-1]
    return argv, None


def _run(cmd, cwd, root=ROOT):
    argv, out = _redirect(shlex.split(cmd, comments=True))
    out = cwd / out if out else None
    env = dict(ENV, BK_CALLER_CWD=str(cwd))    # relative paths from the page's directory
    if root != ROOT:
        env.update(PYTHONPATH=str(root), PYTHONPYCACHEPREFIX=str(root / "out" / "pycache"))
    if argv[0] in ("./build.sh", "build.sh"):
        argv[0] = str(root / "build.sh")
    elif argv[0] in ("bin/beamkit", "beamkit"):
        argv[0] = str(root / "bin" / "beamkit")
    elif argv[0] == "/usr/bin/python3":
        # as typed in the repository's top folder: no PYTHONPATH, no BK_ variables
        env = {k: v for k, v in ENV.items()
               if k not in ("PYTHONPATH", "PYTHONPYCACHEPREFIX") and not k.startswith("BK_")}
        cwd = root
    else:
        raise AssertionError(f"a runnable block runs ./build.sh, bin/beamkit or /usr/bin/python3 only: {cmd}")
    r = subprocess.run(argv, cwd=cwd, capture_output=True, text=True, timeout=1800, env=env)
    if out is not None:
        out.write_text(r.stdout)
    return r


def follow(page, cwd, root=ROOT, long=False):
    """Run the steps of a page (a path relative to the repository) in the
    directory cwd with the build.sh of root, asserting each command's success
    and each stated result; long: the ```sh run long blocks too."""
    text = (ROOT / page).read_text()
    todo = steps(text, long)
    assert any(s[0] == "sh" for s in todo), f"{page}: no ```sh run block"
    last = None
    for s in todo:
        if s[0] == "scene":
            (cwd / s[1]).parent.mkdir(parents=True, exist_ok=True)
            (cwd / s[1]).write_text(s[2])
        elif s[0] == "sh":
            last = r = _run(s[1], cwd, root)
            assert r.returncode == 0, f"{page}: `{s[1]}` exited {r.returncode}:\n{r.stdout[-2000:]}\n{r.stderr[-3000:]}"
        elif s[0] == "file":
            assert (cwd / s[1]).exists(), f"{page}: {s[1]} was not written"
        elif s[0] == "output":
            pat = _output_pattern(s[1])
            assert last is not None and any(pat.match(line) for line in last.stdout.splitlines()), \
                f"{page}: `{last.args}` printed no line starting with {s[1]!r}:\n{last.stdout[-2000:]}"
        elif s[0] == "table":
            _, f, nrows, cols = s
            with open(cwd / f, newline="") as fh:
                rows = list(csv.reader(l for l in fh if not l.startswith("#")))
            assert rows and rows[0] == cols, f"{page}: {f} has the columns {rows[:1]}, the page says {cols}"
            assert len(rows) - 1 == nrows, f"{page}: {f} has {len(rows) - 1} rows, the page says {nrows}"
        else:
            _, f, key, val, tol, rel = s
            got = float(_lookup(_load(cwd / f), key))
            bound = abs(val) * tol / 100 if rel else tol
            assert abs(got - val) <= bound, f"{page}: {f} {key} = {got}, the page says {val} ± {bound}"


def _follow_page(page, tmp_path, long=False):
    if in_copy((ROOT / page).read_text()):
        root = scratch_copy(tmp_path / "repo")
        follow(page, root, root, long)
    else:
        follow(page, tmp_path, long=long)


@pytest.mark.parametrize("page", [pytest.param(p, marks=pytest.mark.slow) if _slow(p) else p for p in RUN_PAGES])
def test_page_runs_and_its_numbers_hold(page, tmp_path):
    _follow_page(page, tmp_path)


LONG_PAGES = [p for p in RUN_PAGES if has_long((ROOT / p).read_text())]


@pytest.mark.slow
@pytest.mark.parametrize("page", LONG_PAGES)
def test_long_blocks_run(page, tmp_path):
    """The long mode (BK_DOCS_LONG=1): the page again, its ```sh run long
    blocks (LONG: what each costs) and their stated results included."""
    if not LONG_MODE:
        pytest.skip("a ```sh run long block: runs with BK_DOCS_LONG=1 (the long mode)")
    _follow_page(page, tmp_path, long=True)


def test_markers_are_parsed():
    """The parser finds each kind of marker (a page whose markers were misspelt
    would otherwise run nothing)."""
    text = ("```toml scene=a\n[scene]\n```\n```csv file=d.csv\nt,x\n```\n\n```sh run\n# c\n./build.sh run a.toml \\\n  --out o\n```\n"
            "> expect: o/summary.json `sensors.tip.displacement[2]` = -1.5e-3 ± 2 %\n"
            "> expect file: o/beam.png\n```sh\n./build.sh test\n```\n")
    got = steps(text)
    assert got == [("scene", "a.toml", "[scene]\n"), ("scene", "d.csv", "t,x\n"), ("sh", "./build.sh run a.toml --out o"),
                   ("expect", "o/summary.json", "sensors.tip.displacement[2]", -1.5e-3, 2.0, True),
                   ("file", "o/beam.png")]
    text = "1. a step:\n\n   ```python file=gen/x.py\n   A = 1\n     B = 2\n   ```\n\n   ```sh run copy\n   ./build.sh gen\n" \
           "   ./build.sh calculix s --json > s.json\n   ```\n\n   > expect: s.json `a[0].b` = 2 ± 0.1\n"
    assert steps(text) == [("scene", "gen/x.py", "A = 1\n  B = 2\n"), ("sh", "./build.sh gen"),
                           ("sh", "./build.sh calculix s --json > s.json"), ("expect", "s.json", "a[0].b", 2.0, 0.1, False)]
    assert in_copy(text) and not in_copy("```sh run\n./build.sh gen\n```\n")
    assert _redirect(shlex.split("./build.sh calculix s --json > s.json")) == (["./build.sh", "calculix", "s", "--json"],
                                                                              "s.json")
    assert _redirect(["./build.sh", "run", "a.toml"]) == (["./build.sh", "run", "a.toml"], None)
    assert _lookup({"s": {"d": [1, 2, 3]}}, "s.d[2]") == 3
    assert _lookup({"p": {"m.s.E": {"value": 4}}}, 'p["m.s.E"].value') == 4
    assert _lookup({"runs": [1, 2, 3]}, "len(runs)") == 3
    # long blocks: left out with their expect lines unless long; output and table lines
    text = ("```sh run\n/usr/bin/python3 -c \"print(1)\"\n```\n> expect output: `(-0.02..., 1)`\n"
            "```sh run long\n./build.sh fit s --out f\n```\n> expect: f/fit.json len(runs) = 22 ± 0\n"
            "> expect table: f/t.csv: 3 rows of run, a.b, c:d@1:2\n```sh run\n./build.sh run b\n```\n"
            "> expect: o/sweep.csv [2][\"B.uz\"] = 0.1 ± 1 %\n")
    assert steps(text) == [("sh", '/usr/bin/python3 -c "print(1)"'), ("output", "(-0.02..., 1)"),
                           ("sh", "./build.sh run b"), ("expect", "o/sweep.csv", '[2]["B.uz"]', 0.1, 1.0, True)]
    assert steps(text, long=True)[2:5] == [("sh", "./build.sh fit s --out f"),
                                           ("expect", "f/fit.json", "len(runs)", 22.0, 0.0, False),
                                           ("table", "f/t.csv", 3, ["run", "a.b", "c:d@1:2"])]
    assert has_long(text) and not has_long("```sh run\n./build.sh gen\n```\n")
    pat = _output_pattern("(-0.0209958..., 0.0555659...)")
    assert pat.match("(-0.020995812, 0.05556591)") and not pat.match("(-0.0209959, 0.0555659)")
    rows = [{"run": "0", "B.uz": "0.25"}]
    assert float(_lookup(rows, '[0]["B.uz"]')) == 0.25


# Fenced blocks of the tutorial and the how-to guides that no test runs: (page,
# the block's first line) -> why.  Blocks without a language are a command's
# output; ```c, ```python, ... without file= are excerpts of a file.
SHOWN = {
    ("docs/howto/sweep-dask.md", "# one node: the scheduler (writes its address to a file on the shared file "
                                 "system)"): "needs a Slurm cluster",
    ("docs/howto/verify-calculix.md", "./build.sh calculix silicone_cantilever_sag --set "
                                      "constraint.0.cross_section=rigid"):
        "ccx runs 20-36 minutes (the page says so): longer than the long mode (BK_DOCS_LONG=1) is meant for",
}

# ```sh run long blocks: (page, the block's first line) -> what it costs.  They
# run in the long mode only (BK_DOCS_LONG=1, test_long_blocks_run); the CI's
# share of the docs' runs is about a minute of wall on 2 cores.
LONG = {
    ("docs/howto/calibrate.md", "./build.sh fit silicone_fall --data models/data/silicone_fall_rayleigh_calculix.csv \\"):
        "a fit of 22 dynamic runs with Rayleigh damping, 3 s each: 41 s of wall with 2 workers; runs with "
        "BK_DOCS_LONG=1",
}


def _unrun(page):
    """(first line, info) of the page's fenced blocks that no marker runs or writes."""
    out = []
    for _, info, body in _blocks((ROOT / page).read_text()):
        if info[:2] == ["sh", "run"] or any(w.startswith(("scene=", "file=")) for w in info):
            continue
        first = body.splitlines()[0] if body.strip() else ""
        out.append((first, info))
    return out


def _long(page):
    """First lines of the page's ```sh run long blocks."""
    return [body.splitlines()[0] for _, info, body in _blocks((ROOT / page).read_text())
            if info[:3] == ["sh", "run", "long"]]


def test_every_command_block_runs_or_says_why_not():
    """A fenced block of the tutorial or a how-to guide is run (```sh run), written
    (scene=, file=), a command's output (no language), an excerpt of a file
    (```c, ```python, ... in a page that writes whole files or explains one), or
    listed in SHOWN with the reason no test runs it; a ```sh run long block is
    listed in LONG with what it costs."""
    pages = ["docs/tutorial.md"] + sorted(str(p.relative_to(ROOT)) for p in (ROOT / "docs" / "howto").glob("*.md"))
    bad, seen, seen_long = [], set(), set()
    for page in pages:
        for first, info in _unrun(page):
            if not info or info[0] not in ("sh", "bash", "console"):
                continue
            if (page, first) in SHOWN:
                seen.add((page, first))
            else:
                bad.append(f"{page}: a ```{' '.join(info)} block that no test runs: {first}")
        for first in _long(page):
            if (page, first) in LONG:
                seen_long.add((page, first))
            else:
                bad.append(f"{page}: a ```sh run long block that LONG does not list: {first}")
    bad += [f"{p}: SHOWN lists a block the page no longer has: {f}" for p, f in set(SHOWN) - seen]
    bad += [f"{p}: LONG lists a block the page no longer has: {f}" for p, f in set(LONG) - seen_long]
    assert not bad, "\n".join(bad)


# ---- links -------------------------------------------------------------------

LINK = re.compile(r"(?<!\!)\[[^\]]*\]\(([^)\s]+)\)|!\[[^\]]*\]\(([^)\s]+)\)")


def slug(heading):
    """GitHub's anchor of a heading: lower case, punctuation dropped (letters,
    digits, spaces, hyphens and underscores kept), spaces to hyphens."""
    h = heading.strip().lower()
    h = re.sub(r"`", "", h)
    out = []
    for ch in h:
        cat = unicodedata.category(ch)
        if ch in " -_" or cat[0] in "LN":
            out.append(ch)
    return "".join(out).replace(" ", "-")


def anchors(path):
    text = FENCE.sub("", path.read_text())
    seen, out = {}, set()
    for m in re.finditer(r"^#{1,6} (.+)$", text, re.M):
        s = slug(m.group(1))
        n = seen.get(s, 0)
        out.add(s if n == 0 else f"{s}-{n}")
        seen[s] = n + 1
    return out


def doc_files():
    return [ROOT / "README.md"] + sorted((ROOT / "docs").rglob("*.md"))


def test_slug_rules():
    assert slug("Scene reference") == "scene-reference"
    assert slug("`ancf3363` next to a rigid clamp") == "ancf3363-next-to-a-rigid-clamp"
    assert slug("Many runs: Python API, sweeps, calibration") == "many-runs-python-api-sweeps-calibration"


def test_every_relative_link_resolves():
    bad = []
    for f in doc_files():
        text = FENCE.sub("", f.read_text())
        text = re.sub(r"`[^`\n]*`", "", text)
        for m in LINK.finditer(text):
            target = m.group(1) or m.group(2)
            if re.match(r"[a-z]+:", target):
                continue
            path, _, anchor = target.partition("#")
            dest = (f.parent / path).resolve() if path else f
            if not dest.exists():
                bad.append(f"{f.relative_to(ROOT)}: {target}: no such file")
            elif anchor and dest.suffix == ".md" and anchor not in anchors(dest):
                bad.append(f"{f.relative_to(ROOT)}: {target}: no heading #{anchor}")
    assert not bad, "\n".join(bad)


def test_readme_is_short_and_keeps_the_commands():
    text = (ROOT / "README.md").read_text()
    assert len(text.splitlines()) <= 200
    for needle in ("./build.sh test", "./build.sh run", "bin/beamkit", "docs/tutorial.md"):
        assert needle in text, needle
    png = ROOT / "docs" / "images" / "finger_beam.png"
    assert png.stat().st_size < 100_000
