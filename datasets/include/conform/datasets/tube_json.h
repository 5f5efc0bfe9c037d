#pragma once
// The ground truth of a generated tube as JSON (what `generate tube` writes beside the mesh): every parameter with
// its unit in the key (_mm, _deg), the seed, the frame, the exact axis and radius, the holes cut and the outliers'
// vertex indices. Per-vertex truth stays in memory (TubeTruth); the file is regenerated from the seed if needed.
// Keys come out sorted (nlohmann::json objects are ordered maps), so the same truth dumps to the same bytes.

#include <nlohmann/json.hpp>

#include "conform/datasets/tube.h"

namespace conform {

nlohmann::json tube_truth_json(const TubeScan& scan);

}  // namespace conform
