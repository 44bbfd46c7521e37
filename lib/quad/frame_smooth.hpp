#pragma once
// The smoothing quadsmooth does with --frame FRAME (docs/quadsmooth.md), as one library call:
// shape_smooth (quad/smooth.hpp) in the frame's metric — at each point the M of the frame cell
// holding it (FrameSampler: reflections removed, the nearest cell outside the background) —
// towards squares of the frame's target edge, which in the units of M is
// 1 / Frame::cell_metric_factor() = 2 (a target cell spans ±v, ±w). With ShapeSmoothOptions{}'s
// target_edge = 1 the quads would fit half the frame's edge: this call is what the tool does.
#include "frame/frame.hpp"
#include "mesh/mesh.hpp"
#include "quad/smooth.hpp"

namespace quadapt {

/// Smooths m (all quads, counter-clockwise, valid) in place towards the frame's quads;
/// opt.target_edge is replaced by the frame's (above), every other option is kept. Throws
/// InputError when the frame is empty. The mesh's fields are left as they were (stale after the
/// nodes moved: quadsmooth drops them).
SmoothStats shape_smooth_to_frame(Mesh& m, const Frame& frame, ShapeSmoothOptions opt = {});

}  // namespace quadapt
