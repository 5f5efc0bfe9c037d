#pragma once
// The align job's verdict (AlignVerdict in pipelines/align/align.h): the fit's residuals against the scan's own noise, the
// overlap, the motions held, the coarse ranking.

#include <vector>

#include <Eigen/Core>

#include "conform/core/mesh.h"
#include "conform/pipelines/align/align.h"
#include "conform/registration/icp_reference.h"

namespace conform::detail {

// scan: the points ICP used (scan frame); reference: as prepared for ICP (a cloud's noise is estimated over its
// kd-tree, not a second one).
AlignVerdict judge_alignment(const std::vector<Eigen::Vector3d>& scan, const IcpReference& reference,
                             const AlignOptions& options, const AlignResult& result);

}  // namespace conform::detail
