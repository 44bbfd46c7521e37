#!/usr/bin/env python3
"""Markdown tables of docs/quad-quality.md from the outputs of figures.sh."""
import json, sys

out, cases = sys.argv[1], sys.argv[2:]
REQ = {1: 3456, 2: 7776, 3: 13824}  # README: requested DOFs at step 3 (1.5x sequences)

def J(name):
    return json.load(open("%s/%s" % (out, name)))

def p_of(c):
    return int(c.split("_p")[1])

print("### Complexity (cells; DOFs = cells (p+1)^2)\n")
print("| case | p | README requested DOFs (step 3) | frame N (PHiLiP conv.) cells / DOFs | thesis output_2 cells / DOFs "
      "| bamgquad cells / DOFs (N ratio, 1st run, runs) | lpcvt path cells / DOFs (N ratio) |")
print("|---|---|---|---|---|---|---|")
SPECIAL = {"saddle": "eq. 6.1 x 8", "band": "curved band"}
for c in cases + list(SPECIAL):
    b = J("%s_bamg.json" % c)
    l = J("%s_lpcvt_q.json" % c)
    N = b["target_complexity"]
    if c in SPECIAL:
        bg = "16x16" if c == "saddle" else "48x48"
        print("| %s, %s (quadapt conv.) | - | - | %.0f | - | %d (%.3f, %.3f, %d) | %d (%.3f) |" % (
            SPECIAL[c], bg, N, b["cells"], b["complexity_ratio"], b["calibration"]["first_ratio"], b["calibration"]["runs"],
            l["cells"], l["cells"] / N))
        continue
    p = p_of(c); w = (p + 1) ** 2
    t = J("%s_thesis.mq.json" % c)
    print("| %s | %d | %d | %.0f / %.0f | %d / %d | %d / %d (%.3f, %.3f, %d) | %d / %d (%.3f) |" % (
        c, p, REQ[p], N, N * w, t["cells"], t["cells"] * w, b["cells"], b["cells"] * w, b["complexity_ratio"],
        b["calibration"]["first_ratio"], b["calibration"]["runs"], l["cells"], l["cells"] * w, l["cells"] / N))

def row(mq, metric=True):
    ph = mq["physical"]
    s = "%.1f | %.2f | %.3f" % (ph["angle_min_deg"], ph["quad_angle_share_80_100"], ph["scaled_jacobian_min"])
    if metric:
        m = mq["metric"]
        s += " | %.1f | %.2f | %.3f | %.2f" % (m["angle_min_deg"], m["quad_angle_share_80_100"], m["scaled_jacobian_min"],
                                            m["edge_length"]["share_in_range"])
    return s

print("\n### Quality (physical | in the frame's metric)\n")
print("min angle in degrees; share = quad corners within 90 +- 10 degrees; SJ = scaled Jacobian (cell minimum); "
      "'edges in range' = share of cell edges whose metric length is in [1/sqrt2, sqrt2] (PHiLiP's frames "
      "are measured as 2 Vinv, their full-edge convention, so that a target edge has length 1).\n")
print("| case | mesh | min angle | share 80-100 | min SJ | metric min angle | metric share 80-100 | metric min SJ | edges in range |")
print("|---|---|---|---|---|---|---|---|---|")
for c in cases + list(SPECIAL):
    if c not in SPECIAL:
        print("| %s | thesis output_2 (physical only) | %s | | | | |" % (c, row(J("%s_thesis.mq.json" % c), False)))
    for m, label in (("bamg", "bamgquad"), ("bamg_s", "bamgquad + quadsmooth"), ("lpcvt", "lpcvt + recombine + quadsmooth --frame")):
        print("| %s | %s | %s |" % (SPECIAL.get(c, c), label, row(J("%s_%s.mq.json" % (c, m)))))
