"""Structure of the generated rod kernels that keeps their first compile short
(issue 12 item 9): the kinematics shared by gef, euler_bernoulli and kirchhoff
is generated once, in files of moderate size whose functions are small enough
for gcc's superlinear passes (register allocation); the element and pair files
only add the material law.  Compile times themselves are measured by
`./build.sh bench`, never asserted here."""
import json
import re

from util import ROOT

KERNELS = ROOT / "out" / "kernels"
RODS = ("gef", "euler_bernoulli", "kirchhoff")
SHARED = ("rod_strain.c", "rod_common.c", "rod_inertia.c", "rod_line.c")
MAX_FILE_LINES = 1800        # before the split: 6,384 (euler_bernoulli_resultant.c)
MAX_FUNCTION_LINES = 800     # before: one 5,594-line force_tangent function
MAX_OWN_LINES = 300          # element and pair files once the kinematics is shared
MAX_TANGENT_OPS = 15000      # before: 26,699 operations per gef force + tangent call


def functions(text):
    """{function signature line: body lines} of a generated C file (functions
    start with a signature at column 0 and a '{' line, end with a '}' line)."""
    out, name, n = {}, None, None
    for line in text.splitlines():
        if re.match(r"^[a-z].*\(", line):
            name = line
        elif line == "{" and name:
            n = 0
        elif line == "}" and n is not None:
            out[name] = n
            n = None
        elif n is not None:
            n += 1
    return out


def rod_pairs():
    index = json.loads((KERNELS / "index.json").read_text())
    return [p for p in index["pairs"] if p["element"] in RODS]


def test_rod_pairs_link_one_shared_kinematics():
    pairs = rod_pairs()
    assert {p["element"] for p in pairs} == set(RODS)
    for p in pairs:
        assert sorted(f for f in p["files"] if f in SHARED) == sorted(SHARED), p
        own = [f for f in p["files"] if f not in SHARED]
        assert own == [f"{p['element']}.c", f"{p['element']}_{p['material']}.c"], p
    # a solver with all three elements links each shared file once (the build
    # takes the union of the pairs' files, gen/solver_build.kernel_objects)
    files = []
    for p in pairs:
        files += [f for f in p["files"] if f not in files]
    assert sum(f in SHARED for f in files) == len(SHARED)


def test_element_and_pair_files_carry_no_kinematics():
    """Rotation maps (bk_at, bk_sh, bk_ch of rod_math.h) and the strain
    derivatives live only in the shared files."""
    for p in rod_pairs():
        for f in p["files"]:
            if f in SHARED:
                continue
            text = (KERNELS / f).read_text()
            assert len(text.splitlines()) <= MAX_OWN_LINES, f"{f}: {len(text.splitlines())} lines"
            assert not re.search(r"\bbk_(at|sh|ch)\w*\(", text), f"{f} evaluates rotation maps itself"
            assert "rod_math.h" not in text, f


def test_no_generated_rod_file_or_function_is_huge():
    seen = set()
    for p in rod_pairs():
        for f in p["files"]:
            if f in seen:
                continue
            seen.add(f)
            text = (KERNELS / f).read_text()
            assert len(text.splitlines()) <= MAX_FILE_LINES, f"{f}: {len(text.splitlines())} lines"
            fns = functions(text)
            assert fns, f"no functions found in {f}"
            for sig, n in fns.items():
                assert n <= MAX_FUNCTION_LINES, f"{f}: {n} lines in {sig[:60]}"
    assert set(SHARED) <= seen


def test_rod_tangent_operation_count():
    """Derived through the strain measures, the force + tangent of an element
    call costs at most MAX_TANGENT_OPS operations (header of each pair file)."""
    for p in rod_pairs():
        text = (KERNELS / f"{p['element']}_{p['material']}.h").read_text()
        m = re.search(r"force \+ upper tangent (\d+)", text)
        assert m, p
        assert int(m.group(1)) <= MAX_TANGENT_OPS, (p["element"], int(m.group(1)))
