#!/usr/bin/env python3
"""Checks of a DG solution file that do not come from the code under test (issue #16: "goldens
carry independent bounds"). Python 3 standard library only.

    dg_exact.py SOL.msh CASE.json      -> one JSON object on stdout:
      l2_error        ||u - u_h||_L2 over the domain, u_h evaluated from the file alone: the
                      per-cell nodal values of the $ElementNodeData "u" times the basis of the
                      file's $InterpolationScheme (Gmsh's convention: phi_i = sum_j F[i][j]
                      xi^a_j eta^b_j on [-1, 1]^2), mapped by the quad's corners
      l2_projection   ||u - P u||_L2, P the L2 projection onto piecewise Q_p (the DG space):
                      no function of that space is closer to u, so l2_error >= l2_projection
                      for any solver (a rigorous lower bound)
      functional      J(u_h) = integral of u_h^2 over x = 1 (the cases' functional), from the file
      functional_exact J(u) by composite Gauss quadrature of the exact solution (400 panels x 10)
      functional_error_linearized  J'(u_h)(u - u_h) = integral over x = 1 of 2 u_h (u - u_h): the
                      error the DWR estimates (it linearises J at u_h); the true error is
                      J(u) - J(u_h) = J'(u_h)(u - u_h) + integral of (u - u_h)^2
      p, cells

The exact solution is the case file's "exact" expression evaluated by Python (^ -> **; sin cos
tan exp log sqrt tanh sinh cosh atan abs pi e), not by quadapt's expression parser. Cells must be
parallelograms (the golden grids are), so that Q_p in reference coordinates is Q_p in x, y.
Quadrature: 12 x 12 Gauss points per cell (the S-shock layer, width ~1/24, spans a cell of 1/16).
"""
import json
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from golden_compare import read_msh  # noqa: E402


def gauss(n):
    """Gauss-Legendre points and weights on [-1, 1] (Newton on P_n, to rounding)."""
    xs, ws = [], []
    for k in range(n):
        x = math.cos(math.pi * (k + 0.75) / (n + 0.5))
        for _ in range(100):
            p0, p1 = 1.0, x
            for m in range(2, n + 1):
                p0, p1 = p1, ((2 * m - 1) * x * p1 - (m - 1) * p0) / m
            dp = n * (x * p1 - p0) / (x * x - 1)
            dx = p1 / dp
            x -= dx
            if abs(dx) < 1e-16:
                break
        xs.append(x)
        ws.append(2 / ((1 - x * x) * dp * dp))
    return xs, ws


def legendre(n, x):
    """P_0..P_n at x."""
    out = [1.0, x]
    for m in range(2, n + 1):
        out.append(((2 * m - 1) * x * out[-1] - (m - 1) * out[-2]) / m)
    return out[:n + 1]


def exact_function(case):
    expr = case["exact"].replace("^", "**")
    names = {k: getattr(math, k) for k in ("sin", "cos", "tan", "exp", "log", "sqrt", "tanh", "sinh", "cosh", "atan")}
    names.update(abs=abs, pi=math.pi, e=math.e)
    code = compile(expr, "exact", "eval")
    return lambda x, y: eval(code, {"__builtins__": {}}, dict(names, x=x, y=y))


def read_scheme(path):
    """The first $InterpolationScheme of the file: (F rows, exponents)."""
    lines = open(path).read().split("\n")
    i = lines.index("$InterpolationScheme")
    rows, cols = map(int, lines[i + 5].split())
    F = [[float(v) for v in lines[i + 6 + r].split()] for r in range(rows)]
    j = i + 6 + rows
    ne = int(lines[j].split()[0])
    exps = [[int(v) for v in lines[j + 1 + r].split()] for r in range(ne)]
    assert len(exps) == cols, "scheme: %d monomials, %d columns" % (len(exps), cols)
    return F, exps


