"""`beamkit animate RUN` (report/animate.py, issue 39 point 4): a run's ParaView
frames as an MP4 (or GIF) drawn offscreen, without a display: one video frame
per ParaView frame, the motion visible (first and last frames differ), a field
the user picks, one clear line for a bad field or a run without frames."""
import json
import os
import subprocess
import tempfile
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np

from util import BUILD, ROOT, ensure_dir, run_cli


def _headless():
    env = {k: v for k, v in os.environ.items() if k not in ("DISPLAY", "WAYLAND_DISPLAY")}
    env["MPLBACKEND"] = ""            # whatever the user's setting, no display is used
    return env


def _run(sets):
    out = Path(tempfile.mkdtemp(prefix="bk-anim-", dir=ensure_dir(BUILD / "runs")))
    r = run_cli(["run", "silicone_fall", "--quiet", "--out", str(out)] + sum((["--set", s] for s in sets), []))
    assert r.returncode == 0, r.stderr[-2000:]
    return out


def _animate(args):
    return subprocess.run([str(ROOT / "bin" / "beamkit"), "animate"] + [str(a) for a in args], capture_output=True,
                          text=True, env=_headless(), timeout=900)


def _frame(mp4, n):
    """Video frame n as raw RGB bytes (ffmpeg)."""
    r = subprocess.run(["ffmpeg", "-loglevel", "error", "-i", str(mp4), "-vf", f"select=eq(n\\,{n})", "-vframes", "1",
                        "-f", "rawvideo", "-pix_fmt", "rgb24", "-"], capture_output=True, timeout=120)
    assert r.returncode == 0, r.stderr
    return np.frombuffer(r.stdout, dtype=np.uint8)


def test_mp4_of_every_frame_drawn_offscreen_and_gif_of_another_field():
    run = _run(["dynamic.t_end=0.1", "output.vtk_every=1", "dynamic.output_every=10"])
    frames = ET.parse(run / "results.pvd").getroot().findall("Collection/DataSet")
    assert len(frames) >= 8
    r = _animate([run])
    assert r.returncode == 0, r.stderr[-2000:]
    mp4 = run / "animation.mp4"
    probe = subprocess.run(["ffprobe", "-v", "error", "-count_frames", "-select_streams", "v:0", "-show_entries",
                            "stream=nb_read_frames,width,height", "-of", "json", str(mp4)], capture_output=True,
                           text=True, timeout=120)
    st = json.loads(probe.stdout)["streams"][0]
    assert int(st["nb_read_frames"]) == len(frames) and (st["width"], st["height"]) == (800, 600)
    a, b = _frame(mp4, 0), _frame(mp4, len(frames) - 1)
    assert a.size == b.size == 800 * 600 * 3
    assert np.mean(a != b) > 0.005           # the beam moved (and the time in the title changed)
    r = _animate([run, "--gif", "--field", "strain_energy_density", "--fps", "5"])
    assert r.returncode == 0, r.stderr[-2000:]
    from PIL import Image
    with Image.open(run / "animation.gif") as im:
        assert im.n_frames == len(frames)


def test_bad_field_and_a_run_without_frames_one_line_each():
    run = _run(["dynamic.t_end=0.02", "output.vtk_every=1"])
    r = _animate([run, "--gif", "--field", "no_such_field"])
    assert r.returncode == 1
    assert r.stderr.count("error:") == 1 and "no_such_field" in r.stderr and "strain_energy_density" in r.stderr
    run0 = _run(["dynamic.t_end=0.02", "output.vtk_every=0"])
    r = _animate([run0, "--gif"])
    assert r.returncode == 1 and "no ParaView frames" in r.stderr and r.stderr.count("error:") == 1


def test_colour_range_ignores_the_bodies_nan_and_the_body_is_drawn():
    """A rigid body's points carry NaN for the section fields: the colour range
    is the beams' (0.74 N in the trial's gripper, not -0.1..0.1), and the
    animation of section_force of a scene with a body is written."""
    import numpy as np
    from report.animate import color_range
    assert color_range([np.array([0.2, np.nan, 0.74]), np.array([np.nan, 0.1])]) == (0.1, 0.74)
    assert color_range([np.array([np.nan])]) == (0.0, 1.0)
    out = BUILD / "runs" / "animate_body"
    r = run_cli(["run", "contact_ball_on_cantilever", "--quiet", "--out", str(out)])
    assert r.returncode == 0, r.stderr[-2000:]
    r = run_cli(["animate", str(out), "--field", "section_force", "--gif", "--fps", "4"])
    assert r.returncode == 0, r.stderr[-2000:]
    assert (out / "animation.gif").stat().st_size > 1000
