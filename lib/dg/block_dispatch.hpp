#pragma once
// Compile-time block sizes for the hot dense-block kernels of the DG solvers.
#include <Eigen/Core>
#include <type_traits>

namespace quadapt {

/// Calls f(std::integral_constant<int, NB>()) for the DG block sizes (p+1)^2, p = 1..6, so that
/// the kernels use fixed-size Eigen types (unrolled, no heap); other sizes get Eigen::Dynamic
/// (the kernel must then use the runtime size).
template <class F>
void dispatch_block_size(int nb, F&& f) {
  switch (nb) {
    case 4: f(std::integral_constant<int, 4>()); break;
    case 9: f(std::integral_constant<int, 9>()); break;
    case 16: f(std::integral_constant<int, 16>()); break;
    case 25: f(std::integral_constant<int, 25>()); break;
    case 36: f(std::integral_constant<int, 36>()); break;
    case 49: f(std::integral_constant<int, 49>()); break;
    default: f(std::integral_constant<int, Eigen::Dynamic>()); break;
  }
}

}  // namespace quadapt
