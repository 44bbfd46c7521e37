#pragma once
// JSON forms of the quad module's statistics, for the tools' reports.
#include <nlohmann/json.hpp>

#include "quad/quality_summary.hpp"
#include "quad/recombine.hpp"

namespace quadapt {

nlohmann::json to_json(const QualitySummary& q);
nlohmann::json to_json(const StretchSummary& s);
/// {"triangles_in", "parity_split", "after_blossom": {"quads", "triangles"}, "cells", "quads",
///  "quality": {...}}
nlohmann::json to_json(const RecombineStats& s);

}  // namespace quadapt
