#!/usr/bin/python3
"""Oracle optimiser for issue #14 item 2: move the vertices of a quad mesh (connectivity kept,
boundary vertices sliding on the walls of the unit square, corners fixed) to maximise the share
of quad corners within 90 +- 10 deg in the frame's metric (meshquality's 'metric
quad_angle_share_80_100') and the share of metric edge lengths in [1/sqrt2, sqrt2], every quad
valid (physical and metric scaled Jacobian > --sjmin).

usage: oracle.py MESH FRAME [--out OUT.msh] [--variant A|B] [--time SEC] [--seed S] [--check MQ.json] [--json REP] [--robust]
  variant A: first raise edges-in-range to >= 0.8 (if below), then maximise right corners
             subject to global edges-in-range >= 0.8 (lexicographic (R, E, smooth)).
  variant B: maximise R + E (share of right corners + share of edges in range), smooth tie-break.
  --measure-only: just print the measure (to compare with meshquality --frame).
Measure = meshquality's: each quad mapped by M of the frame cell containing its area centroid
(det M < 0 -> row 2 negated), M = 2 Vinv for a frame without $FrameConvention (philip), Vinv for
'quadapt'; metric edge length |M e|/2; per cell, interior edges counted twice.
"""
import sys, json, time, argparse
import numpy as np


def read_msh(path):
    """Gmsh MSH 4.1 ASCII: nodes, quads (type 3), ElementData fields by name, FrameConvention."""
    lines = open(path).read().split('\n')
    i = 0
    nodes = {}
    quads = []
    qtags = []
    fields = {}
    conv = None
    n = len(lines)
    while i < n:
        l = lines[i].strip()
        if l == '$Nodes':
            nb, nn, _, _ = map(int, lines[i + 1].split()); i += 2
            for _ in range(nb):
                d, t, par, cnt = map(int, lines[i].split()); i += 1
                tags = [int(lines[i + k]) for k in range(cnt)]; i += cnt
                for k in range(cnt):
                    xyz = lines[i + k].split(); nodes[tags[k]] = (float(xyz[0]), float(xyz[1]))
                i += cnt
            continue
        if l == '$Elements':
            nb, ne, _, _ = map(int, lines[i + 1].split()); i += 2
            for _ in range(nb):
                d, t, et, cnt = map(int, lines[i].split()); i += 1
                if et == 3:
                    for k in range(cnt):
                        a = list(map(int, lines[i + k].split())); qtags.append(a[0]); quads.append(a[1:5])
                i += cnt
            continue
        if l == '$ElementData':
            i += 1
            ns = int(lines[i]); name = lines[i + 1].strip().strip('"'); i += 1 + ns
            nr = int(lines[i]); i += 1 + nr
            ni = int(lines[i]); ints = [int(lines[i + 1 + k]) for k in range(ni)]; i += 1 + ni
            ncomp = ints[1]; cnt = ints[2]
            vals = {}
            for k in range(cnt):
                a = lines[i + k].split(); vals[int(a[0])] = [float(x) for x in a[1:1 + ncomp]]
            fields[name] = vals; i += cnt
            continue
        if l == '$FrameConvention':
            conv = lines[i + 1].strip(); i += 2; continue
        i += 1
    ids = sorted(nodes)
    index = {t: k for k, t in enumerate(ids)}
    P = np.array([nodes[t] for t in ids])
    Q = np.array([[index[v] for v in q] for q in quads], dtype=np.int64)
    return P, Q, qtags, fields, conv


