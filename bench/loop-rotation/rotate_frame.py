#!/usr/bin/python3
"""A frame file rotated about the origin with its background mesh (bench/loop-rotation, tests/cli/loop_rotation.sh).

The background's nodes are rotated by R(ANGLE) (rotate_case.rotate_mesh) and every cell's frame
turns with them: M = V^-1 becomes M R^T (the 'Vinv' view, 9 components, M in the upper-left 2x2),
so a target cell of the rotated frame is the rotated target cell; 'theta' views gain ANGLE (in
radians); 'h' and 'rho' views are unchanged. Every other line is copied ($FrameConvention too).

  rotate_frame.py FRAME.msh ANGLE OUT.msh
"""
import math, os, sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from rotate_case import rotate_mesh  # noqa: E402


def rotate_views(lines, c, s, angle):
    out, i = [], 0
    while i < len(lines):
        if lines[i] != "$ElementData":
            out.append(lines[i])
            i += 1
            continue
        out.append(lines[i])
        i += 1
        header = []
        for _ in range(3):  # string, real, integer tags: a count, then the tags
            n = int(lines[i])
            header.extend(lines[i:i + n + 1])
            i += n + 1
        out.extend(header)
        name = header[1].strip('"')
        while lines[i] != "$EndElementData":
            parts = lines[i].split()
            if name == "Vinv":
                v = [float(x) for x in parts[1:]]
                m00, m01, m10, m11 = v[0], v[1], v[3], v[4]
                v[0], v[1] = m00 * c - m01 * s, m00 * s + m01 * c  # M R^T, R = [[c, -s], [s, c]]
                v[3], v[4] = m10 * c - m11 * s, m10 * s + m11 * c
                out.append(parts[0] + " " + " ".join(repr(x) for x in v))
            elif name == "theta":
                out.append(parts[0] + " " + repr(float(parts[1]) + angle))
            else:
                out.append(lines[i])
            i += 1
    return out


def main():
    if len(sys.argv) != 4:
        raise SystemExit(__doc__.strip())
    src, angle, dst = sys.argv[1], float(sys.argv[2]), sys.argv[3]
    c, s = math.cos(math.radians(angle)), math.sin(math.radians(angle))
    tmp = dst + ".tmp-rot"
    rotate_mesh(src, tmp, c, s)
    lines = open(tmp).read().split("\n")
    os.remove(tmp)
    open(dst, "w").write("\n".join(rotate_views(lines, c, s, math.radians(angle))))


if __name__ == "__main__":
    main()
