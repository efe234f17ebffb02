"""Conventions of the test standards that several layers share, defined once.

The pivot of a pendulum or pinned-bat test is 6 in from the knob end in ASTM F2398, F2219,
F1890 and the NCAA protocols (DESIGN.md section 1); spec files may state another. Standard
gravity is the value of the ASTM F2398 pendulum formula.
"""

from __future__ import annotations

# 6 in from the knob end [m], written out: 6 * 0.0254 rounds to 0.15239999999999998
DEFAULT_PIVOT = 0.1524
STANDARD_GRAVITY = 9.80665  # [m/s^2]