def write_msh(src, dst, P_new):
    """Copy src with node coordinates replaced (same order as read_msh's sorted node tags)."""
    lines = open(src).read().split('\n')
    i = lines.index('$Nodes')
    nb, nn, _, _ = map(int, lines[i + 1].split()); i += 2
    tagpos = {}
    for _ in range(nb):
        d, t, par, cnt = map(int, lines[i].split()); i += 1
        tags = [int(lines[i + k]) for k in range(cnt)]; i += cnt
        for k in range(cnt):
            tagpos[tags[k]] = i + k
        i += cnt
    ids = sorted(tagpos)
    for k, t in enumerate(ids):
        lines[tagpos[t]] = '%.17g %.17g 0' % (P_new[k, 0], P_new[k, 1])
    open(dst, 'w').write('\n'.join(lines))


class Frame:
    def __init__(self, path):
        P, Q, qt, fields, conv = read_msh(path)
        V = fields['Vinv']
        M = np.array([[[V[t][0], V[t][1]], [V[t][3], V[t][4]]] for t in qt])
        det = M[:, 0, 0] * M[:, 1, 1] - M[:, 0, 1] * M[:, 1, 0]
        M[det < 0, 1, :] *= -1.0
        factor = 1.0 if conv == 'quadapt' else 2.0
        self.M = M * factor * 0.5          # cell metric: length = |M e| directly
        self.poly = P[Q]                   # (nc, 4, 2)
        self.nc = len(Q)
        self.cent = self.poly.mean(axis=1)
        lo = P.min(0); hi = P.max(0)
        G = max(4, int(np.sqrt(self.nc)))
        self.G = G; self.lo = lo; self.sz = (hi - lo) / G * (1 + 1e-12)
        bmin = np.floor((self.poly.min(1) - lo) / self.sz).astype(int).clip(0, G - 1)
        bmax = np.floor((self.poly.max(1) - lo) / self.sz).astype(int).clip(0, G - 1)
        buckets = [[] for _ in range(G * G)]
        for c in range(self.nc):
            for bx in range(bmin[c, 0], bmax[c, 0] + 1):
                for by in range(bmin[c, 1], bmax[c, 1] + 1):
                    buckets[bx * G + by].append(c)
        mc = max(len(b) for b in buckets)
        self.table = -np.ones((G * G, mc), dtype=np.int64)
        for k, b in enumerate(buckets):
            self.table[k, :len(b)] = b

    def locate(self, X):
        """X (n, 2) -> frame cell ids (crossing-number test; nearest centroid if none)."""
        b = np.floor((X - self.lo) / self.sz).astype(int).clip(0, self.G - 1)
        cand = self.table[b[:, 0] * self.G + b[:, 1]]            # (n, mc)
        valid = cand >= 0
        poly = self.poly[np.where(valid, cand, 0)]                 # (n, mc, 4, 2)
        x = X[:, None, 0:1]; y = X[:, None, 1:2]
        a = poly; bb = np.roll(poly, -1, axis=2)
        ay = a[..., 1]; by = bb[..., 1]; ax = a[..., 0]; bx = bb[..., 0]
        cond = (ay > y) != (by > y)
        with np.errstate(divide='ignore', invalid='ignore'):
            xi = ax + (y - ay) * (bx - ax) / (by - ay)
        cross = cond & (x < xi)
        inside = (cross.sum(-1) % 2 == 1) & valid
        has = inside.any(1)
        first = np.argmax(inside, axis=1)
        out = cand[np.arange(len(X)), first]
        if not has.all():
            miss = np.where(~has)[0]
            d = ((X[miss, None, :] - self.cent[None]) ** 2).sum(-1)
            out[miss] = d.argmin(1)
        return out


LO, HI = 1 / np.sqrt(2.0), np.sqrt(2.0)


def centroid(p):
    """p (..., 4, 2) -> area centroid as in lib/mesh/mesh.cpp."""
    a, b, c, d = p[..., 0, :], p[..., 1, :], p[..., 2, :], p[..., 3, :]
    def ta(p, q, r):
        return 0.5 * ((q[..., 0] - p[..., 0]) * (r[..., 1] - p[..., 1]) - (q[..., 1] - p[..., 1]) * (r[..., 0] - p[..., 0]))
    a1 = ta(a, b, c); a2 = ta(a, c, d); s = a1 + a2
    s_safe = np.where(np.abs(s) < 1e-300, 1.0, s)
    g = (a1[..., None] * (a + b + c) / 3 + a2[..., None] * (a + c + d) / 3) / s_safe[..., None]
    return np.where((np.abs(s) < 1e-300)[..., None], (a + b + c + d) / 4, g)


