#include "cli/frame_coverage.hpp"

namespace quadapt {

std::vector<Mat2> sample_frame_checked(Tool& tool, const Frame& frame, const Mesh& mesh, const std::string& mesh_path,
                                       const std::string& frame_path) {
  int outside = 0;
  std::vector<Mat2> M = frame.at_cells(mesh, &outside);
  tool.report()["cells_outside_frame"] = outside;
  if (outside > 0.01 * mesh.num_cells())
    tool.warn(std::to_string(outside) + " of " + std::to_string(mesh.num_cells()) + " cells of " + mesh_path +
              " have their centroid outside " + frame_path +
              "'s background (the nearest frame cell is used there): is it the frame of this mesh?");
  return M;
}

}  // namespace quadapt
