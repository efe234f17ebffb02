"""Conventions of the test standards that several layers share, defined once.

The pivot of a pendulum or pinned-bat test is 6 in from the knob end in ASTM F2398, F2219,
F1890 and the NCAA protocols (DESIGN.md section 1); spec files may state another. Standard
gravity is the value of the ASTM F2398 pendulum formula. A bat, a ball and a batter profile are
for one game (``body``): a softball is 11 or 12 in round (radius 44.5 or 48.5 mm), a baseball
9 to 9 1/4 in (36.4 to 37.4 mm), so a ball larger than 10 in round is a softball.
"""

from __future__ import annotations

import math

# 6 in from the knob end [m], written out: 6 * 0.0254 rounds to 0.15239999999999998
DEFAULT_PIVOT = 0.1524
STANDARD_GRAVITY = 9.80665  # [m/s^2]

BODIES = ("baseball", "softball")  # the games a bat, a ball or a batter profile is for
SOFTBALL_RADIUS = 10 * 0.0254 / (2 * math.pi)  # [m], 40.4 mm: 10 in round
