"""The reference lists what the code does (issue 39 point 1):
* docs/reference/outputs.md lists every file, CSV column, summary.json key and
  ParaView field that small static, dynamic, modal, buckling, joint, actuator
  and contact runs actually write (the runs are the source of truth, the page is checked
  against them, not against an earlier copy of itself);
* docs/reference/commands.md carries the text of `./build.sh --help` and every
  exit status it lists."""
import csv
import json
import re
import subprocess

import pytest

from util import ENV, ROOT, run_cli

OUTPUTS = ROOT / "docs" / "reference" / "outputs.md"
COMMANDS = ROOT / "docs" / "reference" / "commands.md"

# (scene, overrides): one of each analysis, joints with an axis, contact of
# each kind (beam on a primitive, beam on beam, body on a primitive), an actuator.
RUNS = [
    ("cantilever_bend_10N", []),
    ("pendulum_soft_ancf", ["dynamic.t_end=0.01"]),
    ("cantilever_modal", []),
    ("column_buckling", []),
    ("two_link_arm", ["dynamic.t_end=0.01"]),
    ("contact_propped_cantilever", []),
    ("contact_crossed_beams", []),
    ("contact_box_table", []),
    ("actuator_link", []),
]


def _scene_text(name):
    """Scenes of the runs that models/ does not have, as TOML text (else None)."""
    if name == "actuator_link":                     # a hinged link held by a PD actuator (tests/test_actuators.py)
        import test_actuators
        return test_actuators.LINK + ('[[actuator]]\nname = "pd"\njoint = "hinge"\nkp = 4.0\nkd = 0.7\n'
                                      'setpoint = 0.5\n')
    return None


def _section(text, heading):
    start = text.index(heading)
    nxt = text.find("\n## ", start + len(heading))
    return text[start:nxt if nxt >= 0 else len(text)]


def _documented_files():
    """{file pattern: set of listed columns or keys} from the first table."""
    out = {}
    sec = _section(OUTPUTS.read_text(), "## Every file and column")
    for row in sec.splitlines():
        if not row.startswith("| `"):
            continue
        cells = row.split("|")
        names = re.findall(r"`([^`]+)`", cells[1])
        cols = set(re.findall(r"`([^`]+)`", cells[3]))
        for n in names:
            out[n] = cols
    return out


def _documented_fields():
    """{file pattern: set of fields} from the ParaView table."""
    out = {}
    sec = _section(OUTPUTS.read_text(), "## ParaView fields")
    for row in sec.splitlines():
        if not row.startswith("| `"):
            continue
        cells = row.split("|")
        f = re.findall(r"`([^`]+)`", cells[1])[0]
        out.setdefault(f, set()).update(re.findall(r"`([^`]+)`", cells[2]))
    return out


def _pattern(name):
    return re.sub(r"_\d{2}\.", "_NN.", re.sub(r"\d{6}", "NNNNNN", name))


def _fields(path):
    head = path.read_bytes()[:200_000].split(b"<AppendedData")[0].decode("latin1")
    names = set(re.findall(r'<DataArray[^>]*Name="([^"]+)"', head))
    return names - {"connectivity", "offsets", "types"}


@pytest.fixture(scope="module")
def runs(tmp_path_factory):
    base = tmp_path_factory.mktemp("outputs")
    out = {}
    for scene, sets in RUNS:
        d = base / scene
        text = _scene_text(scene)
        if text is not None:
            (base / f"{scene}.toml").write_text(text)
        args = ["run", str(base / f"{scene}.toml") if text is not None else scene, "--out", str(d), "--quiet"]
        for s in sets:
            args += ["--set", s]
        r = run_cli(args, timeout=600)
        assert r.returncode == 0, (scene, r.stderr[-2000:])
        out[scene] = d
    return out


def test_every_output_file_and_column_is_listed(runs):
    doc = _documented_files()
    missing = []
    for scene, d in runs.items():
        for f in sorted(d.iterdir()):
            pat = _pattern(f.name)
            if pat not in doc:
                missing.append(f"{scene}: file {f.name}")
                continue
            if f.suffix == ".csv":
                with open(f, newline="") as fh:
                    header = next(csv.reader(fh))
                missing += [f"{scene}: {f.name} column {c}" for c in header if c not in doc[pat]]
            elif f.name == "summary.json":
                keys = json.loads(f.read_text())
                missing += [f"{scene}: summary.json key {k}" for k in keys if k not in doc[pat]]
    assert not missing, "not in docs/reference/outputs.md:\n" + "\n".join(missing)


def test_every_paraview_field_is_listed(runs):
    doc = _documented_fields()
    missing, seen = [], set()
    for scene, d in runs.items():
        for f in sorted(d.glob("*.vt[up]")):
            pat = _pattern(f.name)
            seen.add(pat)
            missing += [f"{scene}: {f.name} field {n}" for n in _fields(f) if n not in doc.get(pat, set())]
    assert not missing, "not in docs/reference/outputs.md:\n" + "\n".join(missing)
    # the runs wrote every kind of frame the page describes, so the check saw them all
    assert seen == set(doc), (seen, set(doc))
    assert "strain_energy_density" in doc["step_NNNNNN.vtu"]


def test_commands_reference_is_the_help_text():
    """The fenced block under "## Every command and option" is `./build.sh --help`
    as it prints now: paste the new text when a command changes."""
    r = subprocess.run([str(ROOT / "build.sh"), "--help"], capture_output=True, text=True, env=ENV)
    assert r.returncode == 0
    sec = _section(COMMANDS.read_text(), "## Every command and option")
    block = re.search(r"```text\n(.*?)```", sec, re.S).group(1)
    assert block.strip() == r.stdout.strip(), "docs/reference/commands.md: the help text is stale"
    for code in re.findall(r"^  (\d+) ", r.stdout, re.M):
        assert f"| {code} |" in COMMANDS.read_text(), f"exit status {code} not in the table"
