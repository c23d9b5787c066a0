#!/usr/bin/env python3
"""Writes scenes/models/ball.obj: a bumpy ball of radius about 0.5 m centred on the origin, a
latitude-longitude grid of r x r cells, 2 r (r - 1) outward-facing triangles (r = 48: 4,512; the
poles' cells have one each), so that no rotation maps it onto itself. The animated ball of
scenes/dynamic-ball.bounce.json; run from the repository root."""
import math

R = 48
lines = ["# A bumpy ball (scripts/make_ball_obj.py): radius about 0.5 m, %d outward triangles." % (2 * R * (R - 1)),
         "mtllib cube.mtl", "o ball"]
for i in range(R + 1):
    for j in range(R + 1):
        theta, phi = math.pi * i / R, 2.0 * math.pi * j / R
        bump = 1.0 + 0.15 * math.sin(3.0 * theta) * math.sin(2.0 * phi)
        r = 0.5 * bump
        lines.append("v %.5f %.5f %.5f" % (r * math.sin(theta) * math.cos(phi), r * math.cos(theta),
                                           r * math.sin(theta) * math.sin(phi)))
lines.append("usemtl cube_white")
at = lambda i, j: i * (R + 1) + j + 1  # OBJ indices start at 1
for i in range(R):
    for j in range(R):
        if i != R - 1:  # else two of its corners are the south pole
            lines.append("f %d %d %d" % (at(i, j), at(i + 1, j + 1), at(i + 1, j)))
        if i != 0:  # else two of its corners are the north pole
            lines.append("f %d %d %d" % (at(i, j), at(i, j + 1), at(i + 1, j + 1)))
with open("scenes/models/ball.obj", "w") as f:
    f.write("\n".join(lines) + "\n")