def check(sol_path, case_path):
    case = json.load(open(case_path))
    u = exact_function(case)
    m = read_msh(sol_path)
    nodes = m["nodes"]
    quads = m["elements"][3]
    view = m["views"]["u"]["values"]
    F, exps = read_scheme(sol_path)
    nb = len(F)
    p = int(round(math.sqrt(nb))) - 1
    gx, gw = gauss(12)

    def basis(xi, eta):
        mono = [xi ** a * eta ** b for a, b, _ in exps]
        return [sum(F[i][j] * mono[j] for j in range(nb)) for i in range(nb)]

    B = [[basis(a, b) for b in gx] for a in gx]  # B[qa][qb][i]
    L = [legendre(p, a) for a in gx]
    err2 = proj2 = 0.0
    J_h = J_lin = 0.0
    ge, we = gx, gw  # on an edge: u_h^2 exactly (degree 2p), u_h u to the quadrature's accuracy
    # reference edge k from corner k to k + 1 (corners (-1,-1), (1,-1), (1,1), (-1,1)), parameter t
    on_edge = [lambda t: (t, -1.0), lambda t: (1.0, t), lambda t: (-t, 1.0), lambda t: (-1.0, -t)]
    Be = [[basis(*on_edge[k](t)) for t in ge] for k in range(4)]
    xmax = max(n[0] for n in nodes)
    for c, q in enumerate(quads):
        P = [nodes[k] for k in q]
        vals = view[(3, c)]
        # parallelogram: x = x0 + A (xi, eta)
        ex = [(P[1][0] - P[0][0]) / 2, (P[1][1] - P[0][1]) / 2]
        ey = [(P[3][0] - P[0][0]) / 2, (P[3][1] - P[0][1]) / 2]
        ctr = [sum(v[0] for v in P) / 4, sum(v[1] for v in P) / 4]
        if abs(P[2][0] - (P[0][0] + 2 * ex[0] + 2 * ey[0])) > 1e-12 or abs(P[2][1] - (P[0][1] + 2 * ex[1] + 2 * ey[1])) > 1e-12:
            raise SystemExit("dg_exact.py: cell %d is not a parallelogram" % (c + 1))
        det = abs(ex[0] * ey[1] - ex[1] * ey[0])
        uq = [[0.0] * len(gx) for _ in gx]
        coef = [[0.0] * (p + 1) for _ in range(p + 1)]
        for a in range(len(gx)):
            for b in range(len(gx)):
                x = ctr[0] + ex[0] * gx[a] + ey[0] * gx[b]
                y = ctr[1] + ex[1] * gx[a] + ey[1] * gx[b]
                ue = u(x, y)
                uq[a][b] = ue
                uh = sum(vals[i] * B[a][b][i] for i in range(nb))
                err2 += gw[a] * gw[b] * det * (ue - uh) ** 2
                for i in range(p + 1):
                    for j in range(p + 1):
                        coef[i][j] += gw[a] * gw[b] * ue * L[a][i] * L[b][j]
        for i in range(p + 1):
            for j in range(p + 1):
                coef[i][j] *= (2 * i + 1) * (2 * j + 1) / 4  # ||P_i||^2 = 2 / (2i + 1)
        for a in range(len(gx)):
            for b in range(len(gx)):
                pu = sum(coef[i][j] * L[a][i] * L[b][j] for i in range(p + 1) for j in range(p + 1))
                proj2 += gw[a] * gw[b] * det * (uq[a][b] - pu) ** 2
        # edges on x = xmax: J(u_h) = integral of u_h^2 ds (edge k runs from corner k to k + 1)
        for k in range(4):
            a, b = P[k], P[(k + 1) % 4]
            if abs(a[0] - xmax) < 1e-12 and abs(b[0] - xmax) < 1e-12:
                half = math.hypot(b[0] - a[0], b[1] - a[1]) / 2
                for e, (t, w) in enumerate(zip(ge, we)):
                    uh = sum(vals[i] * Be[k][e][i] for i in range(nb))
                    xa = a[0] + (b[0] - a[0]) * (t + 1) / 2
                    ya = a[1] + (b[1] - a[1]) * (t + 1) / 2
                    J_h += w * half * uh * uh
                    J_lin += w * half * 2 * uh * (u(xa, ya) - uh)
    ymin, ymax = min(n[1] for n in nodes), max(n[1] for n in nodes)
    g10, w10 = gauss(10)
    panels = 400
    h = (ymax - ymin) / panels
    J = 0.0
    for k in range(panels):
        for t, w in zip(g10, w10):
            J += w * h / 2 * u(xmax, ymin + h * (k + (t + 1) / 2)) ** 2
    return {"p": p, "cells": len(quads), "l2_error": math.sqrt(err2), "l2_projection": math.sqrt(proj2),
            "functional": J_h, "functional_exact": J, "functional_error_linearized": J_lin}


if __name__ == "__main__":
    if len(sys.argv) != 3:
        raise SystemExit(__doc__)
    print(json.dumps(check(sys.argv[1], sys.argv[2])))
