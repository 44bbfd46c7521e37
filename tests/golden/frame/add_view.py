# Appends a 1-component $ElementData view to a MSH 4.1 ASCII file (for the size-solve CLI tests):
# NAME = f(values of view SRC, cell centroid index k), here either a copy of SRC scaled by a
# smooth factor (default) or a constant.
# usage: add_view.py IN.msh OUT.msh NAME SRC [const VALUE]
import sys
src_path, out_path, name, src = sys.argv[1:5]
const = float(sys.argv[6]) if len(sys.argv) > 6 and sys.argv[5] == "const" else None
text = open(src_path).read()
lines = text.split("\n")
vals = None
i = 0
while i < len(lines):
    if lines[i] == "$ElementData" and lines[i + 2] == '"%s"' % src:
        nreal = int(lines[i + 3]); j = i + 4 + nreal
        nint = int(lines[j]); n = int(lines[j + 3]); start = j + 1 + nint
        vals = [(int(l.split()[0]), float(l.split()[1])) for l in lines[start:start + n]]
        break
    i += 1
if vals is None:
    sys.exit("no view %s in %s" % (src, src_path))
out = text.rstrip("\n").split("\n")
out += ["$ElementData", "1", '"%s"' % name, "1", "0", "3", "0", "1", str(len(vals))]
for k, (tag, v) in enumerate(vals):
    out.append("%d %.17g" % (tag, const if const is not None else v * (1 + 0.5 * ((k * 7919) % 13) / 13)))
out.append("$EndElementData")
open(out_path, "w").write("\n".join(out) + "\n")