def shape(p):
    """p (..., 4, 2) -> angles (deg, [0,360)), sin(angle) per corner, edge lengths |p_{i+1}-p_i|."""
    en = np.roll(p, -1, axis=-2) - p
    ep = np.roll(p, 1, axis=-2) - p
    cr = en[..., 0] * ep[..., 1] - en[..., 1] * ep[..., 0]
    dt = (en * ep).sum(-1)
    ang = np.degrees(np.arctan2(cr, dt)) % 360.0
    ln = np.sqrt((en ** 2).sum(-1))
    lp = np.sqrt((ep ** 2).sum(-1))
    sj = cr / np.maximum(ln * lp, 1e-300)
    return ang, sj, ln


ROBUST = False


def eval_quads(fr, p):
    """p (..., 4, 2) physical quads -> dict of per-quad figures. With ROBUST (--robust), a corner
    counts as right only if it is within 80-100 both in the centroid cell's M (meshquality) and in
    the M of the frame cell containing the corner vertex itself."""
    sh = p.shape[:-2]
    flat = p.reshape(-1, 4, 2)
    cell = fr.locate(centroid(flat))
    M = fr.M[cell]                                              # (n, 2, 2)
    q = np.einsum('nij,nkj->nki', M, flat)
    ang, sj, ln = shape(q)
    _, psj, _ = shape(flat)
    dev = np.abs(ang - 90.0)
    rc = (ang >= 80.0) & (ang <= 100.0)
    if ROBUST:
        vcell = fr.locate(flat.reshape(-1, 2)).reshape(-1, 4)
        for j in range(4):
            a2, s2, _ = shape(np.einsum('nij,nkj->nki', fr.M[vcell[:, j]], flat))
            rc[:, j] &= (a2[:, j] >= 80.0) & (a2[:, j] <= 100.0)
            dev[:, j] = np.maximum(dev[:, j], np.abs(a2[:, j] - 90.0))
    right = rc.sum(-1)
    einr = ((ln >= LO) & (ln <= HI)).sum(-1)
    # smooth surrogate (tie-break): distance of angles outside [81, 99] and log lengths outside
    sm = -(np.maximum(0.0, dev - 9.0) / 10.0) ** 2
    lg = np.abs(np.log2(np.maximum(ln, 1e-300)))
    sm = sm.sum(-1) - ((np.maximum(0.0, lg - 0.45) / 0.5) ** 2).sum(-1)
    r = dict(right=right, einr=einr, msj=sj.min(-1), psj=psj.min(-1), smooth=sm, cell=cell,
             ang=ang, len=ln)
    return {k: (v.reshape(sh + v.shape[1:]) if isinstance(v, np.ndarray) else v) for k, v in r.items()}


def measure(fr, P, Q):
    e = eval_quads(fr, P[Q])
    nq = len(Q)
    return dict(right_share=e['right'].sum() / (4 * nq), edge_share=e['einr'].sum() / (4 * nq),
                metric_sj_min=float(e['msj'].min()), phys_sj_min=float(e['psj'].min()),
                R=int(e['right'].sum()), E=int(e['einr'].sum()), ncorners=4 * nq), e


def stall_stats(fr, P, Q, e):
    """Right-corner share in quads whose 4 vertices lie in the centroid's frame cell vs not."""
    vc = fr.locate(P)
    one = (vc[Q] == e['cell'][:, None]).all(1)
    rs = lambda m: float(e['right'][m].sum() / max(1, 4 * m.sum()))
    es = lambda m: float(e['einr'][m].sum() / max(1, 4 * m.sum()))
    return dict(quads_in_one_cell=float(one.mean()), right_share_one_cell=rs(one), right_share_multi=rs(~one),
                edge_share_one_cell=es(one), edge_share_multi=es(~one))


