#include "cli/help_examples.hpp"

#include <map>

namespace quadapt {

std::string help_example(const std::string& name) {
  static const std::map<std::string, std::pair<const char*, const char*>> ex = {
      {"dgsolve",
       {"dgsolve examples/meshes/square16.msh -c examples/cases/sshock.json -p 2 -o sol.msh",
        "solves the S-shock at p = 2: sol.msh (u; sol.msh.opt for Gmsh), sol.json (dofs, l2_error, ...)"}},
      {"adjoint",
       {"adjoint sol.msh -c examples/cases/sshock.json -o dwr.msh",
        "per-cell DWR 'dwr' and adjoint 'psi' in dwr.msh; functional_error_estimate in dwr.json"}},
      {"estimate-frame", {"estimate-frame sol.msh -o shape.msh", "per-cell theta, rho, B, A1, A2 in shape.msh"}},
      {"size-solve",
       {"size-solve shape.msh --growth 1.5 -o frame.msh", "frame Vinv for 1.5x the solution's DOFs in frame.msh"}},
      {"lpcvt", {"lpcvt frame.msh -o tri.msh --seed 1", "triangles conforming to the frame in tri.msh"}},
      {"recombine", {"recombine tri.msh -o quad.msh", "the all-quad quad.msh: metric matching when tri.msh carries a frame (lpcvt's output), else Blossom-Quad; then the split"}},
      {"quadsmooth", {"quadsmooth quad.msh -o mesh.msh", "angle-based smoothing: mesh.msh, ready for dgsolve"}},
      {"bamgquad", {"bamgquad frame.msh -o quad.msh", "BAMG + Blossom-Quad + split: the all-quad quad.msh"}},
      {"refine",
       {"refine examples/meshes/square16.msh --uniform -o fine.msh", "every quad split into 4: fine.msh (32x32)"}},
      {"meshquality",
       {"meshquality mesh.msh --frame frame.msh > quality.json",
        "angles, Jacobians and metric edge lengths of mesh.msh against frame.msh"}},
      {"meshplot", {"meshplot sol.msh --field u -o u.png", "the solution (high order) over the mesh as a PNG"}},
      {"meshconvert",
       {"meshconvert sol.msh -o sol.vtu", "sol.vtu for ParaView (u as Lagrange quads of degree p, every field)"}},
  };
  auto it = ex.find(name);
  if (it == ex.end()) return "";
  return std::string("Example:\n  ") + it->second.first + "\n  # " + it->second.second + "\n";
}

}  // namespace quadapt
