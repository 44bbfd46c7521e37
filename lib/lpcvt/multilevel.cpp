#include "lpcvt/multilevel.hpp"

namespace quadapt::lpcvt {

std::vector<Vec2> refine_sites(const Background& fine, const std::vector<Vec2>& coarse) {
  std::vector<Vec2> out;
  out.reserve(4 * coarse.size());
  int hint = -1;
  for (const Vec2& x : coarse) {
    const int c = fine.locate(x, hint);
    if (c < 0) continue;
    hint = c;
    const Mat2 V = fine.metric(c, x).inverse();
    const Vec2 a = 0.5 * V.col(0), b = 0.5 * V.col(1);
    for (const Vec2& y : {Vec2(x - a - b), Vec2(x + a - b), Vec2(x + a + b), Vec2(x - a + b)}) {
      const int cy = fine.locate(y, c);
      if (cy >= 0) out.push_back(y);
    }
  }
  return out;
}

}  // namespace quadapt::lpcvt
