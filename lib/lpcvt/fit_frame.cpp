#include "lpcvt/fit_frame.hpp"

#include "core/error.hpp"
#include "lpcvt/background.hpp"
#include "lpcvt/lpcvt.hpp"
#include "lpcvt/metric_filter.hpp"
#include "lpcvt/run.hpp"

namespace quadapt::lpcvt {

const char* to_string(FitFrame f) {
  switch (f) {
    case FitFrame::Raw: return "raw";
    case FitFrame::Meshed: return "meshed";
    case FitFrame::Capped: return "capped";
  }
  return "?";
}

FitFrame parse_fit_frame(const std::string& word, const std::string& source) {
  if (word == "raw") return FitFrame::Raw;
  if (word == "meshed") return FitFrame::Meshed;
  if (word == "capped") return FitFrame::Capped;
  throw InputError(source, "unknown fit frame '" + word + "' (raw, meshed or capped)");
}

Frame fit_frame(const Frame& raw, const FitFrameOptions& opt, FitFrameReport* report) {
  FitFrameReport rep;
  if (opt.gradation != 0 && !(opt.gradation > 1)) throw InputError("", "the fit frame's gradation must be > 1 (or 0: none)");
  if (opt.smooth < 0) throw InputError("", "the fit frame's smoothing passes must be >= 0");
  if (opt.mode == FitFrame::Raw) {
    if (report) *report = rep;
    return raw;
  }
  // the same background and filters as lpcvt's (run.cpp, finish_background), in its units
  const double scale = frame_metric_scale();
  Background bg = Background::from_frame(raw, scale);
  const FilterReports fr = filter_metric(bg, opt.smooth, opt.gradation);
  if (fr.smoothing) rep.smoothed_cells = fr.smoothing->cells_changed;
  if (fr.gradation) rep.graded_cells = fr.gradation->cells_changed;
  if (opt.mode == FitFrame::Capped) {
    std::vector<Mat2> floor(raw.M.size());
    for (size_t c = 0; c < floor.size(); ++c) floor[c] = scale * raw.M[c];
    const FilterReport f = cap_metric(bg, floor);
    rep.capped_cells = f.cells_changed;
    rep.cap_rescale = f.rescale;
  }
  if (report) *report = rep;
  Frame out = meshed_frame(bg);
  out.source = raw.source;  // the convention the file was read in (M is quadapt's either way)
  return out;
}

}  // namespace quadapt::lpcvt
