#pragma once
// The frame quadsmooth's shape fit aims at (docs/quadsmooth.md, "Which frame the fit aims at").
//
// lpcvt places its points for a filtered frame (metric_filter.hpp: log-Euclidean smoothing, then
// size gradation, both keeping the metric area), not for the frame it reads. A fit to the raw
// frame pulls the nodes back towards shapes the points were not placed for; a fit to the
// filtered frame loses what the filters average away: isolated fine cells of a goal-oriented
// frame, which the loop then leaves coarse until their error shows (docs/studies.md). Three
// choices, per background cell c, with 𝓜 = Mᵀ M:
//   raw:     the frame as read;
//   meshed:  the filtered frame lpcvt meshes with the same settings (lpcvt --write-frame, up to
//            the turn of nearly isotropic cells, which no metric sees);
//   capped:  meshed ∩ raw (the metric intersection: never coarser than the raw frame along any
//            direction), rescaled to the meshed frame's metric area (so the cell count it asks
//            is lpcvt's).
// quadsmooth's default is raw: over the study matrix meshed and capped lower the error on most
// rows but raise it on the S-shock goal rows (docs/studies.md, "Fitting the meshed frame").
// On a constant frame all three are the raw frame bit for bit.
#include "frame/frame.hpp"

namespace quadapt::lpcvt {

enum class FitFrame { Raw, Meshed, Capped };

/// "raw" / "meshed" / "capped".
const char* to_string(FitFrame f);
/// Parses the words of to_string; throws InputError(source, ...) otherwise.
FitFrame parse_fit_frame(const std::string& word, const std::string& source = "");

struct FitFrameOptions {
  FitFrame mode = FitFrame::Raw;
  int smooth = 4;          ///< lpcvt --smooth: log-Euclidean passes (0: none)
  double gradation = 2.0;  ///< lpcvt --gradation: growth per unit metric length (0: none; else > 1)
};

/// Counts of what the filters changed (for reports).
struct FitFrameReport {
  int smoothed_cells = 0, graded_cells = 0, capped_cells = 0;
  double cap_rescale = 1;  ///< the uniform factor after the cap (< 1: the cap added cells)
};

/// The frame to fit (above), on raw's background mesh, in the quadapt convention. Throws
/// InputError for gradation in (0, 1].
Frame fit_frame(const Frame& raw, const FitFrameOptions& opt, FitFrameReport* report = nullptr);

}  // namespace quadapt::lpcvt
