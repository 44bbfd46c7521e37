#!/usr/bin/python3
"""A study's problem rotated about the origin: the case file and the start mesh (bench/loop-rotation).

Given ANGLE in degrees and the rotation R(ANGLE), the rotated problem is u_rot(x) = u(R^T x) on
R(square): the exact solution's expression with x, y replaced by the rotated-back coordinates,
the advection R c, the diffusion R D R^T (numbers; constant expressions of the case are evaluated
first by the case's own rules: pi, e), the same boundary names, Dirichlet data and functional. The start mesh's
nodes are rotated (MSH 4.1 ASCII; every other line copied), so the rotated problem on the rotated
mesh is the same discrete problem: dgsolve gives the same error to rounding
(tests/cli/loop_rotation.sh checks it).

  rotate_case.py CASE.json MESH.msh ANGLE OUT_CASE.json OUT_MESH.msh
"""
import json, math, re, sys


def const(v):
    """A number, or a constant expression of the case format (numbers, + - * / ( ), pi, e)."""
    if isinstance(v, (int, float)):
        return float(v)
    if not re.fullmatch(r"[0-9.eE+\-*/() pi]*", v):
        raise SystemExit(f"rotate_case.py: cannot evaluate the constant '{v}'")
    return float(eval(v, {"__builtins__": {}}, {"pi": math.pi, "e": math.e}))


def rotate_expr(expr, c, s):
    """expr(x, y) -> expr(R^T (x, y)): x -> (c x + s y), y -> (-s x + c y), whole identifiers only."""
    X, Y = f"({c!r}*x + {s!r}*y)", f"({-s!r}*x + {c!r}*y)"
    return re.sub(r"\b[xy]\b", lambda m: X if m.group(0) == "x" else Y, expr)


def rotate_mesh(src, dst, c, s):
    lines = open(src).read().split("\n")
    out, i = [], 0
    while i < len(lines):
        out.append(lines[i])
        if lines[i] == "$Nodes":
            i += 1
            out.append(lines[i])
            blocks = int(lines[i].split()[0])
            i += 1
            for _ in range(blocks):
                n = int(lines[i].split()[3])
                out.append(lines[i])
                i += 1
                out.extend(lines[i:i + n])  # node tags
                i += n
                for _ in range(n):
                    x, y, z = map(float, lines[i].split()[:3])
                    out.append(f"{c * x - s * y!r} {s * x + c * y!r} {z!r}")
                    i += 1
            continue
        i += 1
    open(dst, "w").write("\n".join(out))


def main():
    if len(sys.argv) != 6:
        raise SystemExit(__doc__.strip())
    case_path, mesh_path, angle, out_case, out_mesh = sys.argv[1], sys.argv[2], float(sys.argv[3]), sys.argv[4], sys.argv[5]
    c, s = math.cos(math.radians(angle)), math.sin(math.radians(angle))
    case = json.load(open(case_path))
    case["exact"] = rotate_expr(case["exact"], c, s)
    if "advection" in case:
        cx, cy = (const(v) for v in case["advection"])
        case["advection"] = [c * cx - s * cy, s * cx + c * cy]
    if "diffusion" in case:
        (a, b), (b2, d) = ([const(v) for v in row] for row in case["diffusion"])
        # R D R^T
        r = [[c, -s], [s, c]]
        D = [[a, b], [b2, d]]
        RD = [[sum(r[i][k] * D[k][j] for k in range(2)) for j in range(2)] for i in range(2)]
        case["diffusion"] = [[sum(RD[i][k] * r[j][k] for k in range(2)) for j in range(2)] for i in range(2)]
        case["diffusion"][1][0] = case["diffusion"][0][1]  # exactly symmetric
    if isinstance(case.get("dirichlet"), dict) or "neumann" in case:
        raise SystemExit("rotate_case.py: data maps (dirichlet/neumann expressions) are not rotated; use a case with exact data")
    # the functional stays: its boundary group rotates with the mesh, so J = integral of u^2 over it
    # is the same number (dgsolve's functional on both: tests/cli/loop_rotation.sh)
    case["name"] = f"{case.get('name', 'case')}-rot{angle:g}"
    case["description"] = f"{case_path} rotated by {angle:g} degrees about the origin (bench/loop-rotation)"
    json.dump(case, open(out_case, "w"), indent=1)
    rotate_mesh(mesh_path, out_mesh, c, s)


if __name__ == "__main__":
    main()
