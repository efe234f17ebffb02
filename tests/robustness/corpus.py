# ruff: noqa: E501  (a data file: one case per line reads best)
"""A corpus of malformed, degenerate and extreme inputs for every kind of batcert input.

Every case is a modified copy of a shipped input (bat, ball, protocol, league, study) or a
command line, with the files it needs and the commands to try. ``@REPO@`` in a case's files and
commands stands for the checkout (shipped files named by path). Kinds (the ``category``):
YAML structure and bombs, huge files, non-finite and extreme numbers, degenerate tests, text
(NUL, Latin-1, markup, emoji codes), unit typos, references between files, missing fields and
wrong types, and command lines. ``expect`` says what a case must give: ``invalid`` (exit 2 or 3
before anything runs), ``valid`` (runs) or ``either``. test_corpus.py runs them all.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

MAIN = Path(__file__).resolve().parents[2]


@dataclass
class Case:
    id: str
    category: str
    desc: str
    kind: str  # bat | ball | protocol | league | study | cmd
    main: str  # the case's main file name
    expect: str  # invalid | valid | either
    content: str | bytes
    files: dict[str, str | bytes] = field(default_factory=dict)
    commands: list[list[str]] | None = None
    # a defect this case finds that is not fixed yet: the test expects it to fail (strict xfail)
    # until the fix lands and the marker is removed
    known: str = ""
    links: dict[str, str] = field(default_factory=dict)  # symlink name -> target (in the case dir)


SOLID = """name: Ash 34 in (fuzz)
reference: fuzz copy of bats/ash-34.yaml
version: "1.0"
construction: solid
length: 860 mm
profile:
  - [0.0 in, 2.40 in]
  - [0.5 in, 2.40 in]
  - [0.9 in, 1.45 in]
  - [1.5 in, 1.18 in]
  - [3.0 in, 1.02 in]
  - [6.0 in, 0.96 in]
  - [10.0 in, 0.98 in]
  - [13.0 in, 1.06 in]
  - [16.0 in, 1.32 in]
  - [19.0 in, 1.75 in]
  - [22.0 in, 2.22 in]
  - [24.0 in, 2.45 in]
  - [26.0 in, 2.56 in]
  - [28.0 in, 2.61 in]
  - [32.6 in, 2.61 in]
  - [33.4 in, 2.52 in]
  - [860 mm, 2.30 in]
material: ash-bat
measured:
  pivot: 150 mm
  mass: 906 g
  cg: 429 mm
  moi: 0.209 kg*m^2
reconcile: density-profile
"""

HOLLOW = """name: Aluminium 34 in (fuzz)
reference: fuzz copy of bats/aluminium-34.yaml
version: "1.0"
construction: hollow
length: 860 mm
profile:
  - [0.0 in, 2.30 in]
  - [0.4 in, 2.30 in]
  - [0.8 in, 1.20 in]
  - [1.5 in, 0.98 in]
  - [9.0 in, 0.95 in]
  - [11.0 in, 1.00 in]
  - [14.0 in, 1.30 in]
  - [17.0 in, 1.85 in]
  - [20.0 in, 2.45 in]
  - [21.5 in, 2.625 in]
  - [860 mm, 2.625 in]
wall:
  - [0 in, 1.8 mm]
  - [11 in, 1.8 mm]
  - [20 in, 2.2 mm]
  - [22 in, 2.7 mm]
  - [860 mm, 2.7 mm]
material: aluminium-7050
measured:
  pivot: 150 mm
  mass: 863 g
  cg: 418 mm
  moi: 0.198 kg*m^2
reconcile: point-masses
"""

R161 = (MAIN / "bats/r161.yaml").read_text()
BBCOR_ALLOY = (MAIN / "bats/bbcor-alloy-34.yaml").read_text()

BALL = """name: Collegiate baseball (fuzz)
version: "1.0"
mass: 5.125 oz
radius: 36.9 mm
cor:
  - [1 m/s, 0.64]
  - [85 ft/s, 0.546]
  - [71 m/s, 0.50]
contact:
  model: power-law-hysteresis
  k1: 6.53e7
  alpha: 1.84
"""

BALL_PROTO = """id: fuzz-ball-proto
title: BBCOR with the fuzz ball
reference: fuzz
version: "1.0"
pivot: 6 in
ball: ball.yaml
conditions:
  - name: stationary-bat
    pitch_speed: 136 mph
    bat_angular_speed: 0 rad/s
impact_location:
  rule: max-metric
  window: [2 in, 12 in]
metric: bbcor
aggregate: mean
limit:
  max: 0.500
"""

BBCOR = """id: fuzz-bbcor
title: NCAA BBCOR (fuzz)
reference: fuzz copy of protocols/ncaa-bbcor.yaml
version: "1.0"
pivot: 6 in
ball: collegiate-baseball
conditions:
  - name: stationary-bat
    pitch_speed: 136 mph
    bat_angular_speed: 0 rad/s
impact_location:
  rule: max-metric
  window: [2 in, 12 in]
metric: bbcor
aggregate: mean
limit:
  max: 0.500
  tolerance: 0.0
"""

BESR = """id: fuzz-besr
title: NCAA BESR (fuzz)
reference: fuzz copy of protocols/ncaa-besr.yaml
version: "1.0"
pivot: 6 in
ball: collegiate-baseball
conditions:
  - name: pitched-and-swung
    pitch_speed: 70 mph
    bat_speed: 66 mph
    bat_speed_from_tip: 6 in
impact_location:
  rule: sweet-spot
  window: [2 in, 12 in]
metric: besr
aggregate: mean
limit:
  max: 0.728
"""

PROPOSED = """id: fuzz-proposed
title: Matched relative speed (fuzz)
reference: fuzz copy of protocols/proposed.yaml
version: "1.0"
pivot: 150 mm
ball: collegiate-baseball
conditions:
  - name: stationary-bat
    relative_speed: 60 m/s
    stationary: bat
  - name: stationary-ball
    relative_speed: 60 m/s
    stationary: ball
  - name: pitched-and-swung
    relative_speed: 60 m/s
    pitch_speed: 31 m/s
impact_location:
  rule: sweet-spot
metric: bpf
aggregate: mean
"""

ASTM = """id: fuzz-astm
title: BPF at the COP (fuzz)
reference: fuzz copy of protocols/astm-bpf.yaml
version: "1.0"
pivot: 150 mm
ball: collegiate-baseball
conditions:
  - name: stationary-bat
    pitch_speed: 31 m/s
    bat_angular_speed: 0 rad/s
impact_location:
  rule: cop
metric: bpf
aggregate: mean
limit:
  max: 1.15
"""

EXIT = """id: fuzz-exit
title: Exit speed at a fixed point (fuzz)
reference: fuzz
version: "1.0"
pivot: 6 in
ball: collegiate-baseball
conditions:
  - name: pitched-and-swung
    pitch_speed: 70 mph
    bat_angular_speed: 53 rad/s
impact_location:
  rule: fixed-from-tip
  from_tip: 6 in
metric: exit-speed
aggregate: mean
limit:
  max: 97 mph
  tolerance: 1 mph
"""

LEAGUE = """id: fuzz-league
title: Fuzz league (copy of ncaa)
reference: fuzz
version: "1.0"
rules:
  - id: length
    kind: max-length
    limit: 36 in
    source: fuzz
    confidence: M
  - id: barrel
    kind: max-barrel-diameter
    limit: 2.625 in
    source: fuzz
    confidence: M
  - id: handle
    kind: min-diameter
    limit: 0.8 in
    source: fuzz
    confidence: M
  - id: drop
    kind: max-drop
    limit: 3
    applies_to: non-wood
    source: fuzz
    confidence: M
  - id: bbcor
    kind: performance
    protocol: ncaa-bbcor
    limit: 0.500
    applies_to: non-wood
    source: fuzz
    confidence: M
  - id: construction
    kind: construction
    required: solid
    applies_to: wood
    source: fuzz
    confidence: M
  - id: material
    kind: material
    allowed: [wood, metal]
    source: fuzz
    confidence: M
"""

STUDY = """id: fuzz-study
title: Fuzz study (copy of smith2001)
reference: fuzz
version: "1.0"
bats: [ash-34, aluminium-34]
protocols:
  - @REPO@/protocols/studies/smith2001-bpf-cop.yaml
  - @REPO@/protocols/studies/smith2001-besr-sweet-spot.yaml
  - @REPO@/protocols/studies/smith2001-bpf-sweet-spot.yaml
  - proposed
claims:
  - id: disagree
    statement: methods disagree
    check: sign-disagreement
    protocols: [smith2001-bpf-cop, smith2001-besr-sweet-spot]
    tolerance: 0.005
  - id: consistent
    statement: proposal consistent
    check: consistent-across-conditions
    protocols: [proposed]
    compare_with: [smith2001-bpf-cop, smith2001-besr-sweet-spot]
    tolerance: 0.005
  - id: advantage
    statement: proposal shows the advantage
    check: advantage
    expected: shown
    protocols: [proposed]
    tolerance: 0.005
  - id: lower
    statement: BESR underrates the light bat
    check: lower-than
    protocols: [smith2001-besr-sweet-spot, smith2001-bpf-sweet-spot]
    tolerance: 0.005
  - id: cop
    statement: COP is not the sweet spot
    check: cop-not-sweet-spot
    protocols: [smith2001-bpf-sweet-spot, proposed]
    location_tolerance: 10 mm
  - id: offset
    statement: offsets differ
    check: cop-offset-differs
    protocols: [smith2001-bpf-sweet-spot, proposed]
    location_tolerance: 10 mm
  - id: moves
    statement: sweet spot moves less than rigid
    check: sweet-spot-moves-less-than-rigid
    protocols: [smith2001-bpf-sweet-spot]
    factor: 0.5
