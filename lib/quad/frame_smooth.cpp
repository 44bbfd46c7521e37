#include "quad/frame_smooth.hpp"

namespace quadapt {

SmoothStats shape_smooth_to_frame(Mesh& m, const Frame& frame, ShapeSmoothOptions opt) {
  const FrameSampler sampler(frame);  // throws on an empty frame
  opt.target_edge = 1 / Frame::cell_metric_factor();  // the frame's edge in the units of M
  const HintedNodeMetric metric = [&](const Vec2& x, int& hint) { return sampler.at(x, hint); };
  return shape_smooth(m, opt, metric);
}

}  // namespace quadapt
