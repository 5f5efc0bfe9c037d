#pragma once
// The align job's verdict (AlignVerdict in pipelines/align.h): the fit's residuals against the scan's own noise, the
// overlap, the motions held, the coarse ranking.

#include <vector>

#include <Eigen/Core>

#include "conform/core/mesh.h"
#include "conform/pipelines/align.h"

namespace conform::detail {

// scan: the points ICP used (scan frame); reference: as prepared (a cloud when it has no faces).
AlignVerdict judge_alignment(const std::vector<Eigen::Vector3d>& scan, const Mesh& reference,
                             const AlignOptions& options, const AlignResult& result);

}  // namespace conform::detail
