"""Docs that run (issue 39 point 7): the scenes and commands the tutorial and the
how-to guides mark as runnable are run, and the results they state are checked;
every relative link of README.md and docs/ leads to a file (and heading) that
exists.

Markers (docs/reference/commands.md, "Runnable documentation"):
* a fenced block opened with ```toml scene=NAME is written to NAME.toml in the
  page's working directory, one opened with ```LANG file=NAME to NAME;
* a fenced block opened with ```sh run is run line by line there (a line ending
  in a backslash continues), ./build.sh and bin/beamkit being the repository's;
* a line `> expect: FILE KEY = VALUE ± TOL` states a result: KEY is a path into
  the JSON file FILE (dots, [i] for list items, ["a.b"] for a key with dots), TOL an absolute value or a
  percentage of VALUE;
* a line `> expect file: PATH` states that a run wrote PATH.
Each page runs in a fresh temporary directory, its blocks in order."""
import json
import re
import shlex
import subprocess
import unicodedata
from pathlib import Path

import pytest

from util import ENV, ROOT

def _marked(path):
    return "```sh run" in path.read_text()


# The tutorial and every how-to guide with runnable blocks (pages whose recipes
# take minutes, e.g. a CalculiX study, show their commands unmarked).
RUN_PAGES = ["docs/tutorial.md"] + sorted(
    str(p.relative_to(ROOT)) for p in (ROOT / "docs" / "howto").glob("*.md") if _marked(p))

FENCE = re.compile(r"^```([^\n]*)\n(.*?)^```", re.S | re.M)
EXPECT = re.compile(r"^> expect: `?(\S+?)`? `?(\S+?)`? = `?([-+0-9.eE]+)`? ± `?([0-9.eE+-]+)`? ?(%?)", re.M)
EXPECT_FILE = re.compile(r"^> expect file: `?([^`\s]+)`?", re.M)


def steps(text):
    """The runnable steps of a page, in the order they appear: ('scene', name,
    text), ('sh', command), ('expect', file, key, value, tol, relative),
    ('file', path)."""
    items = []
    for m in FENCE.finditer(text):
        info = m.group(1).split()
        if info[:1] == ["toml"] and any(w.startswith("scene=") for w in info):
            name = next(w for w in info if w.startswith("scene="))[6:]
            items.append((m.start(), ("scene", name + ".toml", m.group(2))))
        elif any(w.startswith("file=") for w in info[1:]):
            name = next(w for w in info if w.startswith("file="))[5:]
            items.append((m.start(), ("scene", name, m.group(2))))
        elif info[:2] == ["sh", "run"]:
            for cmd in _commands(m.group(2)):
                items.append((m.start(), ("sh", cmd)))
    for m in EXPECT.finditer(text):
        f, key, val, tol, pct = m.groups()
        items.append((m.start(), ("expect", f, key, float(val), float(tol), pct == "%")))
    for m in EXPECT_FILE.finditer(text):
        items.append((m.start(), ("file", m.group(1))))
    return [s for _, s in sorted(items, key=lambda t: t[0])]


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
    for part in re.findall(r'\["[^"]+"\]|\[\d+\]|[^.\[\]]+', key):
        if part.startswith('["'):
            data = data[part[2:-2]]
        elif part.startswith("["):
            data = data[int(part[1:-1])]
        else:
            data = data[part]
    return data


def _run(cmd, cwd):
    argv = shlex.split(cmd)
    if argv[0] in ("./build.sh", "build.sh"):
        argv[0] = str(ROOT / "build.sh")
    elif argv[0] in ("bin/beamkit", "beamkit"):
        argv[0] = str(ROOT / "bin" / "beamkit")
    else:
        raise AssertionError(f"a runnable block runs ./build.sh or bin/beamkit only: {cmd}")
    env = dict(ENV, BK_CALLER_CWD=str(cwd))    # relative paths from the page's directory
    return subprocess.run(argv, cwd=cwd, capture_output=True, text=True, timeout=300, env=env)


@pytest.mark.parametrize("page", RUN_PAGES)
def test_page_runs_and_its_numbers_hold(page, tmp_path):
    text = (ROOT / page).read_text()
    todo = steps(text)
    assert any(s[0] == "sh" for s in todo), f"{page}: no ```sh run block"
    for s in todo:
        if s[0] == "scene":
            (tmp_path / s[1]).write_text(s[2])
        elif s[0] == "sh":
            r = _run(s[1], tmp_path)
            assert r.returncode == 0, f"{page}: `{s[1]}` exited {r.returncode}:\n{r.stderr[-3000:]}"
        elif s[0] == "file":
            assert (tmp_path / s[1]).exists(), f"{page}: {s[1]} was not written"
        else:
            _, f, key, val, tol, rel = s
            got = _lookup(json.loads((tmp_path / f).read_text()), key)
            bound = abs(val) * tol / 100 if rel else tol
            assert abs(got - val) <= bound, f"{page}: {f} {key} = {got}, the page says {val} ± {bound}"


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
    assert _lookup({"s": {"d": [1, 2, 3]}}, "s.d[2]") == 3
    assert _lookup({"p": {"m.s.E": {"value": 4}}}, 'p["m.s.E"].value') == 4


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