"""

BASES = {"solid": SOLID, "hollow": HOLLOW, "ball": BALL, "bbcor": BBCOR, "besr": BESR,
         "proposed": PROPOSED, "astm": ASTM, "exit": EXIT, "league": LEAGUE, "study": STUDY}
KIND_OF = {"solid": "bat", "hollow": "bat", "ball": "ball", "bbcor": "protocol",
           "besr": "protocol", "proposed": "protocol", "astm": "protocol", "exit": "protocol",
           "league": "league", "study": "study"}

ALL: list[Case] = []


def sub(text: str, old: str, new: str, count: int = 1) -> str:
    assert old in text, (old, text[:80])
    return text.replace(old, new, count)


def add(cid: str, category: str, desc: str, kind: str, content: str | bytes, *,
        expect: str = "either", files: dict[str, str | bytes] | None = None,
        commands: list[list[str]] | None = None, main: str | None = None) -> None:
    ext = {"bat": "yaml", "ball": "yaml"}.get(kind, "yaml")
    main = main or f"{kind}.{ext}"
    ALL.append(Case(cid, category, desc, kind, main, expect, content, files or {}, commands))


def mod(cid: str, category: str, desc: str, base: str, *edits: tuple[str, str],
        expect: str = "either", append: str = "", commands=None) -> None:
    """A case from a base text with (old, new) replacements and optional appended text."""
    text = BASES[base]
    for old, new in edits:
        text = sub(text, old, new)
    text += append
    kind = KIND_OF[base]
    files = {"proto.yaml": BALL_PROTO} if kind == "ball" else None
    add(cid, category, desc, kind, text, expect=expect, files=files, commands=commands)


def raw(cid: str, category: str, desc: str, kind: str, content, *, expect="invalid",
        commands=None) -> None:
    files = {"proto.yaml": BALL_PROTO} if kind == "ball" else None
    add(cid, category, desc, kind, content, expect=expect, files=files, commands=commands)


# ------------------------------------------------------------------------------------------
# 1. YAML structure
# ------------------------------------------------------------------------------------------
def yaml_structure() -> None:
    c = "1-yaml"
    bomb = "a: &a [x, x, x, x, x, x, x, x, x]\n"
    prev = "a"
    for i in range(1, 10):
        name = chr(ord("a") + i)
        bomb += f"{name}: &{name} [{', '.join(['*' + prev] * 9)}]\n"
        prev = name
    raw("yaml-billion-laughs-bat", c, "billion laughs: 9 levels of 9 aliases as extra keys of "
        "a bat", "bat", SOLID + bomb)
    raw("yaml-billion-laughs-only", c, "billion laughs alone (no bat fields)", "bat", bomb)
    bomb_name = SOLID.replace("name: Ash 34 in (fuzz)\n", "") + bomb + "name: *j\n"
    raw("yaml-billion-laughs-in-name", c, "billion-laughs list used as the bat's name (text "
        "field)", "bat", bomb_name)
    bomb_prof = SOLID.split("profile:")[0] + "x0: &p [0 in, 1 in]\n" + "".join(
        f"x{i}: &p{i} [*{'p' if i == 1 else 'p' + str(i - 1)}, *{'p' if i == 1 else 'p' + str(i - 1)}]\n"
        for i in range(1, 22)) + "profile: *p21\nmaterial: ash\n"
    raw("yaml-alias-bomb-profile", c, "2^21 nested alias list as profile", "bat", bomb_prof)
    raw("yaml-recursive-alias", c, "recursive alias (&a [*a])", "bat",
        SOLID + "extra: &r [1, *r]\n")
    raw("yaml-recursive-alias-map", c, "recursive mapping alias as measured", "bat",
        sub(SOLID, "measured:\n", "measured: &m\n  self: *m\n"))
    raw("yaml-recursive-alias-name", c, "recursive alias used as the name", "bat",
        sub(SOLID, "name: Ash 34 in (fuzz)", "name: &n [*n]"))
    raw("yaml-merge-key", c, "YAML merge key << in measured", "bat",
        sub(SOLID, "measured:\n", "defaults: &d {pivot: 150 mm}\nmeasured:\n  <<: *d\n"))
    deep = "[" * 5000 + "]" * 5000
    raw("yaml-deep-5000-flow", c, "5000-deep flow sequence as a field value", "bat",
        SOLID + f"extra: {deep}\n")
    raw("yaml-deep-5000-name", c, "5000-deep flow sequence as name", "bat",
        sub(SOLID, "name: Ash 34 in (fuzz)", "name: " + deep))
    deepmap = "{a: " * 5000 + "1" + "}" * 5000
    raw("yaml-deep-5000-map", c, "5000-deep flow mapping", "bat", SOLID + f"extra: {deepmap}\n")
    raw("yaml-deep-1000-block", c, "1000-deep block mapping (one-space indents, 0.5 MB)", "bat",
        SOLID + "extra:\n" + "".join(" " * (i + 1) + f"k{i}:\n" for i in range(1000))
        + " " * 1001 + "v: 1\n")
    raw("yaml-deep-5000-profile", c, "5000-deep list as profile item", "bat",
        sub(SOLID, "  - [0.0 in, 2.40 in]\n", f"  - {deep}\n"))
    deep_proto = sub(BBCOR, "window: [2 in, 12 in]", "window: " + deep)
    raw("yaml-deep-5000-protocol", c, "5000-deep list as protocol window", "protocol", deep_proto)
    raw("yaml-empty", c, "empty file", "bat", "")
    raw("yaml-only-comments", c, "only comments", "bat", "# nothing\n# here\n")
    raw("yaml-only-doc-marker", c, "only '---'", "bat", "---\n")
    raw("yaml-null-doc", c, "document '~'", "bat", "~\n")
    raw("yaml-top-list", c, "list at top level", "bat", "- a\n- b\n")
    raw("yaml-top-scalar", c, "scalar at top level", "bat", "hello\n")
    raw("yaml-two-docs", c, "two YAML documents", "bat", SOLID + "---\n" + SOLID)
    raw("yaml-dup-key-top", c, "duplicate key 'length'", "bat", SOLID + "length: 34 in\n")
    raw("yaml-dup-key-nested", c, "duplicate key inside measured", "bat",
        sub(SOLID, "  mass: 906 g\n", "  mass: 906 g\n  mass: 900 g\n"))
    raw("yaml-tabs-indent", c, "tab indentation", "bat",
        sub(SOLID, "  pivot: 150 mm", "\tpivot: 150 mm"))
    raw("yaml-tab-in-value", c, "tab inside a quantity '34\\tin'", "bat",
        sub(SOLID, "length: 860 mm", "length: 860\tmm"), expect="either")
    raw("yaml-binary-garbage", c, "random binary bytes", "bat", bytes(range(256)) * 20)
    raw("yaml-nul-bytes", c, "NUL byte in the name", "bat",
        sub(SOLID, "name: Ash 34 in (fuzz)", "name: Ash\x00 34").encode())
    raw("yaml-nul-only", c, "file of NUL bytes", "bat", b"\x00" * 100)
    raw("yaml-latin1", c, "Latin-1 byte (0xe9) in the name", "bat",
        sub(SOLID, "name: Ash 34 in (fuzz)", "name: Ash caf\xe9").encode("latin-1"))
    raw("yaml-latin1-protocol", c, "Latin-1 byte in a protocol title", "protocol",
        sub(BBCOR, "title: NCAA BBCOR (fuzz)", "title: caf\xe9").encode("latin-1"))
    raw("yaml-bom", c, "UTF-8 BOM at the start", "bat", ("\ufeff" + SOLID).encode("utf-8"),
        expect="either")
    raw("yaml-utf16", c, "UTF-16 encoded file", "bat", SOLID.encode("utf-16"), expect="either")
    raw("yaml-crlf", c, "CRLF line endings", "bat", SOLID.replace("\n", "\r\n").encode(),
        expect="either")
    raw("yaml-cr-only", c, "old-Mac CR line endings", "bat", SOLID.replace("\n", "\r").encode(),
        expect="either")
    raw("yaml-crlf-error", c, "CRLF file with an error on line 5 (caret/line check)", "bat",
        sub(SOLID, "length: 860 mm", "length: 860").replace("\n", "\r\n").encode())
    raw("yaml-nonstr-key", c, "integer and null keys", "bat", SOLID + "1: x\n~: y\n")
    raw("yaml-complex-key", c, "complex (mapping) key", "bat", SOLID + "? {a: 1}\n: x\n")
    raw("yaml-python-tag", c, "!!python/object tag", "bat",
        sub(SOLID, "name: Ash 34 in (fuzz)", "name: !!python/object/apply:os.system ['echo hi']"))
    raw("yaml-binary-tag", c, "!!binary value for name", "bat",
        sub(SOLID, "name: Ash 34 in (fuzz)", "name: !!binary aGVsbG8="), expect="either")
    raw("yaml-unknown-tag", c, "custom !tag", "bat",
        sub(SOLID, "length: 860 mm", "length: !inch 34"))
    raw("yaml-timestamp-name", c, "name is a timestamp (2001-01-01)", "bat",
        sub(SOLID, "name: Ash 34 in (fuzz)", "name: 2001-12-14"), expect="either")
    raw("yaml-set-tag", c, "!!set as profile", "bat",
        sub(SOLID, "profile:\n", "profile: !!set {a, b}\nxprofile:\n"))
    raw("yaml-unclosed-bracket", c, "unclosed flow sequence", "bat",
        sub(SOLID, "  - [0.0 in, 2.40 in]", "  - [0.0 in, 2.40 in"))
    raw("yaml-bad-indent", c, "bad indentation", "bat", sub(SOLID, "  mass: 906 g", "    mass: 906 g"))
    raw("yaml-anchor-undefined", c, "undefined alias *nope", "bat", SOLID + "x: *nope\n")
    raw("yaml-huge-scalar-line", c, "control char U+0007 in name", "bat",
        sub(SOLID, "name: Ash 34 in (fuzz)", 'name: "bell\\a"'), expect="either")
    raw("yaml-int-overflow", c, "sweep_points 10**400", "protocol",
        sub(BBCOR, "  window: [2 in, 12 in]", "  window: [2 in, 12 in]\n  sweep_points: 1" + "0" * 400))


def huge_files() -> None:
    c = "1-yaml"
    # ~3 MB bat: a profile with 90,000 stations (each 36 bytes), above the 2 MB limit
    n = 90_000
    step = 0.86 / (n + 1)
    lines = "".join(f"  - [{(i + 1) * step:.9f} m, 60 mm]\n" for i in range(n))
    text = SOLID.split("profile:")[0] + "profile:\n" + lines + "material: ash-bat\n"
    raw("yaml-huge-3mb-profile", c, f"~3 MB bat: profile with {n} stations", "bat", text,
        expect="either", commands=[["validate", "{f}"], ["inspect", "{f}", "--json"],
                                   ["run", "{f}", "-p", "ncaa-bbcor", "--out", "{out}"]])
    comment = "# " + "x" * 1000 + "\n"
    text = SOLID + comment * 3_000
    raw("yaml-huge-3mb-comments", c, "valid bat followed by 3 MB of comments", "bat", text,
        expect="invalid", commands=[["validate", "{f}"], ["inspect", "{f}", "--json"]])
    text = sub(SOLID, "name: Ash 34 in (fuzz)", "name: " + "N" * 3_000_000)
    raw("yaml-huge-3mb-name", c, "bat whose name is 3 MB", "bat", text, expect="either",
        commands=[["validate", "{f}"], ["inspect", "{f}", "--json"],
                  ["run", "{f}", "-p", "ncaa-bbcor", "--engine", "rigid", "--out", "{out}"]])
    text = SOLID + "".join(f"junk{i}: {i}\n" for i in range(200_000))
    raw("yaml-huge-200k-unknown-keys", c, "200,000 unknown keys (~2.7 MB)", "bat", text,
        commands=[["validate", "{f}"]])


# ------------------------------------------------------------------------------------------
# 2. Numbers
# ------------------------------------------------------------------------------------------
BAD_QUANTITIES = ["nan", ".nan", "nan m", "inf", ".inf", "-.inf", "1e309 m", "-1e309 m",
                  "1e308 m", "0 m", "-1 m", "1e-300 m", "1e30 m", "1000000 in", ".NaN",
                  "NaN mm", "inf in", "1e309 in"]


def numbers() -> None:
    c = "2-numbers"
    # bat: every quantity field with a few extreme values
    bat_fields = {
        "length": ("length: 860 mm", "length: {}", ["1e309 m", "1e-300 m", "0 m", "-860 mm",
                                                   "1000000 in", ".nan", "nan m"]),
        "profile-diam": ("  - [28.0 in, 2.61 in]", "  - [28.0 in, {}]",
                         ["1e309 in", "1e30 m", "1e-300 m", "0 in"]),
        "profile-pos": ("  - [28.0 in, 2.61 in]", "  - [{}, 2.61 in]", ["1e309 in", "-1e309 in"]),
        "knob_mass": ("material: ash-bat", "material: ash-bat\nknob_mass: {}",
                      ["1e309 g", "1e30 kg", "-5 g", "1e-300 kg"]),
        "end_cap_mass": ("material: ash-bat", "material: ash-bat\nend_cap_mass: {}",
                         ["1e309 g", "1e30 kg"]),
        "slice_length": ("material: ash-bat", "material: ash-bat\nslice_length: {}",
                         ["1e-300 m", "0.01 mm", "1e-5 m", "0.02 m"]),
        "shear_correction": ("material: ash-bat", "material: ash-bat\nshear_correction: {}",
                             [".nan", "1e-300", "nan"]),
        "measured.mass": ("  mass: 906 g", "  mass: {}", ["1e309 kg", "1e30 kg", "1e-300 kg",
                                                         "0 g", "inf kg"]),
        "measured.cg": ("  cg: 429 mm", "  cg: {}", ["1e309 m", "1e-300 m", "0 m", "2 m"]),
        "measured.moi": ("  moi: 0.209 kg*m^2", "  moi: {}", ["1e309 kg*m^2", "1e30 kg*m^2",
                                                             "1e-300 kg*m^2", "0 kg*m^2"]),
        "measured.pivot": ("  pivot: 150 mm", "  pivot: {}", ["1e309 m", "-1 mm", "0 m",
                                                             "900 mm"]),
    }
    for fname, (old, tmpl, values) in bat_fields.items():
        for v in values:
            cid = f"num-bat-{fname}-{v}".replace(" ", "").replace("*", "").replace("^", "")
            mod(cid, c, f"bat {fname} = {v}", "solid", (old, tmpl.format(v)))
    # inline material
    mat = ("material: ash-bat", "material:\n  density: {d}\n  youngs_modulus: {e}\n"
           "  shear_modulus: {g}\n  poisson_ratio: {nu}\n  loss_factor: {eta}")
    base = dict(d="600 kg/m^3", e="15 GPa", g="0.868 GPa", nu="0.3", eta="0.01")
    for key, v in [("d", "1e309 kg/m^3"), ("d", "1e-300 kg/m^3"), ("d", "1e30 kg/m^3"),
                   ("e", "1e309 Pa"), ("e", "1e-300 Pa"), ("e", "1e30 GPa"), ("g", "1e-300 Pa"),
                   ("g", "1e309 Pa"), ("nu", ".nan"), ("nu", "nan"), ("nu", "0.5"),
                   ("eta", ".nan"), ("eta", "0.5"), ("eta", "nan"), ("nu", "0")]:
        vals = {**base, key: v}
        mod(f"num-material-{key}-{v}".replace(" ", "").replace("/", "").replace("^", ""), c,
            f"inline material {key} = {v}", "solid", (mat[0], mat[1].format(**vals)))
    # hollow: wall values and barrel measurements
    for v in ["1e309 mm", "1e-300 m", "0 mm", "nan mm", "20 mm", "40 mm"]:
        mod(f"num-wall-const-{v}".replace(" ", ""), c, f"constant wall {v}", "hollow",
            ("wall:\n  - [0 in, 1.8 mm]\n  - [11 in, 1.8 mm]\n  - [20 in, 2.2 mm]\n"
             "  - [22 in, 2.7 mm]\n  - [860 mm, 2.7 mm]", f"wall: {v}"))
    for v in ["1e309 mm", "1e-300 m", "33.3 mm"]:
        mod(f"num-wall-station-{v}".replace(" ", ""), c, f"wall station thickness {v}", "hollow",
            ("  - [22 in, 2.7 mm]", f"  - [22 in, {v}]"))
    comp = "\n  barrel_compression:\n    force: {f}\n    deflection: {x}\n    position: {p}\n" \
           "    platen_width: {w}\n"
    cbase = dict(f="220 lbf", x="1 mm", p="6 in", w="1 in")
    for key, v in [("f", "1e309 N"), ("f", "1e-300 N"), ("x", "1e-300 m"), ("x", "1e309 m"),
                   ("x", "100 mm"), ("p", "40 in"), ("p", "1e-300 m"), ("w", "1e309 m"),
                   ("w", "1e-300 m"), ("w", "40 in")]:
        vals = {**cbase, key: v}
        mod(f"num-compression-{key}-{v}".replace(" ", ""), c, f"barrel_compression {key} = {v}",
            "hollow", ("  moi: 0.198 kg*m^2", "  moi: 0.198 kg*m^2" + comp.format(**vals).rstrip()))
    for v in ["1e309 Hz", "1e-300 Hz", "1e9 Hz", "1 Hz", "nan Hz"]:
        mod(f"num-hoop-{v}".replace(" ", ""), c, f"hoop_frequency {v}", "hollow",
            ("  moi: 0.198 kg*m^2", f"  moi: 0.198 kg*m^2\n  hoop_frequency: {v}"))
    for v in ["1e309 Hz", "1e-300 Hz", "1e9 Hz", "0.001 Hz"]:
        mod(f"num-bendfreq-{v}".replace(" ", ""), c, f"first_bending_frequency {v}", "solid",
            ("  moi: 0.209 kg*m^2", f"  moi: 0.209 kg*m^2\n  first_bending_frequency: {v}"))
    for v in ["1e309 s", "1e-300 s", "100 s"]:
        mod(f"num-pendulum-{v}".replace(" ", ""), c, f"pendulum_period {v}", "solid",
            ("  moi: 0.209 kg*m^2", f"  pendulum_period: {v}"))
    for v in ["1e309 m", "1e-300 m", "10 m"]:
        mod(f"num-gyration-{v}".replace(" ", ""), c, f"radius_of_gyration {v}", "solid",
            ("  moi: 0.209 kg*m^2", f"  radius_of_gyration: {v}"))
    mod("num-balance-point-huge", c, "balance_point 1e309 m", "solid",
        ("  cg: 429 mm", "  balance_point: 1e309 m"))
    # ball
    for key, old, vals in [
        ("mass", "mass: 5.125 oz", ["1e309 kg", "1e30 kg", "1e-300 kg", "0 kg", "-1 oz"]),
        ("radius", "radius: 36.9 mm", ["1e309 m", "1e-300 m", "1 m", "0 mm", "500 mm"]),
        ("k1", "k1: 6.53e7", [".nan", "nan", ".inf", "1e309", "1e-300", "0", "-1", "6.53e+300"]),
        ("alpha", "alpha: 1.84", [".nan", "nan", "1", "3", "NaN", ".inf"]),
        ("cor-speed", "  - [85 ft/s, 0.546]", ["[1e309 m/s, 0.546]", "[nan m/s, 0.5]"]),
        ("cor-value", "  - [85 ft/s, 0.546]", ["[85 ft/s, .nan]", "[85 ft/s, 1e-300]",
                                               "[85 ft/s, 1]", "[85 ft/s, '0.5']"]),
    ]:
        for v in vals:
            new = old.split(":")[0] + ": " + v if key not in ("cor-speed", "cor-value") else \
                "  - " + v
            mod(f"num-ball-{key}-{v}".replace(" ", "").replace("/", "").replace("[", "")
                .replace("]", "").replace(",", "_").replace("'", ""), c, f"ball {key} = {v}",
                "ball", (old, new))
    mod("num-ball-single-cor-1", c, "ball with a single COR point of 1.0", "ball",
        ("  - [1 m/s, 0.64]\n  - [85 ft/s, 0.546]\n  - [71 m/s, 0.50]", "  - [58 m/s, 1]"))
    mod("num-ball-cor-tiny", c, "ball COR 1e-300 everywhere", "ball",
        ("  - [1 m/s, 0.64]\n  - [85 ft/s, 0.546]\n  - [71 m/s, 0.50]", "  - [58 m/s, 1e-300]"))
    # protocol numbers
    for key, old, tmpl, vals in [
        ("pitch", "    pitch_speed: 136 mph", "    pitch_speed: {}",
         ["1e309 mph", "1e308 mph", "1e30 m/s", "1e-300 m/s", "nan mph", "-10 mph", "3e8 m/s"]),
        ("w1", "    bat_angular_speed: 0 rad/s", "    bat_angular_speed: {}",
         ["1e309 rad/s", "1e30 rad/s", "-5 rad/s", "1e-300 rad/s"]),
        ("pivot", "pivot: 6 in", "pivot: {}", ["1e309 m", "-1 in", "0 in", "1e-300 m", "40 in",
                                               "33.9 in"]),
        ("limit", "  max: 0.500", "  max: {}", [".nan", "nan", ".inf", "-.inf", "1e309",
                                                "-1e309", "0.5 mph"]),
        ("tolerance", "  tolerance: 0.0", "  tolerance: {}", [".nan", "nan", ".inf", "1e309",
                                                             "-0.1"]),
        ("resolution", "  window: [2 in, 12 in]", "  window: [2 in, 12 in]\n  resolution: {}",
         ["1e-9 m", "1e-300 m", "1e309 m", "1 m", "0.1 mm"]),
        ("sweep", "  window: [2 in, 12 in]", "  window: [2 in, 12 in]\n  sweep_points: {}",
         ["5", "2001", "4", "2002", "5.5", "'10'", "0x10", "1_000"]),
    ]:
        for v in vals:
            mod(f"num-proto-{key}-{v}".replace(" ", "").replace("/", "").replace("'", ""), c,
                f"protocol (ncaa-bbcor copy) {key} = {v}", "bbcor", (old, tmpl.format(v)))
    for key, old, tmpl, vals in [
        ("bat_speed", "    bat_speed: 66 mph", "    bat_speed: {}",
         ["1e309 mph", "1e308 mph", "3e8 m/s", "0 mph", "1e-300 m/s"]),
        ("from_tip", "    bat_speed_from_tip: 6 in", "    bat_speed_from_tip: {}",
         ["1e-300 m", "1e309 m"]),
    ]:
        for v in vals:
            mod(f"num-besr-{key}-{v}".replace(" ", "").replace("/", ""), c,
                f"protocol (ncaa-besr copy) {key} = {v}", "besr", (old, tmpl.format(v)))
    for v in ["1e309 m/s", "1e308 m/s", "1e-300 m/s", "3e8 m/s", "nan m/s"]:
        mod(f"num-relative-{v}".replace(" ", "").replace("/", ""), c,
            f"matched relative_speed {v} (proposed copy)", "proposed",
            ("  - name: stationary-bat\n    relative_speed: 60 m/s",
             f"  - name: stationary-bat\n    relative_speed: {v}"))
    mod("num-relative-pitch-just-below", c, "matched pitch 59.9999999 m/s below relative 60",
        "proposed", ("    pitch_speed: 31 m/s", "    pitch_speed: 59.99999999999 m/s"))
    for v in ["nan mph", "1e309 mph", "-1e309 mph", "1e-300 mph", "97", "-97 mph", ".nan"]:
        mod(f"num-exit-limit-{v}".replace(" ", ""), c, f"exit-speed limit max = {v}", "exit",
            ("  max: 97 mph", f"  max: {v}"))
    for v in ["1e309 mph", "1e309 m/s"]:
        mod(f"num-exit-tol-{v}".replace(" ", "").replace("/", ""), c, f"exit-speed tolerance {v}",
            "exit", ("  tolerance: 1 mph", f"  tolerance: {v}"))
    # league numbers
    for key, old, tmpl, vals in [
        ("length", "    limit: 36 in", "    limit: {}", ["1e309 in", "nan in", "0 in", "-1 in",
                                                          "36", "1e-300 m"]),
        ("drop", "    limit: 3\n", "    limit: {}\n", [".nan", "nan", ".inf", "-.inf", "1e309",
                                                       "3 in", "'3'"]),
        ("perf", "    limit: 0.500", "    limit: {}", [".nan", "nan", "1e309", "-.inf",
                                                       "0.5 mph"]),
        ("perf-tol", "    limit: 0.500", "    limit: 0.500\n    tolerance: {}",
         [".nan", "nan", "1e309"]),
        ("handle", "    limit: 0.8 in", "    limit: {}", ["1e309 in", "0 in"]),
        ("from-len", "    kind: max-length", "    kind: max-length\n    applies_from_length: {}",
         ["1e309 in", "nan in", "1e-300 m"]),
        ("below-len", "    kind: max-length", "    kind: max-length\n    applies_below_length: {}",
         ["1e309 in", "1e-300 m"]),
    ]:
        for v in vals:
            mod(f"num-league-{key}-{v}".replace(" ", "").replace("'", ""), c,
                f"league {key} = {v}", "league", (old, tmpl.format(v)))
    # study claim numbers
    for key, old, tmpl, vals in [
        ("tolerance", "    tolerance: 0.005\n  - id: consistent",
         "    tolerance: {}\n  - id: consistent", [".nan", "nan", ".inf", "1e309", "-1"]),
        ("location_tolerance", "    location_tolerance: 10 mm", "    location_tolerance: {}",
         ["nan mm", "1e309 m", "-1 mm", ".nan"]),
        ("factor", "    factor: 0.5", "    factor: {}", [".nan", "nan", "1e-300", "1"]),
    ]:
        for v in vals:
            mod(f"num-study-{key}-{v}".replace(" ", ""), c, f"study claim {key} = {v}", "study",
                (old, tmpl.format(v)))


# ------------------------------------------------------------------------------------------
# 3. Degenerate tests and geometry
# ------------------------------------------------------------------------------------------
def degenerate() -> None:
    c = "3-degenerate"
    mod("deg-stationary-bat-pitch0", c, "stationary bat (w1 0) and pitch 0: nothing moves",
        "bbcor", ("    pitch_speed: 136 mph", "    pitch_speed: 0 mph"))
    mod("deg-stationary-ball-w0", c, "stationary ball (pitch 0) with bat_angular_speed 0",
        "astm", ("    pitch_speed: 31 m/s", "    pitch_speed: 0 m/s"))
    mod("deg-besr-both-zero", c, "BESR: pitch 0 and bat_speed 0", "besr",
        ("    pitch_speed: 70 mph", "    pitch_speed: 0 mph"), ("    bat_speed: 66 mph",
                                                               "    bat_speed: 0 mph"))
    mod("deg-exit-both-zero", c, "exit-speed metric, fixed point, all speeds 0", "exit",
        ("    pitch_speed: 70 mph", "    pitch_speed: 0 mph"),
        ("    bat_angular_speed: 53 rad/s", "    bat_angular_speed: 0 rad/s"))
    mod("deg-stationary-ball-bpf-w0", c, "stationary-ball protocol with w1 = 0, sweet spot",
        "proposed", ("  - name: stationary-bat\n    relative_speed: 60 m/s\n    stationary: bat\n"
                     "  - name: stationary-ball\n    relative_speed: 60 m/s\n    stationary: ball\n"
                     "  - name: pitched-and-swung\n    relative_speed: 60 m/s\n    pitch_speed: 31 m/s",
                     "  - name: nothing\n    pitch_speed: 0 m/s\n    bat_angular_speed: 0 rad/s"))
    # bat_speed_from_tip at / beyond the pivot: bat 34 in, pivot 6 in -> 28 in from tip
    for v, what in [("707.6 mm", "exactly at the pivot of ash-34 (860 mm - 6 in)"),
                    ("28 in", "beyond the pivot of ash-34, at the pivot of a 34 in bat"), ("27.999999 in", "just before the pivot"),
                    ("30 in", "beyond the pivot"), ("34 in", "at the knob"), ("100 in", "far off the bat")]:
        mod(f"deg-besr-from-tip-{v}".replace(" ", ""), c, f"bat_speed_from_tip {v}: {what}",
            "besr", ("    bat_speed_from_tip: 6 in", f"    bat_speed_from_tip: {v}"))
    # ash-34: 860 mm, bbcor pivot 6 in (152.4 mm): tip - pivot = 707.6 mm
    for v, what in [("707.6 mm", "at the pivot"), ("707 mm", "just short of the pivot"),
                    ("800 mm", "beyond the pivot"), ("900 mm", "beyond the knob"),
                    ("1e-9 m", "at the tip")]:
        mod(f"deg-fixed-from-tip-{v}".replace(" ", ""), c, f"fixed-from-tip {v}: {what}",
            "exit", ("  from_tip: 6 in", f"  from_tip: {v}"))
    for win, what in [("[2 in, 6 in, 12 in]", "three items"), ("[12 in, 2 in]", "reversed"),
                      ("[6 in, 6 in]", "zero width"), ("[2 in, 30 in]", "past the pivot"),
                      ("[2 in, 27.85 in]", "just short of the pivot (27.86 in)"),
                      ("[0 in, 12 in]", "starts at the tip"), ("[2 in]", "one item"),
                      ("[]", "empty"), ("[2 in, 2.0000001 in]", "width 2.5 nm"),
                      ("[2 in, 12 in, oops]", "three items, third not a length"),
                      ("[1e-300 m, 2e-300 m]", "1e-300 m wide at the tip"),
                      ("[-1 in, 12 in]", "negative start"),
                      ("{a: 1}", "mapping")]:
        mod(f"deg-window-{what}".replace(" ", "-").replace("(", "").replace(")", "")
            .replace(".", ""), c, f"window {win}: {what}", "bbcor",
            ("  window: [2 in, 12 in]", f"  window: {win}"))
    for win, what in [("[2 in, 6 in, 12 in]", "three items"), ("[6 in, 6 in]", "zero width"),
                      ("[2 in, 30 in]", "past the pivot")]:
        mod(f"deg-window-besr-{what}".replace(" ", "-"), c, f"sweet-spot window {win}: {what}",
            "besr", ("  window: [2 in, 12 in]", f"  window: {win}"))
    mod("deg-window-cop-past-pivot", c, "cop rule with a window past the pivot", "astm",
        ("  rule: cop", "  rule: cop\n  window: [2 in, 40 in]"))
    for v in ["1e-9 m", "1e-12 m", "10 in", "1e-6 m"]:
        mod(f"deg-resolution-{v}".replace(" ", ""), c, f"sweet-spot resolution {v}", "besr",
            ("  window: [2 in, 12 in]", f"  window: [2 in, 12 in]\n  resolution: {v}"))
    for sp in ["5", "2001"]:
        mod(f"deg-sweep-{sp}", c, f"sweep_points {sp} (limit) on matched proposed", "proposed",
            ("  rule: sweet-spot", f"  rule: sweet-spot\n  sweep_points: {sp}"))
    mod("deg-sweep-5-res-1e-9", c, "sweep_points 5 with resolution 1e-9 m", "besr",
        ("  window: [2 in, 12 in]", "  window: [2 in, 12 in]\n  sweep_points: 5\n  resolution: 1e-9 m"))
    mod("deg-free-support", c, "support: free", "bbcor", ("pivot: 6 in", "pivot: 6 in\nsupport: free"),
        expect="either")
    mod("deg-pivot-at-tip", c, "protocol pivot at the tip (860 mm)", "astm",
        ("pivot: 150 mm", "pivot: 860 mm"))
    mod("deg-pivot-0-cop", c, "protocol pivot at the knob (0), cop rule", "astm",
        ("pivot: 150 mm", "pivot: 0 mm"), expect="either")
    mod("deg-pivot-near-tip-cop", c, "pivot 850 mm (10 mm from tip) with cop", "astm",
        ("pivot: 150 mm", "pivot: 850 mm"))
    mod("deg-pivot-beyond-tip", c, "pivot 2 m (off the bat)", "astm", ("pivot: 150 mm", "pivot: 2 m"))
    mod("deg-many-conditions", c, "200 conditions", "bbcor",
        ("  - name: stationary-bat\n    pitch_speed: 136 mph\n    bat_angular_speed: 0 rad/s\n",
         "".join(f"  - name: c{i}\n    pitch_speed: {10 + i} mph\n    bat_angular_speed: 0 rad/s\n"
                 for i in range(200))), expect="valid")
    mod("deg-dup-condition-names", c, "two conditions with the same name", "bbcor",
        ("  - name: stationary-bat\n", "  - name: x\n    pitch_speed: 1 mph\n    bat_angular_speed: 0 rad/s\n"
         "  - name: x\n"), expect="invalid")
    mod("deg-condition-name-unhashable", c, "condition name is a list", "bbcor",
        ("  - name: stationary-bat\n", "  - name: [a, b]\n"), expect="invalid")
    mod("deg-conditions-empty", c, "conditions: []", "bbcor",
        ("conditions:\n  - name: stationary-bat\n    pitch_speed: 136 mph\n    bat_angular_speed: 0 rad/s\n",
         "conditions: []\n"), expect="invalid")
    mod("deg-aggregate-min-max", c, "aggregate: max", "proposed", ("aggregate: mean", "aggregate: max"),
        expect="valid")
    for metric in ["besr", "bpf", "collision-efficiency", "exit-speed", "bbcor"]:
        mod(f"deg-stationary-bat-pitch0-{metric}", c, f"all speeds zero, metric {metric}, cop rule",
            "astm", ("    pitch_speed: 31 m/s", "    pitch_speed: 0 m/s"), ("metric: bpf", f"metric: {metric}"),
            ("limit:\n  max: 1.15\n", ""))
    for metric in ["besr", "bbcor", "collision-efficiency", "exit-speed"]:
        mod(f"deg-stationary-ball-max-metric-{metric}", c, f"stationary ball, max-metric, {metric}",
            "bbcor", ("    pitch_speed: 136 mph", "    pitch_speed: 0 mph"),
            ("    bat_angular_speed: 0 rad/s", "    bat_angular_speed: 53 rad/s"),
            ("metric: bbcor", f"metric: {metric}"), ("limit:\n  max: 0.500\n  tolerance: 0.0\n", ""),
            expect="valid")
    # bat geometry
    prof = "profile:\n" + SOLID.split("profile:\n")[1].split("material:")[0]
    mod("geo-one-station", c, "profile with one station", "solid",
        (prof, "profile:\n  - [0 in, 2.4 in]\n"))
    mod("geo-two-stations", c, "profile with two stations (cylinder)", "solid",
        (prof, "profile:\n  - [0 in, 2.4 in]\n  - [860 mm, 2.4 in]\n"), expect="either")
    mod("geo-slice-0.01mm", c, "slice_length 0.01 mm (86000 slices)", "solid",
        ("material: ash-bat", "material: ash-bat\nslice_length: 0.01 mm"))
    mod("geo-slice-0.1mm", c, "slice_length 0.1 mm (8600 slices)", "solid",
        ("material: ash-bat", "material: ash-bat\nslice_length: 0.1 mm"))
    mod("geo-slice-0.5mm-hollow", c, "hollow bat slice_length 0.5 mm", "hollow",
        ("material: aluminium-7050", "material: aluminium-7050\nslice_length: 0.5 mm"))
    mod("geo-stations-outside", c, "profile station past the tip (40 in)", "solid",
        ("  - [860 mm, 2.30 in]", "  - [40 in, 2.30 in]"))
    mod("geo-stations-negative", c, "profile station at -2 in", "solid",
        ("  - [0.0 in, 2.40 in]", "  - [-2 in, 2.40 in]"))
    mod("geo-stations-short", c, "profile ends at 20 in on a 860 mm bat (held constant)",
        "solid", (prof, "profile:\n  - [0 in, 2.4 in]\n  - [20 in, 2.6 in]\n"), expect="either")
    mod("geo-stations-equal", c, "two stations at the same position", "solid",
        ("  - [0.5 in, 2.40 in]", "  - [0.0 in, 2.40 in]"))
    mod("geo-stations-tiny-step", c, "stations 1e-12 m apart", "solid",
        ("  - [0.5 in, 2.40 in]", "  - [0.0000000001 in, 2.40 in]"), expect="either")
    mod("geo-wall-outside", c, "wall station at -30 in", "hollow",
        ("  - [0 in, 1.8 mm]", "  - [-30 in, 1.8 mm]"))
    mod("geo-wall-beyond-tip", c, "wall station at 60 in", "hollow",
        ("  - [860 mm, 2.7 mm]", "  - [60 in, 2.7 mm]"))
    mod("geo-wall-thicker-than-radius", c, "wall 40 mm > barrel radius 33 mm", "hollow",
        ("  - [22 in, 2.7 mm]", "  - [22 in, 40 mm]"))
    mod("geo-wall-equal-radius", c, "wall = handle radius 12.07 mm (0.95 in / 2)", "hollow",
        ("  - [11 in, 1.8 mm]", "  - [11 in, 12.065 mm]"))
    mod("geo-wall-one-station", c, "wall list with one station", "hollow",
        ("wall:\n  - [0 in, 1.8 mm]\n  - [11 in, 1.8 mm]\n  - [20 in, 2.2 mm]\n  - [22 in, 2.7 mm]\n"
         "  - [860 mm, 2.7 mm]", "wall:\n  - [22 in, 2.7 mm]"), expect="either")
    mod("geo-wall-empty-list", c, "wall: []", "hollow",
        ("wall:\n  - [0 in, 1.8 mm]\n  - [11 in, 1.8 mm]\n  - [20 in, 2.2 mm]\n  - [22 in, 2.7 mm]\n"
         "  - [860 mm, 2.7 mm]", "wall: []"))
    mod("geo-wall-tiny", c, "wall 1 um", "hollow",
        ("wall:\n  - [0 in, 1.8 mm]\n  - [11 in, 1.8 mm]\n  - [20 in, 2.2 mm]\n  - [22 in, 2.7 mm]\n"
         "  - [860 mm, 2.7 mm]", "wall: 0.001 mm"))
    for length, what in [("0.5 in", "shorter than 1 in"), ("0.9 in", "0.9 in"), ("101 in", "longer than 100 in"),
                         ("1000 in", "1000 in")]:
        L = length
        mod(f"geo-length-{length}".replace(" ", ""), c, f"bat length {length} ({what}), profile scaled",
            "solid", (prof, f"profile:\n  - [0 in, 2.4 in]\n  - [{L}, 2.6 in]\n"),
            ("length: 860 mm", f"length: {L}"), ("measured:\n  pivot: 150 mm\n  mass: 906 g\n"
                                                 "  cg: 429 mm\n  moi: 0.209 kg*m^2\n", ""))
    mod("geo-short-with-measured", c, "bat 0.5 in with the ash measured block", "solid",
        (prof, "profile:\n  - [0 in, 2.4 in]\n  - [0.5 in, 2.6 in]\n"), ("length: 860 mm", "length: 0.5 in"))
    mod("geo-no-measured", c, "no measured block, reconcile none", "solid",
        ("measured:\n  pivot: 150 mm\n  mass: 906 g\n  cg: 429 mm\n  moi: 0.209 kg*m^2\n", ""),
        ("reconcile: density-profile", "reconcile: none"), expect="valid")
    mod("geo-measured-only-mass", c, "measured mass only, point-masses", "solid",
        ("  cg: 429 mm\n  moi: 0.209 kg*m^2\n", ""), ("reconcile: density-profile", "reconcile: point-masses"),
        expect="either")
    mod("geo-cg-off-bat", c, "cg 800 mm from pivot (off the bat)", "solid", ("  cg: 429 mm", "  cg: 800 mm"))
    mod("geo-moi-too-small", c, "moi 0.001 kg m^2 (< M rbar^2)", "solid", ("  moi: 0.209 kg*m^2", "  moi: 0.001 kg*m^2"))
    mod("geo-moi-huge", c, "moi 100 kg m^2", "solid", ("  moi: 0.209 kg*m^2", "  moi: 100 kg*m^2"))
    mod("geo-mass-tiny", c, "measured mass 1 g (density scale 0.001)", "solid", ("  mass: 906 g", "  mass: 1 g"))
    mod("geo-mass-huge", c, "measured mass 100 kg", "solid", ("  mass: 906 g", "  mass: 100 kg"))
    mod("geo-pivot-at-tip-measured", c, "measured pivot at the tip", "solid",
        ("  pivot: 150 mm", "  pivot: 860 mm"))
    mod("geo-point-masses-infeasible", c, "point-masses with impossible cg", "hollow",
        ("  cg: 418 mm", "  cg: 700 mm"))
    mod("geo-diam-tiny", c, "profile diameters 1 um", "solid",
        (prof, "profile:\n  - [0 in, 0.001 mm]\n  - [860 mm, 0.001 mm]\n"))
    mod("geo-diam-huge", c, "profile diameters 10 m", "solid",
        (prof, "profile:\n  - [0 in, 10 m]\n  - [860 mm, 10 m]\n"))
    mod("geo-hollow-huge-barrel-compression", c, "barrel_compression position beyond the bat",
        "hollow", ("  moi: 0.198 kg*m^2", "  moi: 0.198 kg*m^2\n  barrel_compression:\n    force: 220 lbf\n"
                   "    deflection: 1 mm\n    position: 50 in\n    platen_width: 1 in"))
    mod("geo-open-barrel", c, "barrel_end: open", "hollow",
        ("material: aluminium-7050", "material: aluminium-7050\nbarrel_end: open"), expect="valid")
    mod("geo-profile-10000", c, "profile with 10000 stations", "solid",
        (prof, "profile:\n" + "".join(f"  - [{i * 0.086:.3f} mm, {60 + (i % 7)} mm]\n"
                                      for i in range(10001))), expect="either")


# ------------------------------------------------------------------------------------------
# 4. Text
# ------------------------------------------------------------------------------------------
TEXTS = {
    "markup-close": "'[/]'",
    "markup-bold": "'[bold]x[/bold]'",
    "markup-unclosed": "'[bold red]x'",
    "markup-link": "'[link=http://x]y[/link]'",
    "emoji": "':100: :baseball:'",
    "html-script": "'<script>alert(1)</script>'",
    "html-img": "'<img src=x onerror=alert(1)>'",
    "amp-entities": "'&amp; &lt; \"q\" `b` | pipe | *star* _u_'",
    "jinja": "'{{ 7*7 }} {% if true %}x{% endif %}'",
    "long-10k": "'" + "L" * 10_000 + "'",
    "newlines": "\"line1\\nline2\\n\\nline4\"",
    "unicode": "'Frêne 34″ — 木のバット 🏏 ﷽ \u202eRTL'",
    "zero-width": "'\u200b\u200d'",
    "empty-string": "''",
    "spaces": "'   '",
    "ansi": "\"\\e[31mred\\e[0m\"",
    "slash": "'../../etc/passwd'",
    "dots": "'..'",
    "nul-escaped": "\"a\\0b\"",
    "percent": "'%s %d {0} {}'",
    "md-heading": "'# Heading\\n| a | b |'",
    "number": "12345",
    "bool": "yes",
    "null": "~",
    "list": "[a, b]",
    "backslash": "'C:\\\\Windows\\\\'",
}


def text_cases() -> None:
    c = "4-text"
    for tname, value in TEXTS.items():
        exp = "invalid" if tname in ("bool", "list") else "either"
        mod(f"text-bat-name-{tname}", c, f"bat name = {value[:60]}", "solid",
            ("name: Ash 34 in (fuzz)", f"name: {value}"), expect=exp)
    for tname in ["markup-close", "markup-bold", "emoji", "html-script", "long-10k", "newlines",
                  "unicode", "jinja", "slash", "empty-string", "md-heading", "ansi", "nul-escaped"]:
        value = TEXTS[tname]
        mod(f"text-proto-title-{tname}", c, f"protocol title = {value[:60]}", "bbcor",
            ("title: NCAA BBCOR (fuzz)", f"title: {value}"))
        mod(f"text-proto-id-{tname}", c, f"protocol id = {value[:60]}", "bbcor",
            ("id: fuzz-bbcor", f"id: {value}"))
        mod(f"text-cond-name-{tname}", c, f"condition name = {value[:60]}", "bbcor",
            ("  - name: stationary-bat", f"  - name: {value}"))
        mod(f"text-ball-name-{tname}", c, f"ball name = {value[:60]}", "ball",
            ("name: Collegiate baseball (fuzz)", f"name: {value}"))
        mod(f"text-league-title-{tname}", c, f"league title and rule id = {value[:60]}", "league",
            ("title: Fuzz league (copy of ncaa)", f"title: {value}"), ("  - id: length", f"  - id: {value}"))
        mod(f"text-study-claim-{tname}", c, f"study title and claim statement = {value[:60]}",
            "study", ("title: Fuzz study (copy of smith2001)", f"title: {value}"),
            ("    statement: methods disagree", f"    statement: {value}"))
    for tname in ["markup-close", "html-script", "unicode", "long-10k", "newlines"]:
        value = TEXTS[tname]
        mod(f"text-material-name-{tname}", c, f"inline material name = {value[:60]}", "solid",
            ("material: ash-bat", "material:\n  name: " + value + "\n  density: 600 kg/m^3\n"
             "  youngs_modulus: 15 GPa\n  shear_modulus: 0.868 GPa"))
        mod(f"text-limit-source-{tname}", c, f"limit source = {value[:60]}", "bbcor",
            ("  tolerance: 0.0", f"  tolerance: 0.0\n  source: {value}"))
    # text in error messages: a bad value that contains markup / newlines
    mod("text-error-markup-unit", c, "unit typo containing markup '[/]'", "solid",
        ("length: 860 mm", "length: '860 [/]'"), expect="invalid")
    mod("text-error-newline-material", c, "unknown material with newline and markup", "solid",
        ("material: ash-bat", "material: \"[bold]ash\\nx[/bold]\""), expect="invalid")
    mod("text-error-long-unknown-key", c, "10,000-char unknown key", "solid",
        ("reconcile: density-profile", "reconcile: density-profile\n" + "k" * 10000 + ": 1"),
        expect="invalid")
    mod("text-error-unicode-key", c, "unicode key 'lëngth'", "solid",
        ("length: 860 mm", "lëngth: 860 mm"), expect="invalid")


# ------------------------------------------------------------------------------------------
# 5. Unit typos
# ------------------------------------------------------------------------------------------
def unit_typos() -> None:
    c = "5-units"
    typos = [
        ("bat-length", "solid", "length: 860 mm", "length: 860 mms"),
        ("bat-length-inchs", "solid", "length: 860 mm", "length: 33.86 inchs"),
        ("bat-profile", "solid", "  - [28.0 in, 2.61 in]", "  - [28.0 in, 2.61 inchs]"),
        ("bat-profile-paren", "solid", "  - [28.0 in, 2.61 in]", "  - [28.0 in, 2.61 in)]"),
        ("bat-mass", "solid", "  mass: 906 g", "  mass: 906 grams_"),
        ("bat-mass-as-length", "solid", "  mass: 906 g", "  mass: 906 m"),
        ("bat-moi", "solid", "  moi: 0.209 kg*m^2", "  moi: 0.209 kg*m^3"),
        ("bat-moi-typo", "solid", "  moi: 0.209 kg*m^2", "  moi: 0.209 kgm^2"),
        ("bat-knob", "solid", "material: ash-bat", "material: ash-bat\nknob_mass: 10 gg"),
        ("bat-density", "solid", "material: ash-bat", "material:\n  density: 600 kg/m3x\n"
         "  youngs_modulus: 15 GPa\n  shear_modulus: 0.868 GPa"),
        ("bat-modulus-psi", "solid", "material: ash-bat", "material:\n  density: 600 kg/m^3\n"
         "  youngs_modulus: 2.2e6 psi\n  shear_modulus: 0.868 GPaa"),
        ("bat-freq-rads", "solid", "  moi: 0.209 kg*m^2", "  moi: 0.209 kg*m^2\n  first_bending_frequency: 1000 rad/s"),
        ("bat-wall", "hollow", "  - [22 in, 2.7 mm]", "  - [22 in, 2.7 mn]"),
        ("bat-wall-const", "hollow", "wall:\n  - [0 in, 1.8 mm]", "wall: 2 mmm\nxwall:\n  - [0 in, 1.8 mm]"),
        ("bat-hoop-rpm", "hollow", "  moi: 0.198 kg*m^2", "  moi: 0.198 kg*m^2\n  hoop_frequency: 1800 rpm"),
        ("bat-offset-unit", "solid", "length: 860 mm", "length: 860 degC"),
        ("bat-dimensionless", "solid", "length: 860 mm", "length: 860 percent"),
        ("ball-radius", "ball", "radius: 36.9 mm", "radius: 36.9 inchs"),
        ("ball-mass", "ball", "mass: 5.125 oz", "mass: 5.125 ozz"),
        ("ball-cor-speed", "ball", "  - [85 ft/s, 0.546]", "  - [85 fps, 0.546]"),
        ("ball-cor-speed-bare", "ball", "  - [85 ft/s, 0.546]", "  - [85, 0.546]"),
        ("ball-k1-unit", "ball", "k1: 6.53e7", "k1: 6.53e7 N/m"),
        ("ball-cor-unit", "ball", "  - [85 ft/s, 0.546]", "  - [85 ft/s, 0.546 m]"),
        ("proto-pitch", "bbcor", "    pitch_speed: 136 mph", "    pitch_speed: 136 mhp"),
        ("proto-pitch-bare", "bbcor", "    pitch_speed: 136 mph", "    pitch_speed: 136"),
        ("proto-w1-hz", "bbcor", "    bat_angular_speed: 0 rad/s", "    bat_angular_speed: 0 Hz"),
        ("proto-w1-1s", "bbcor", "    bat_angular_speed: 0 rad/s", "    bat_angular_speed: 10 1/s"),
        ("proto-pivot", "bbcor", "pivot: 6 in", "pivot: 6 inn"),
        ("proto-window", "bbcor", "  window: [2 in, 12 in]", "  window: [2 in, 12 inchs]"),
        ("proto-window-bare", "bbcor", "  window: [2 in, 12 in]", "  window: [2, 12]"),
        ("proto-resolution", "besr", "  window: [2 in, 12 in]", "  window: [2 in, 12 in]\n  resolution: 1 mmm"),
        ("proto-limit-unit", "bbcor", "  max: 0.500", "  max: 0.500 mph"),
        ("proto-exit-limit-typo", "exit", "  max: 97 mph", "  max: 97 mhp"),
        ("proto-exit-limit-length", "exit", "  max: 97 mph", "  max: 97 m"),
        ("proto-bat-speed", "besr", "    bat_speed: 66 mph", "    bat_speed: 66 rad/s"),
        ("proto-from-tip", "besr", "    bat_speed_from_tip: 6 in", "    bat_speed_from_tip: 6 s"),
        ("proto-relative", "proposed", "    relative_speed: 60 m/s\n    stationary: bat",
         "    relative_speed: 60 m/ss\n    stationary: bat"),
        ("proto-from-tip-fixed", "exit", "  from_tip: 6 in", "  from_tip: 6 inch es"),
        ("league-length", "league", "    limit: 36 in", "    limit: 36 inchs"),
        ("league-barrel", "league", "    limit: 2.625 in", "    limit: 2.625 mph"),
        ("league-perf", "league", "    limit: 0.500", "    limit: 0.500 inchs"),
        ("league-from", "league", "    kind: max-length", "    kind: max-length\n    applies_from_length: 30 inchs"),
        ("study-loc-tol", "study", "    location_tolerance: 10 mm", "    location_tolerance: 10 mmm"),
    ]
    for cid, base, old, new in typos:
        # "fps" is pint's symbol for feet per second: a unit, not a typo
        expect = "valid" if cid == "ball-cor-speed" else "invalid"
        mod(f"unit-{cid}", c, f"unit typo: {new.strip()[:70]}", base, (old, new), expect=expect)
    # unit typo in a protocol's ball file only, run through a valid protocol: check reports
    mod("unit-ball-via-run", c, "ball radius '36.9 inchs' reached only through run -p proto.yaml",
        "ball", ("radius: 36.9 mm", "radius: 36.9 inchs"), expect="invalid",
        commands=[["run", "ash-34", "-p", "{d}/proto.yaml", "--out", "{out}"],
                  ["run", "ash-34", "-p", "ncaa-bbcor", "-p", "{d}/proto.yaml", "--out", "{out}"],
                  ["run", "ash-34", "-p", "ncaa-bbcor", "-p", "{d}/proto.yaml", "--json", "--out", "{out}"],
                  ["compare", "ash-34", "aluminium-34", "-p", "ncaa-bbcor", "-p", "{d}/proto.yaml", "--out", "{out}"]])


# ------------------------------------------------------------------------------------------
# 6. References
# ------------------------------------------------------------------------------------------
def references() -> None:
    c = "6-refs"
    mod("ref-unknown-material", c, "unknown material 'oak'", "solid", ("material: ash-bat", "material: oak"),
        expect="invalid")
    mod("ref-material-number", c, "material: 42", "solid", ("material: ash-bat", "material: 42"), expect="invalid")
    mod("ref-material-list", c, "material: [ash]", "solid", ("material: ash-bat", "material: [ash]"), expect="invalid")
    mod("ref-material-empty", c, "material: (empty)", "solid", ("material: ash-bat", "material:"), expect="invalid")
    mod("ref-unknown-ball", c, "protocol ball 'softball'", "bbcor",
        ("ball: collegiate-baseball", "ball: softball"), expect="invalid")
    mod("ref-ball-missing-path", c, "protocol ball path that does not exist", "bbcor",
        ("ball: collegiate-baseball", "ball: ./nope.yaml"), expect="invalid")
    mod("ref-ball-is-dir", c, "protocol ball path is a directory", "bbcor",
        ("ball: collegiate-baseball", "ball: /tmp"), expect="invalid")
    mod("ref-ball-is-dir-rel", c, "protocol ball path '.' (the protocol's own directory)", "bbcor",
        ("ball: collegiate-baseball", "ball: ."), expect="invalid")
    mod("ref-ball-is-protocol", c, "ball points to a protocol file", "bbcor",
        ("ball: collegiate-baseball", "ball: @REPO@/protocols/ncaa-besr.yaml"), expect="invalid")
    mod("ref-ball-is-bat", c, "ball points to a bat file", "bbcor",
        ("ball: collegiate-baseball", "ball: @REPO@/bats/ash-34.yaml"), expect="invalid")
    mod("ref-ball-self", c, "ball points to the protocol itself", "bbcor",
        ("ball: collegiate-baseball", "ball: protocol.yaml"), expect="invalid")
    mod("ref-ball-dev-null", c, "ball: /dev/null", "bbcor",
        ("ball: collegiate-baseball", "ball: /dev/null"), expect="invalid")
    mod("ref-ball-number", c, "ball: 42", "bbcor", ("ball: collegiate-baseball", "ball: 42"), expect="invalid")
    mod("ref-ball-list", c, "ball: [a]", "bbcor", ("ball: collegiate-baseball", "ball: [a]"), expect="invalid")
    mod("ref-league-unknown-protocol", c, "league performance rule with unknown protocol", "league",
        ("    protocol: ncaa-bbcor", "    protocol: ncaa-bbcorr"), expect="invalid")
    mod("ref-league-protocol-dir", c, "league protocol path is a directory", "league",
        ("    protocol: ncaa-bbcor", "    protocol: @REPO@/protocols"), expect="invalid")
    mod("ref-league-protocol-dir-dot", c, "league protocol path '.'", "league",
        ("    protocol: ncaa-bbcor", "    protocol: ."), expect="invalid")
    mod("ref-league-protocol-is-bat", c, "league protocol path is a bat file", "league",
        ("    protocol: ncaa-bbcor", "    protocol: @REPO@/bats/ash-34.yaml"), expect="invalid")
    mod("ref-league-protocol-is-league", c, "league protocol path points to itself", "league",
        ("    protocol: ncaa-bbcor", "    protocol: league.yaml"), expect="invalid")
    mod("ref-league-protocol-bad-ball", c, "league protocol whose ball is unknown", "league",
        ("    protocol: ncaa-bbcor", "    protocol: badball-proto.yaml"), expect="invalid")
    ALL[-1].files = {"badball-proto.yaml": sub(BBCOR, "ball: collegiate-baseball", "ball: nope")}
    mod("ref-league-protocol-invalid", c, "league protocol file that is invalid (unit typo)", "league",
        ("    protocol: ncaa-bbcor", "    protocol: bad-proto.yaml"), expect="invalid")
    ALL[-1].files = {"bad-proto.yaml": sub(BBCOR, "pivot: 6 in", "pivot: 6 inchs")}
    mod("ref-league-protocol-not-applicable", c, "league protocol whose window passes the pivot",
        "league", ("    protocol: ncaa-bbcor", "    protocol: far-proto.yaml"), expect="either")
    ALL[-1].files = {"far-proto.yaml": sub(BBCOR, "  window: [2 in, 12 in]", "  window: [2 in, 40 in]")}
    mod("ref-league-perf-no-protocol", c, "performance rule without protocol", "league",
        ("    protocol: ncaa-bbcor\n", ""), expect="invalid")
    mod("ref-league-unknown-class", c, "material rule allows 'plastic'", "league",
        ("    allowed: [wood, metal]", "    allowed: [wood, plastic]"), expect="invalid")
    mod("ref-league-dup-rule-ids", c, "two rules with id 'length'", "league",
        ("  - id: barrel", "  - id: length"), expect="invalid")
    mod("ref-league-other-modelled", c, "kind other without not-modelled", "league",
        ("    kind: max-length\n    limit: 36 in", "    kind: other"), expect="invalid")
    mod("ref-league-not-modelled-no-reason", c, "not-modelled rule without reason", "league",
        ("    kind: max-length\n", "    kind: max-length\n    status: not-modelled\n"), expect="invalid")
    mod("ref-league-not-modelled-limit-list", c, "not-modelled rule with a list limit", "league",
        ("    kind: max-length\n    limit: 36 in", "    kind: max-length\n    status: not-modelled\n"
         "    reason: x\n    limit: [1, 2]"), expect="invalid")
    mod("ref-league-rules-empty", c, "rules: []", "league",
        ("rules:\n", "rules: []\nxrules:\n"), expect="invalid")
    mod("ref-league-rule-not-map", c, "a rule that is a string", "league",
        ("  - id: length\n", "  - just text\n  - id: length\n"), expect="invalid")
    mod("ref-league-rule-id-list", c, "rule id is a list (unhashable)", "league",
        ("  - id: length", "  - id: [a, b]"), expect="invalid")
    mod("ref-study-unknown-protocol", c, "study with unknown protocol id", "study",
        ("  - proposed", "  - proposedd"), expect="invalid")
    mod("ref-study-protocol-dir", c, "study protocol path is a directory", "study",
        ("  - proposed", "  - @REPO@/protocols"), expect="invalid")
    mod("ref-study-protocol-is-bat", c, "study protocol path is a bat", "study",
        ("  - proposed", "  - @REPO@/bats/ash-34.yaml"), expect="invalid")
    mod("ref-study-protocol-number", c, "study protocol entry is a number", "study",
        ("  - proposed", "  - 42"), expect="invalid")
    mod("ref-study-unknown-bat", c, "study default bat unknown", "study",
        ("bats: [ash-34, aluminium-34]", "bats: [ash-34, oak-34]"), expect="invalid")
    mod("ref-study-bat-dir", c, "study default bat is a directory", "study",
        ("bats: [ash-34, aluminium-34]", "bats: [ash-34, @REPO@/bats]"), expect="invalid")
    mod("ref-study-bat-invalid", c, "study default bat file is invalid (unit typo)", "study",
        ("bats: [ash-34, aluminium-34]", "bats: [ash-34, bad-bat.yaml]"), expect="invalid")
    ALL[-1].files = {"bad-bat.yaml": sub(SOLID, "length: 860 mm", "length: 860 mms")}
    mod("ref-study-one-bat", c, "study with a single default bat", "study",
        ("bats: [ash-34, aluminium-34]", "bats: [ash-34]"), expect="either")
    mod("ref-study-same-bat-twice", c, "study bats [ash-34, ash-34]", "study",
        ("bats: [ash-34, aluminium-34]", "bats: [ash-34, ash-34]"), expect="either")
    mod("ref-study-claim-unknown-protocol", c, "claim reads a protocol not in the study", "study",
        ("    protocols: [proposed]\n    compare_with", "    protocols: [astm-bpf]\n    compare_with"),
        expect="invalid")
    mod("ref-study-dup-protocol", c, "study lists 'proposed' twice", "study",
        ("  - proposed\n", "  - proposed\n  - proposed\n"), expect="invalid")
    mod("ref-study-lower-than-3", c, "lower-than with three protocols", "study",
        ("    protocols: [smith2001-besr-sweet-spot, smith2001-bpf-sweet-spot]",
         "    protocols: [smith2001-besr-sweet-spot, smith2001-bpf-sweet-spot, proposed]"), expect="invalid")
    mod("ref-study-inline-protocol", c, "study with an inline protocol whose window passes the pivot",
        "study", ("  - proposed\n", "  - proposed\n  - " + sub(BBCOR, "  window: [2 in, 12 in]",
                  "  window: [2 in, 40 in]").replace("\n", "\n    ").rstrip() + "\n"), expect="invalid")
    mod("ref-study-inline-bad-ball", c, "study inline protocol with unknown ball", "study",
        ("  - proposed\n", "  - proposed\n  - " + sub(BBCOR, "ball: collegiate-baseball",
                                                     "ball: nope").replace("\n", "\n    ").rstrip() + "\n"),
        expect="invalid")
    mod("ref-study-inline-valid", c, "study with a valid inline protocol", "study",
        ("  - proposed\n", "  - proposed\n  - " + BBCOR.replace("\n", "\n    ").rstrip() + "\n"),
        expect="either")
    mod("ref-study-protocol-bad-ball-path", c, "study references a protocol file whose ball is missing",
        "study", ("  - proposed", "  - badball-proto.yaml"), expect="invalid")
    ALL[-1].files = {"badball-proto.yaml": sub(BBCOR, "ball: collegiate-baseball", "ball: nope.yaml")}
    mod("ref-study-protocol-bad-ball-content", c, "study protocol whose ball file has a unit typo",
        "study", ("  - proposed", "  - p.yaml"), expect="invalid")
    ALL[-1].files = {"p.yaml": sub(BBCOR, "ball: collegiate-baseball", "ball: b.yaml"),
                        "b.yaml": sub(BALL, "radius: 36.9 mm", "radius: 36.9 inchs")}
    mod("ref-league-protocol-bad-ball-content", c, "league protocol whose ball file has a unit typo",
        "league", ("    protocol: ncaa-bbcor", "    protocol: p.yaml"), expect="invalid")
    ALL[-1].files = {"p.yaml": sub(BBCOR, "ball: collegiate-baseball", "ball: b.yaml"),
                        "b.yaml": sub(BALL, "radius: 36.9 mm", "radius: 36.9 inchs")}
    mod("ref-protocol-ball-self-ref-ball", c, "protocol ball is a ball file with a unit typo", "bbcor",
        ("ball: collegiate-baseball", "ball: b.yaml"), expect="invalid")
    ALL[-1].files = {"b.yaml": sub(BALL, "radius: 36.9 mm", "radius: 36.9 inchs")}
    # command-line references
    cmds = [
        ("cli-bat-missing", ["run", "{d}/nope.yaml", "-p", "ncaa-bbcor", "--out", "{out}"]),
        ("cli-bat-missing-noext", ["run", "{d}/nope", "-p", "ncaa-bbcor", "--out", "{out}"]),
        ("cli-bat-dir", ["run", "{d}", "-p", "ncaa-bbcor", "--out", "{out}"]),
        ("cli-bat-dir-slash", ["run", "{d}/", "-p", "ncaa-bbcor", "--out", "{out}"]),
        ("cli-bat-devnull", ["run", "/dev/null", "-p", "ncaa-bbcor", "--out", "{out}"]),
        ("cli-bat-is-protocol", ["run", "@REPO@/protocols/ncaa-bbcor.yaml", "-p", "ncaa-bbcor", "--out", "{out}"]),
        ("cli-bat-is-ball", ["run", "@REPO@/protocols/balls/nathan-2000.yaml", "-p", "ncaa-bbcor", "--out", "{out}"]),
        ("cli-bat-is-league", ["run", "@REPO@/protocols/leagues/ncaa.yaml", "-p", "ncaa-bbcor", "--out", "{out}"]),
        ("cli-protocol-dir", ["run", "ash-34", "-p", "{d}", "--out", "{out}"]),
        ("cli-protocol-dir-json", ["run", "ash-34", "-p", "@REPO@/protocols", "--json", "--out", "{out}"]),
        ("cli-protocol-missing", ["run", "ash-34", "-p", "{d}/nope.yaml", "--out", "{out}"]),
        ("cli-protocol-unknown", ["run", "ash-34", "-p", "ncaa-bbcorr", "--out", "{out}"]),
        ("cli-protocol-is-bat", ["run", "ash-34", "-p", "@REPO@/bats/aluminium-34.yaml", "--out", "{out}"]),
        ("cli-protocol-is-ball", ["run", "ash-34", "-p", "@REPO@/protocols/balls/nathan-2000.yaml", "--out", "{out}"]),
        ("cli-protocol-is-study", ["run", "ash-34", "-p", "@REPO@/protocols/studies/smith2001.yaml", "--out", "{out}"]),
        ("cli-protocol-devnull", ["run", "ash-34", "-p", "/dev/null", "--out", "{out}"]),
        ("cli-validate-missing", ["validate", "{d}/nope.yaml"]),
        ("cli-validate-dir", ["validate", "{d}"]),
        ("cli-validate-devnull", ["validate", "/dev/null"]),
        ("cli-validate-study", ["validate", "@REPO@/protocols/studies/smith2001.yaml"]),
        ("cli-validate-csv", ["validate", "@REPO@/bats/r161-profile.csv"]),
        ("cli-validate-shipped-name", ["validate", "ash-34"]),
        ("cli-inspect-missing", ["inspect", "{d}/nope.yaml"]),
        ("cli-inspect-dir", ["inspect", "{d}"]),
        ("cli-inspect-devnull", ["inspect", "/dev/null"]),
        ("cli-inspect-protocol", ["inspect", "@REPO@/protocols/ncaa-bbcor.yaml"]),
        ("cli-inspect-study", ["inspect", "@REPO@/protocols/studies/smith2001.yaml"]),
        ("cli-inspect-csv", ["inspect", "@REPO@/bats/r161-profile.csv"]),
        ("cli-inspect-pivot-nan", ["inspect", "ash-34", "--pivot", "nan in"]),
        ("cli-inspect-pivot-inf", ["inspect", "ash-34", "--pivot", "1e309 in"]),
        ("cli-inspect-pivot-neg", ["inspect", "ash-34", "--pivot", "-10 in", "--json"]),
        ("cli-inspect-pivot-huge", ["inspect", "ash-34", "--pivot", "1e300 in", "--json"]),
        ("cli-inspect-pivot-beyond", ["inspect", "ash-34", "--pivot", "40 in", "--json"]),
        ("cli-inspect-pivot-bare", ["inspect", "ash-34", "--pivot", "6"]),
        ("cli-inspect-pivot-cop0", ["inspect", "aluminium-34", "--pivot", "0.4180001 m", "--json"]),
        ("cli-inspect-pivot-at-cg", ["inspect", "ash-34", "--pivot", "579 mm", "--json"]),
        ("cli-league-unknown", ["league", "ncaaa", "ash-34", "--out", "{out}"]),
        ("cli-league-dir", ["league", "{d}", "ash-34", "--out", "{out}"]),
        ("cli-league-is-bat", ["league", "@REPO@/bats/ash-34.yaml", "ash-34", "--out", "{out}"]),
        ("cli-league-is-protocol", ["league", "@REPO@/protocols/ncaa-bbcor.yaml", "ash-34", "--out", "{out}"]),
        ("cli-league-bat-missing", ["league", "ncaa", "{d}/nope.yaml", "--out", "{out}"]),
        ("cli-league-bat-dir", ["league", "ncaa", "{d}", "--out", "{out}"]),
        ("cli-league-bat-is-protocol", ["league", "ncaa", "@REPO@/protocols/ncaa-bbcor.yaml", "--out", "{out}"]),
        ("cli-league-all-shipped", ["league", "little-league", "ash-34", "aluminium-34", "r161", "bbcor-alloy-34", "--json", "--out", "{out}"]),
        ("cli-compare-one-bat", ["compare", "ash-34", "-p", "ncaa-bbcor", "--out", "{out}"]),
        ("cli-compare-same-bat", ["compare", "ash-34", "ash-34", "-p", "ncaa-bbcor", "--json", "--out", "{out}"]),
        ("cli-compare-no-protocol", ["compare", "ash-34", "aluminium-34", "--out", "{out}"]),
        ("cli-compare-study-and-p", ["compare", "ash-34", "aluminium-34", "--study", "smith2001", "-p", "ncaa-bbcor", "--out", "{out}"]),
        ("cli-compare-study-dir", ["compare", "--study", "{d}", "--out", "{out}"]),
        ("cli-compare-study-missing", ["compare", "--study", "{d}/nope.yaml", "--out", "{out}"]),
        ("cli-compare-study-is-protocol", ["compare", "--study", "@REPO@/protocols/ncaa-bbcor.yaml", "--out", "{out}"]),
        ("cli-compare-study-is-league", ["compare", "--study", "@REPO@/protocols/leagues/ncaa.yaml", "--out", "{out}"]),
        ("cli-compare-ref-missing", ["compare", "ash-34", "aluminium-34", "-p", "ncaa-bbcor", "--reference", "nope", "--out", "{out}"]),
        ("cli-compare-ref-dir", ["compare", "ash-34", "aluminium-34", "-p", "ncaa-bbcor", "--reference", "{d}", "--out", "{out}"]),
        ("cli-compare-dup-protocol", ["compare", "ash-34", "aluminium-34", "-p", "ncaa-bbcor", "-p", "ncaa-bbcor", "--out", "{out}"]),
        ("cli-compare-bat-dir", ["compare", "ash-34", "{d}", "-p", "ncaa-bbcor", "--out", "{out}"]),
        ("cli-run-dup-protocol", ["run", "ash-34", "-p", "ncaa-bbcor", "-p", "ncaa-bbcor", "--out", "{out}"]),
        ("cli-run-format-bad", ["run", "ash-34", "-p", "ncaa-bbcor", "--format", "pdf", "--out", "{out}"]),
        ("cli-run-format-empty", ["run", "ash-34", "-p", "ncaa-bbcor", "--format", ",", "--out", "{out}"]),
        ("cli-run-out-is-file", ["run", "ash-34", "-p", "ncaa-bbcor", "--out", "@REPO@/bats/ash-34.yaml/x"]),
        ("cli-run-out-devnull", ["run", "ash-34", "-p", "ncaa-bbcor", "--out", "/dev/null"]),
        ("cli-run-out-proc", ["run", "ash-34", "-p", "ncaa-bbcor", "--out", "/proc/nope"]),
        ("cli-run-all-shipped", ["run", "r161", "-p", "astm-bpf", "-p", "ncaa-bbcor", "-p", "ncaa-besr", "-p", "proposed", "-p", "stationary-ball", "--json", "--out", "{out}"]),
        ("cli-run-alloy-all", ["run", "bbcor-alloy-34", "-p", "astm-bpf", "-p", "ncaa-bbcor", "-p", "ncaa-besr", "-p", "proposed", "-p", "stationary-ball", "--out", "{out}"]),
    ]
    for cid, cmd in cmds:
        add(cid, c, "command: batcert " + " ".join(cmd), "cmd", "", commands=[cmd], main=".")


def missing_and_types() -> None:
    """Required fields missing, wrong types (structure inside valid YAML)."""
    c = "7-types"
    mod("type-profile-string", c, "profile: 'abc'", "solid",
        ("profile:\n", "profile: abc\nxprofile:\n"), expect="invalid")
    mod("type-profile-pair-3", c, "profile pair with three items", "solid",
        ("  - [28.0 in, 2.61 in]", "  - [28.0 in, 2.61 in, 1 in]"), expect="invalid")
    mod("type-profile-pair-map", c, "profile item is a mapping", "solid",
        ("  - [28.0 in, 2.61 in]", "  - {a: 1}"), expect="invalid")
    mod("type-profile-pair-null", c, "profile item null", "solid",
        ("  - [28.0 in, 2.61 in]", "  -"), expect="invalid")
    mod("type-measured-list", c, "measured is a list", "solid",
        ("measured:\n  pivot: 150 mm\n  mass: 906 g\n  cg: 429 mm\n  moi: 0.209 kg*m^2\n",
         "measured: [1, 2]\n"), expect="invalid")
    mod("type-measured-empty", c, "measured: (empty)", "solid",
        ("measured:\n  pivot: 150 mm\n  mass: 906 g\n  cg: 429 mm\n  moi: 0.209 kg*m^2\n",
         "measured:\n"), expect="either")
    mod("type-measured-no-mass", c, "measured without mass", "solid",
        ("  mass: 906 g\n", ""), expect="invalid")
    mod("type-measured-cg-and-bp", c, "cg and balance_point both", "solid",
        ("  cg: 429 mm\n", "  cg: 429 mm\n  balance_point: 579 mm\n"), expect="invalid")
    mod("type-construction-bool", c, "construction: yes", "solid",
        ("construction: solid", "construction: yes"), expect="invalid")
    mod("type-construction-list", c, "construction: [solid] (unhashable in choice)", "solid",
        ("construction: solid", "construction: [solid]"), expect="invalid")
    mod("type-reconcile-map", c, "reconcile: {a: 1} (unhashable in choice)", "solid",
        ("reconcile: density-profile", "reconcile: {a: 1}"), expect="invalid")
    mod("type-metric-list", c, "metric: [bbcor] (unhashable)", "bbcor",
        ("metric: bbcor", "metric: [bbcor]"), expect="invalid")
    mod("type-rule-map", c, "impact_location.rule: {x: 1}", "bbcor",
        ("  rule: max-metric", "  rule: {x: 1}"), expect="invalid")
    mod("type-league-kind-list", c, "league rule kind: [max-length]", "league",
        ("    kind: max-length", "    kind: [max-length]"), expect="invalid")
    mod("type-league-confidence-list", c, "league rule confidence: [M]", "league",
        ("    confidence: M\n  - id: barrel", "    confidence: [M]\n  - id: barrel"), expect="invalid")
    mod("type-study-check-list", c, "study claim check: [advantage]", "study",
        ("    check: advantage", "    check: [advantage]"), expect="invalid")
    mod("type-study-claims-not-list", c, "study claims: 5", "study",
        ("claims:\n", "claims: 5\nxclaims:\n"), expect="invalid")
    mod("type-conditions-map", c, "conditions is a mapping", "bbcor",
        ("conditions:\n  - name: stationary-bat\n    pitch_speed: 136 mph\n    bat_angular_speed: 0 rad/s\n",
         "conditions:\n  name: stationary-bat\n"), expect="invalid")
    mod("type-condition-both-speeds", c, "condition with explicit and matched speeds", "bbcor",
        ("    bat_angular_speed: 0 rad/s", "    bat_angular_speed: 0 rad/s\n    relative_speed: 40 m/s"),
        expect="invalid")
    mod("type-limit-list", c, "limit: [0.5]", "bbcor", ("limit:\n  max: 0.500\n  tolerance: 0.0\n", "limit: [0.5]\n"),
        expect="invalid")
    mod("type-limit-number", c, "limit: 0.5 (not a mapping)", "bbcor",
        ("limit:\n  max: 0.500\n  tolerance: 0.0\n", "limit: 0.5\n"), expect="invalid")
    mod("type-version-number", c, "version: 1.0 (a number)", "bbcor", ('version: "1.0"', "version: 1.0"),
        expect="either")
    mod("type-id-null", c, "id: ~", "bbcor", ("id: fuzz-bbcor", "id: ~"), expect="invalid")
    mod("type-window-strings", c, "window: ['2 in', '12 in'] quoted", "bbcor",
        ("  window: [2 in, 12 in]", "  window: ['2 in', '12 in']"), expect="valid")
    mod("type-window-nested", c, "window: [[2 in], [12 in]]", "bbcor",
        ("  window: [2 in, 12 in]", "  window: [[2 in], [12 in]]"), expect="invalid")
    mod("type-study-protocol-map-empty", c, "study protocol entry: {} (empty inline)", "study",
        ("  - proposed", "  - {}"), expect="invalid")
    mod("type-study-protocol-null", c, "study protocol entry null", "study",
        ("  - proposed", "  -"), expect="invalid")
    mod("type-study-bats-map", c, "study bats: {a: 1}", "study",
        ("bats: [ash-34, aluminium-34]", "bats: {a: 1}"), expect="invalid")
    mod("type-ball-contact-list", c, "ball contact: [1]", "ball",
        ("contact:\n  model: power-law-hysteresis\n  k1: 6.53e7\n  alpha: 1.84", "contact: [1]"),
        expect="invalid")
    mod("type-ball-cor-empty", c, "ball cor: []", "ball",
        ("cor:\n  - [1 m/s, 0.64]\n  - [85 ft/s, 0.546]\n  - [71 m/s, 0.50]", "cor: []"), expect="invalid")
    mod("type-ball-cor-decreasing", c, "ball cor speeds decreasing", "ball",
        ("  - [1 m/s, 0.64]", "  - [100 m/s, 0.64]"), expect="invalid")
    mod("type-ball-model-other", c, "contact model hertz", "ball",
        ("  model: power-law-hysteresis", "  model: hertz"), expect="invalid")
    mod("type-detect-ambiguous", c, "file with both 'rules' and 'conditions' keys (kind detection)",
        "bbcor", ("metric: bbcor", "metric: bbcor\nrules: []"), expect="invalid")


SESSION = """name: Lab session (fuzz)
bat: aluminium-34
ball: collegiate-baseball
pivot: 6 in
hits: hits.csv
"""
HITS_HEAD = "hit,ball,inbound_speed [m/s],rebound_speed [m/s],impact_location [in from tip],valid,note\n"
HITS_ROW = "{n},B1,60.80,13.00,6,yes,\n"
HITS = HITS_HEAD + "".join(HITS_ROW.format(n=n) for n in range(1, 7))


def lab_data() -> None:
    """Lab sessions and their hits CSVs: malformed, degenerate and hostile."""
    c = "lab"

    def hits(cid, desc, text, expect="invalid", session=SESSION):
        add(cid, c, desc, "session", session, expect=expect, files={"hits.csv": text},
            main="session.yaml")

    hits("lab-valid", "a valid session of six hits", HITS, expect="valid")
    hits("lab-empty-csv", "an empty hits file", "")
    hits("lab-header-only", "a header and no hits", HITS_HEAD)
    hits("lab-bom", "a UTF-8 byte-order mark before the header (as spreadsheets write)",
         "\ufeff" + HITS, expect="valid")
    hits("lab-latin1", "a file that is not UTF-8", (HITS + "7,B\xe9,60.8,13,6,yes,\n")
         .encode("latin-1"))
    hits("lab-nan", "NaN and infinite speeds", HITS_HEAD + "1,B1,nan,13,6,yes,\n2,B1,60.8,inf,6,"
         "yes,\n")
    hits("lab-zero-speed", "an inbound speed of zero", HITS_HEAD + "1,B1,0,13,6,yes,\n")
    hits("lab-negative-rebound", "a negative rebound speed", HITS_HEAD + "1,B1,60.8,-13,6,yes,\n")
    hits("lab-huge-speed", "a speed of 1e308 m/s", HITS_HEAD + "1,B1,1e308,13,6,yes,\n")
    hits("lab-beyond-tip", "an impact 40 in from the tip, behind the pivot",
         HITS_HEAD + "1,B1,60.8,13,40,yes,\n")
    hits("lab-negative-location", "an impact -3 in from the tip", HITS_HEAD + "1,B1,60.8,13,-3,"
         "yes,\n")
    hits("lab-wrong-unit", "a speed column in kilograms",
         HITS_HEAD.replace("inbound_speed [m/s]", "inbound_speed [kg]") + HITS_ROW.format(n=1))
    hits("lab-unit-nonsense", "a unit that is no unit",
         HITS_HEAD.replace("[m/s],rebound", "[furlongs per fortnight],rebound") + HITS_ROW.format(n=1))
    hits("lab-duplicate-column", "a column twice", HITS_HEAD.replace(",note", ",hit")
         + HITS_ROW.format(n=1))
    hits("lab-short-row", "a row with too few fields", HITS + "7,B1,60.8\n")
    hits("lab-quoted-commas", "a quoted note with commas", HITS_HEAD
         + '1,B1,60.8,13,6,yes,"a, b, c"\n' + "".join(HITS_ROW.format(n=n) for n in range(2, 7)),
         expect="valid")
    hits("lab-valid-maybe", "valid is neither yes nor no", HITS_HEAD + "1,B1,60.8,13,6,maybe,\n")
    hits("lab-gate-times-no-spacing", "gate times without the gate spacing",
         "hit,ball,inbound_gate_time [ms],rebound_gate_time [ms],impact_location [in from tip]\n"
         "1,B1,8.2,38,6\n")
    hits("lab-gate-time-zero", "a gate time of zero",
         "hit,ball,inbound_gate_time [ms],rebound_gate_time [ms],impact_location [in from tip]\n"
         "1,B1,0,38,6\n", session=SESSION + "gate_spacing: 0.5 m\n")
    hits("lab-all-invalid", "every hit marked invalid: nothing certified",
         HITS.replace(",yes,", ",no,"), expect="valid")
    hits("lab-many-columns", "2000 unknown columns", HITS_HEAD.strip() + ","
         + ",".join(f"x{i}" for i in range(2000)) + "\n" + HITS_ROW.format(n=1))
    add("lab-no-hits-file", c, "the session names a hits file that is missing", "session",
        SESSION, expect="invalid", main="session.yaml")
    add("lab-hits-is-dir", c, "the hits path is a directory", "session",
        SESSION.replace("hits: hits.csv", "hits: ."), expect="invalid", main="session.yaml")
    add("lab-unknown-bat", c, "an unknown bat", "session",
        SESSION.replace("aluminium-34", "aluminum-34"), expect="invalid", main="session.yaml",
        files={"hits.csv": HITS})
    add("lab-bad-location-from", c, "location_from: middle", "session",
        SESSION + "location_from: middle\n", expect="invalid", main="session.yaml",
        files={"hits.csv": HITS})
    add("lab-zero-required", c, "hits_required: 0", "session", SESSION + "hits_required: 0\n",
        expect="invalid", main="session.yaml", files={"hits.csv": HITS})


def uncertainty() -> None:
    """Stated uncertainties ('+/-') that are malformed, hostile or too large for their value,
    run through validate and `run --uncertainty`."""
    c = "8-uncertainty"
    bat_cmds = [["validate", "{f}"], ["run", "{f}", "-p", "ncaa-bbcor", "--uncertainty", "20",
                                      "--json", "--out", "{out}"]]
    ball_cmds = [["validate", "{f}"], ["run", "ash-34", "-p", "{d}/proto.yaml", "--uncertainty",
                                       "20", "--out", "{out}"]]
    mass = "  mass: 906 g\n"
    for cid, new, expect, desc in [
        ("unc-mass-u-inf", "  mass: 906 g +/- 1e309 g\n", "invalid", "an infinite uncertainty"),
        ("unc-mass-u-nan", "  mass: 906 g +/- nan g\n", "invalid", "a NaN uncertainty"),
        ("unc-mass-u-negative", "  mass: 906 g +/- -1 g\n", "invalid", "a negative uncertainty"),
        ("unc-mass-u-wrong-unit", "  mass: 906 g +/- 1 m\n", "invalid", "an uncertainty in metres"),
        ("unc-mass-u-missing", "  mass: 906 g +/-\n", "invalid", "'+/-' and nothing after"),
        ("unc-mass-only-u", "  mass: +/- 1 g\n", "invalid", "an uncertainty without a value"),
        ("unc-mass-u-twice", "  mass: 906 g +/- 1 g +/- 1 g\n", "invalid", "'+/-' twice"),
        ("unc-mass-dist-typo", "  mass: 906 g +/- 1 g (uniformm)\n", "invalid",
         "an unknown distribution"),
        ("unc-mass-u-wide", "  mass: 906 g +/- 900 g\n", "either",
         "an uncertainty that draws masses below zero"),
        ("unc-mass-u-zero", "  mass: 906 g +/- 0 g\n", "either",
         "a zero uncertainty (nothing to draw)"),
        ("unc-mass-unicode", "  mass: 906 g \u00b1 1 g (uniform)\n", "valid",
         "'\u00b1' and a uniform distribution"),
    ]:
        mod(cid, c, desc, "solid", (mass, new), expect=expect, commands=bat_cmds)
    mod("unc-moi-u-wide", c, "an MOI uncertainty whose draws cannot be reconciled", "solid",
        ("  moi: 0.209 kg*m^2", "  moi: 0.209 kg*m^2 +/- 0.03 kg*m^2"), expect="either",
        commands=bat_cmds)
    mod("unc-length-pm", c, "'+/-' on a field that takes none (length)", "solid",
        ("length: 860 mm", "length: 860 mm +/- 1 mm"), expect="invalid", commands=bat_cmds)
    mod("unc-wall-mixed", c, "wall stations with a normal and a uniform uncertainty", "hollow",
        ("  - [22 in, 2.7 mm]\n  - [860 mm, 2.7 mm]",
         "  - [22 in, 2.7 mm +/- 0.05 mm]\n  - [860 mm, 2.7 mm +/- 0.05 mm (uniform)]"),
        expect="either", commands=bat_cmds)
    for cid, new, expect, desc in [
        ("unc-cor-u-large", "  - [85 ft/s, 0.546 +/- 0.9]", "either",
         "a COR uncertainty that draws CORs above 1"),
        ("unc-cor-u-text", "  - [85 ft/s, 0.546 +/- abc]", "invalid", "a COR uncertainty that "
         "is no number"),
        ("unc-cor-u-unit", "  - [85 ft/s, 0.546 +/- 0.01 m]", "invalid", "a COR uncertainty "
         "with a unit"),
        ("unc-cor-uniform", "  - [85 ft/s, 0.546 +/- 0.02 (uniform)]", "valid",
         "a uniform COR uncertainty"),
    ]:
        mod(cid, c, desc, "ball", ("  - [85 ft/s, 0.546]", new), expect=expect,
            commands=ball_cmds)
    mod("unc-ball-mass-u-wrong-unit", c, "a ball mass uncertainty in metres", "ball",
        ("mass: 5.125 oz", "mass: 5.125 oz +/- 1 m"), expect="invalid", commands=ball_cmds)


def build() -> list[Case]:
    """Every case, with unique ids."""
    import corpus_surfaces  # the newer surfaces: lab data, sweeps, scale-out, injection, output
    ALL.clear()
    lab_data()
    yaml_structure()
    huge_files()
    numbers()
    degenerate()
    text_cases()
    unit_typos()
    references()
    missing_and_types()
    uncertainty()
    corpus_surfaces.build()
    ids = [c.id for c in ALL]
    assert len(ids) == len(set(ids)), "case ids must be unique"
    return list(ALL)