def optimise(fr, P, Q, variant='A', tmax=120.0, seed=0, sjmin=0.02, K=32, log=sys.stderr):
    rng = np.random.default_rng(seed)
    P = P.copy()
    nv = len(P); nq = len(Q)
    tol = 1e-10
    onx0 = np.abs(P[:, 0]) < tol; onx1 = np.abs(P[:, 0] - 1) < tol
    ony0 = np.abs(P[:, 1]) < tol; ony1 = np.abs(P[:, 1] - 1) < tol
    nb = onx0.astype(int) + onx1 + ony0 + ony1
    corner = nb >= 2
    # mobility: 0 free, 1 slide along x (y fixed), 2 slide along y (x fixed), 3 fixed
    mob = np.zeros(nv, dtype=int)
    mob[ony0 | ony1] = 1; mob[onx0 | onx1] = 2; mob[corner] = 3
    inc = [[] for _ in range(nv)]
    for qi, q in enumerate(Q):
        for v in q:
            inc[v].append(qi)
    inc = [np.array(x) for x in inc]
    e = eval_quads(fr, P[Q])
    R = int(e['right'].sum()); E = int(e['einr'].sum())
    qright = e['right'].copy(); qeinr = e['einr'].copy(); qsm = e['smooth'].copy()
    qmsj = e['msj'].copy(); qpsj = e['psj'].copy()
    Etarget = int(np.ceil(0.8 * 4 * nq))
    step = np.full(nv, 1.0)   # relative step scale per vertex
    t0 = time.time(); sweep = 0
    hist = []
    while time.time() - t0 < tmax:
        sweep += 1
        gain_R = 0; gain_E = 0; moved = 0
        order = rng.permutation(nv)
        for v in order:
            if mob[v] == 3:
                continue
            qs = inc[v]
            loc = Q[qs]                                   # (m, 4)
            pts = P[loc]                                  # (m, 4, 2)
            # shortest incident edge
            el = []
            for q in loc:
                k = int(np.where(q == v)[0][0])
                el.append(np.linalg.norm(P[q[(k + 1) % 4]] - P[v])); el.append(np.linalg.norm(P[q[(k - 1) % 4]] - P[v]))
            rad = 0.3 * min(el) * step[v]
            if mob[v] == 0:
                ang = rng.uniform(0, 2 * np.pi, K); rr = rad * np.sqrt(rng.uniform(0, 1, K))
                d = np.stack([rr * np.cos(ang), rr * np.sin(ang)], 1)
            else:
                t = rng.uniform(-rad, rad, K)
                d = np.zeros((K, 2)); d[:, mob[v] - 1] = t
            cand = P[v] + d
            if mob[v] == 1:
                cand[:, 0] = cand[:, 0].clip(1e-9, 1 - 1e-9)
            elif mob[v] == 2:
                cand[:, 1] = cand[:, 1].clip(1e-9, 1 - 1e-9)
            cp = np.broadcast_to(pts, (K,) + pts.shape).copy()
            mask = (loc == v)
            cp[:, mask] = cand[:, None, :]
            ec = eval_quads(fr, cp)
            # every incident quad: SJ > sjmin, or not below its current value if already below
            ok = ((ec['msj'] > np.minimum(sjmin, qmsj[qs])).all(1) & (ec['psj'] > np.minimum(sjmin, qpsj[qs])).all(1))
            dR = ec['right'].sum(1) - qright[qs].sum()
            dE = ec['einr'].sum(1) - qeinr[qs].sum()
            dS = ec['smooth'].sum(1) - qsm[qs].sum()
            if variant == 'A':
                if E < Etarget:
                    key = np.stack([dE, dR, dS], 1)
                else:
                    ok &= (E + dE >= Etarget)
                    key = np.stack([dR, dE, dS], 1)
            else:
                key = np.stack([dR + dE, dS, np.zeros(K)], 1)
            key = key.astype(float)
            key[~ok] = -np.inf
            best = np.lexsort((key[:, 2], key[:, 1], key[:, 0]))[-1]
            kb = key[best]
            better = kb[0] > 0 or (kb[0] == 0 and (kb[1] > 0 or (kb[1] == 0 and kb[2] > 1e-12)))
            if ok[best] and better:
                P[v] = cand[best]
                qright[qs] = ec['right'][best]; qeinr[qs] = ec['einr'][best]; qsm[qs] = ec['smooth'][best]
                qmsj[qs] = ec['msj'][best]; qpsj[qs] = ec['psj'][best]
                R += int(dR[best]); E += int(dE[best])
                gain_R += int(dR[best]); gain_E += int(dE[best]); moved += 1
                step[v] = min(1.0, step[v] * 1.5)
            else:
                step[v] = max(0.02, step[v] * 0.6)
        hist.append((sweep, R / (4 * nq), E / (4 * nq), moved, round(time.time() - t0, 1)))
        print('sweep %d right %.4f edges %.4f moved %d dR %d dE %d t %.1fs' % (sweep, R / (4 * nq), E / (4 * nq), moved, gain_R, gain_E, time.time() - t0), file=log)
        if moved == 0:
            break
        # stop when the count no longer improves over 3 sweeps
        if len(hist) > 4 and variant == 'A' and E >= Etarget:
            if hist[-1][1] - hist[-4][1] < 0.5 / (4 * nq) and hist[-1][2] - hist[-4][2] < 0.5 / (4 * nq):
                break
        if len(hist) > 4 and variant == 'B':
            if (hist[-1][1] + hist[-1][2]) - (hist[-4][1] + hist[-4][2]) < 0.5 / (4 * nq):
                break
    return P, sweep, time.time() - t0


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument('mesh'); ap.add_argument('frame')
    ap.add_argument('--out'); ap.add_argument('--variant', default='A', choices=['A', 'B'])
    ap.add_argument('--time', type=float, default=120.0); ap.add_argument('--seed', type=int, default=0)
    ap.add_argument('--sjmin', type=float, default=0.02)
    ap.add_argument('--check'); ap.add_argument('--measure-only', action='store_true')
    ap.add_argument('--json')
    ap.add_argument('--robust', action='store_true', help='corner right only if also right in its own vertex cell M')
    a = ap.parse_args()
    global ROBUST
    ROBUST = a.robust
    P, Q, _, _, _ = read_msh(a.mesh)
    fr = Frame(a.frame)
    m0, e0 = measure(fr, P, Q)
    rep = dict(mesh=a.mesh, frame=a.frame, quads=len(Q), before=m0, before_stall=stall_stats(fr, P, Q, e0))
    if a.check:
        d = json.load(open(a.check))['metric']
        rep['meshquality'] = dict(right_share=d['quad_angle_share_80_100'], edge_share=d['edge_length']['share_in_range'],
                                  metric_sj_min=d['scaled_jacobian_min'])
    if not a.measure_only:
        P1, sweeps, secs = optimise(fr, P, Q, a.variant, a.time, a.seed, a.sjmin)
        m1, e1 = measure(fr, P1, Q)
        rep.update(variant=a.variant, after=m1, after_stall=stall_stats(fr, P1, Q, e1), sweeps=sweeps, seconds=round(secs, 1))
        if a.out:
            write_msh(a.mesh, a.out, P1)
    s = json.dumps(rep, indent=1)
    if a.json:
        open(a.json, 'w').write(s)
    print(s)


if __name__ == '__main__':
    main()
