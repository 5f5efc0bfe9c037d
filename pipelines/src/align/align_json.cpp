#include "conform/core/constants.h"
#include "conform/pipelines/align/align_json.h"

#include "conform/pipelines/common/cad_json.h"

#include <cmath>
#include <vector>

#include "conform/core/error.h"
#include "conform/pipelines/common/json_values.h"

namespace conform {
namespace {


nlohmann::json degenerate_json(const DegeneracyReport& report) {
  nlohmann::json list = nlohmann::json::array();
  for (const DegenerateDirection& d : report.directions) {
    nlohmann::json entry = {{"kind", d.kind == MotionKind::kTranslation ? "translation" : "rotation"},
                            {"direction", json_of(d.direction)},
                            {"relative_eigenvalue", d.relative_eigenvalue},
                            {"std_mm", d.std_mm},
                            {"std_deg", d.std_rad * kDegPerRad}};
    if (d.kind == MotionKind::kRotation) {
      entry["point_mm"] = json_of(d.point);
      entry["pitch_mm_per_rad"] = d.pitch_mm_per_rad;
    }
    list.push_back(entry);
  }
  return list;
}

// Every eigen-direction of the constraint: the motion per unit, how well it is fixed, whether it was held.
nlohmann::json constraint_json(const DegeneracyReport& report) {
  nlohmann::json list = nlohmann::json::array();
  for (const ConstraintDirection& d : report.eigen_directions) {
    list.push_back({{"rotation_rad", json_of(d.rotation)},
                    {"translation_mm", json_of(d.translation)},
                    {"relative_eigenvalue", d.relative_eigenvalue},
                    {"std_deg", d.std_rad * kDegPerRad},
                    {"std_mm", d.std_mm},
                    {"held", d.held}});
  }
  return list;
}

nlohmann::json pose_std_json(const DegeneracyReport& report) {
  const Vector6d& s = report.std;
  return {{"rx_deg", s(0) * kDegPerRad}, {"ry_deg", s(1) * kDegPerRad}, {"rz_deg", s(2) * kDegPerRad},
          {"tx_mm", s(3)},         {"ty_mm", s(4)},         {"tz_mm", s(5)}};
}

nlohmann::json verdict_json(const AlignVerdict& v) {
  return {{"trust", to_string(v.trust)},
          {"reasons", v.reasons},
          {"summary", v.summary},
          {"scan_noise_mm", v.scan_noise_mm},
          {"reference_noise_mm", v.reference_noise_mm},
          {"expected_noise_mm", v.expected_noise_mm},
          {"fit_noise_mm", v.fit_noise_mm},
          {"noise_ratio", v.noise_ratio},
          {"overlap", v.overlap},
          {"pose_std_mm", v.pose_std_mm},
          {"pose_tolerance_mm", v.pose_tolerance_mm}};
}

// Every coarse start and its score (kPca, kFpfh), with the pose it was probed at.
nlohmann::json starts_json(const AlignResult& r) {
  nlohmann::json starts = nlohmann::json::array();
  for (const StartReport& s : r.coarse.ranking.starts) {
    nlohmann::json pose = nlohmann::json::array();
    for (int row = 0; row < 4; ++row) {
      pose.push_back(std::vector<double>{s.T_probe(row, 0), s.T_probe(row, 1), s.T_probe(row, 2), s.T_probe(row, 3)});
    }
    starts.push_back({{"label", s.label},
                      {"score_mm", s.score_mm},
                      {"inlier_fraction", s.inlier_fraction},
                      {"inlier_share", s.inlier_share},
                      {"rms_mm", s.rms_mm},
                      {"best_only_share", s.best_only_share},
                      {"only_share", s.only_share},
                      {"separated", s.separated},
                      {"gap_mm2", s.gap_mm2},
                      {"best_gap_mm2", s.best_gap_mm2},
                      {"separated_by_gaps", s.separated_by_gaps},
                      {"same_up_to_free", s.same_up_to_free},
                      {"same_when_settled", s.same_when_settled},
                      {"ties_best", s.ties_best},
                      {"T_ref_scan", pose}});
  }
  return starts;
}

nlohmann::json covariance_json(const DegeneracyReport& c) {
  nlohmann::json covariance = nlohmann::json::array();
  for (int row = 0; row < 6; ++row) {
    covariance.push_back(std::vector<double>{c.covariance(row, 0), c.covariance(row, 1), c.covariance(row, 2),
                                             c.covariance(row, 3), c.covariance(row, 4), c.covariance(row, 5)});
  }
  return covariance;
}

}  // namespace

nlohmann::json align_json(const AlignResult& r) {
  const IcpResult& icp = r.icp;
  const DegeneracyReport& c = icp.degeneracy;
  nlohmann::json j = {{"T_ref_scan", json_of(icp.T_ref_scan)},
                      {"converged", icp.converged && r.verdict.trust != AlignTrust::kNo},
                      {"icp_converged", icp.converged},
                      {"trust", to_string(r.verdict.trust)},
                      {"verdict", verdict_json(r.verdict)},
                      {"noise_mm", c.noise_mm},
                      {"pose_std", pose_std_json(c)},
                      {"inverse_consistency_mm", r.inverse_consistency_mm},
                      {"normal_model_mm", r.normal_model_mm},
                      {"pose_covariance", covariance_json(c)},
                      {"covariance_centre_mm", json_of(c.centre)},
                      {"constraint_directions", constraint_json(c)},
                      {"free_tolerance_mm", c.tolerance_mm},
                      {"free_tolerance_deg", c.tolerance_rad * kDegPerRad},
                      {"iterations", icp.iterations},
                      {"termination", to_string(icp.termination)},
                      {"rms_mm", icp.rms_mm},
                      {"inlier_fraction", icp.inlier_fraction},
                      {"degenerate_directions", degenerate_json(c)},
                      {"degeneracy_eigenvalues",
                       std::vector<double>(c.eigenvalues.data(), c.eigenvalues.data() + c.eigenvalues.size())},
                      {"method", to_string(r.method)},
                      {"init", to_string(r.init)},
                      {"start", r.start},
                      {"starts", starts_json(r)},
                      {"ambiguous", r.coarse.ranking.ambiguous},
                      {"coarse_inlier_distance_mm", r.coarse.inlier_distance_mm},
                      {"max_distance_mm", r.max_distance_mm},
                      {"scan_points", r.scan_points},
                      {"scan_points_used", r.scan_points_used},
                      {"reference_points", r.reference_points},
                      {"reference_faces", r.reference_faces},
                      {"transform_file", r.transform_path},
                      {"aligned_file", r.aligned_path}};
  if (r.init == AlignInit::kPairs) {
    j["pair_residuals_mm"] = r.pairs.residuals_mm;
    j["pair_rms_mm"] = r.pairs.rms_mm;
  }
  j["cad"] = cad_json(r.cad_inputs);
  return j;
}

void set_align_method(const std::string& method, AlignOptions* options) {
  if (method.empty()) return;
  if (method == "point-to-point") {
    options->method = IcpMethod::kPointToPoint;
  } else if (method == "point-to-plane") {
    options->method = IcpMethod::kPointToPlane;
  } else if (method == "point-to-surface") {
    options->method = IcpMethod::kPointToSurface;
  } else if (method == "plane-to-plane" || method == "gicp") {
    options->method = IcpMethod::kPlaneToPlane;
  } else {
    throw Error("--method " + method + ": use point-to-point, point-to-plane, point-to-surface or plane-to-plane");
  }
}

void set_align_init(const std::string& init, AlignOptions* options) {
  if (init == "none") {
    options->init = AlignInit::kNone;
  } else if (init == "pca") {
    options->init = AlignInit::kPca;
  } else if (init == "fpfh") {
    options->init = AlignInit::kFpfh;
  } else if (init.rfind("pairs:", 0) == 0 && init.size() > 6) {
    options->init = AlignInit::kPairs;
    options->pairs_path = init.substr(6);
  } else {
    throw Error("--init " + init + ": use none, pca, fpfh or pairs:FILE");
  }
}

}  // namespace conform
