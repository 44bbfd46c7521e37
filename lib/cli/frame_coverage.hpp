#pragma once
// A --frame FRAME.msh given with another mesh (recombine, quadsmooth): the frame sampled at the
// mesh's cell centroids, and said when it does not cover the mesh — another run's or another
// domain's frame is otherwise used silently, each uncovered cell taking the nearest frame cell.
#include <string>
#include <vector>

#include "cli/tool.hpp"
#include "frame/frame.hpp"

namespace quadapt {

/// Frame::at_cells(mesh) (#cells of mesh matrices M). Records `cells_outside_frame` in the tool's
/// report and warns when more than 1 % of the cells have their centroid outside the frame's
/// background (a few boundary cells of a curved domain's mesh may lie just outside its polygonal
/// frame; more is another domain's frame).
std::vector<Mat2> sample_frame_checked(Tool& tool, const Frame& frame, const Mesh& mesh, const std::string& mesh_path,
                                       const std::string& frame_path);

}  // namespace quadapt
