#pragma once
// Several coarse starts, one answer: a short ICP from each start on a subset of the scan, ranked by a truncated RMS
// that charges every scan point (sqrt(mean(min(d, max_distance)^2)), so that a start matching a small part well
// does not beat one matching all of it), the best one named. Ambiguous when another start ends almost as well
// somewhere else (a symmetric part): then the winner is a coin toss the user should know about.

#include <cstddef>
#include <string>
#include <vector>

#include "conform/registration/coarse_pca.h"
#include "conform/registration/icp.h"

namespace conform {

struct MultiStartOptions {
  IcpOptions probe;                 // the short ICP from each start (its max_iterations: keep small, e.g. 15)
  std::size_t probe_points = 3000;  // scan points the probes use, evenly strided (all when fewer)
  // Another start whose score is within this fraction of the best, ending more than 2 degrees or 1% of the scan's
  // size away from the best, makes the result ambiguous (with inlier scoring: unless separated, below).
  double ambiguity = 0.2;
  // Scoring by inlier share (used when > 0, e.g. 3 times the scan's noise): the share of the probe points within
  // this distance of the reference plane at their nearest reference point (and within a few point spacings of that
  // point) ranks the starts, highest first; the truncated RMS breaks ties and ranks when 0.
  double inlier_distance_mm = 0.0;
  // With inlier scoring: another start ending elsewhere (more than distinct_deg apart, or its centre more than
  // distinct_mm away) whose share is at least (1 - share_margin) times the best's makes the result ambiguous.
  double share_margin = 0.1;
  double distinct_deg = 3.0;
  // 0: 10 times inlier_distance_mm, at least 1% of the scan's size, at most half the thinnest of the reference's
  // thin walls (wall_max_thickness_mm): a pose a wall off is another answer.
  double distinct_mm = 0.0;
  // With inlier scoring, such a close start is still told apart (not ambiguous) when the points that are inliers at
  // the best's pose only outnumber those at its own pose only beyond chance: at least separation_min_share of the
  // probe points, separation_ratio times as many, and more by separation_z standard deviations of a fair coin
  // (sqrt of their sum). At two poses of a symmetric surface those points are threshold noise, as many either way;
  // a small feature that only one pose fits (a boss) is one-sided. separation_z 0: never told apart.
  double separation_z = 4.0;
  double separation_ratio = 3.0;
  double separation_min_share = 0.005;
  // A close start the probe points do not tell apart is counted again on up to this many of the scan's points
  // (evenly strided), the two poses as they are: a feature a few tenths of a percent of the scan (a weld bead's crest)
  // is as many standard deviations beyond chance as the square root of the points allows. Told apart only in the
  // best's favour, by the same three conditions. 0 or no more points than the probe's: not counted again.
  std::size_t separation_recount_points = 12000;
  // With inlier scoring, a close start the scan's points do not tell apart is told apart by the reference's: where
  // the scan has a hole (a pin hole, a notch the part really has) over solid reference surface at the start's pose
  // and over a hole of the reference at the best's (scan_coverage.h). Told apart when the largest region of
  // reference points inside the scan's footprint with no scan point on them, at the start's pose only (not at the
  // same place of the scan at the best's), holds at least gap_min_points points, covers at least gap_min_area
  // squared scan spacings (the rims of a through hole seen at a slant leave regions of about 2), and holds
  // separation_ratio times as many points as the largest at the best's pose only. On gap_scan_points of the scan's
  // points (evenly strided; its spacing the square root of their area per point). 0 points: not tested.
  std::size_t gap_min_points = 10;
  double gap_min_area = 8.0;
  std::size_t gap_scan_points = 50000;

  // The best start is also probed turned by the reference's candidate symmetries (half turns about its principal
  // axes through its centroid; turns every 15 deg about an axis whose other two spread within symmetry_similarity of
  // each other, and half turns about the axes between those two every 15 deg: a square plate's diagonal), labelled
  // "... turned N deg about ...": a symmetric reference then makes the result ambiguous even when no start landed on
  // the other pose.
  bool probe_reference_symmetry = true;
  double symmetry_similarity = 0.1;

  // With inlier scoring: the reference's thin walls up to this thick (thin_walls.h) are looked for, and the best
  // distinct poses (at most wall_bases of them, after the symmetry probes) are also probed shifted through them: by
  // -t, 0 or +t along each of the walls' normal directions, every combination but none. A scan of one side of a plate
  // shifted by its thickness lies on the far face and fits almost as well; no start may land on the right pose, so it
  // is probed for. 0: not probed (coarse_align sets it to the FPFH support when FPFH ran).
  double wall_max_thickness_mm = 0.0;
  std::size_t wall_bases = 3;
  // The shifted starts (up to 26 a wall and base) are screened by a quick probe (wall_screen_iterations steps on
  // wall_screen_points of the probe points); the wall_probes best by inlier share that come within share_margin of
  // the best pose's share on the same points are probed as every start is. On 5 mm and 3 mm plates the same poses as
  // probing every shifted start (docs/measurements/cad.md) at the cost of not probing. Starts given marked for
  // screening (CoarseStart::screen: a tube's fine turns) are screened the same way, the wall_probes best whose quick
  // probes land apart probed with the rest.
  std::size_t wall_probes = 8;
  std::size_t wall_screen_points = 500;
  int wall_screen_iterations = 5;

  // With inlier scoring, against a reference at least 3 times as long as it is wide (a profile, a tube, a bar) and
  // half as long again as the scan: the best distinct poses (at most wall_bases, after the wall shifts) are also slid
  // along its longest principal axis by every multiple of slide_step_share of the scan's size (at least 3 inlier
  // distances; at most slide_max_shifts, the step widened to fit) within its extent, labelled "... slid N mm along
  // reference axis 1", screened as the wall shifts are; of the wall_probes best, those whose quick probes land apart
  // are probed as every start is. A stretch of a long profile is fixed along it only by features (holes, notches)
  // that no start may reach. 0: not probed.
  double slide_step_share = 0.04;
  std::size_t slide_max_shifts = 64;

  // With inlier scoring: the best's loose directions (its probe's predicted std above the probe's free tolerance, or
  // held) are tested for symmetry: the best pose moved along each, both ways, by free_step_share of the scan's
  // size (at least 3 inlier distances), keeps its fit (not told apart from the unmoved pose, as above). Those that
  // do are free motions (a cylinder's axis shift and turn), and another start that differs from the best only along
  // them is the same answer (same_up_to_free), not an ambiguity. 0: no test.
  double free_step_share = 0.05;

  // Before a close start that ended elsewhere can make the result ambiguous, its probe and the best's are run on
  // from where they ended for at most this many more iterations and compared again where they settle (the same
  // minimum, or close, elsewhere and not told apart there). A probe stops after probe.max_iterations: on a real scan
  // pair three of six FPFH probes stopped 5-9 deg short of the one minimum they all reach, where the best scored 3 %
  // inliers and a pose 136 deg away 2.9 % (bunny 270 -> 0, docs/measurements/real_pairs.md). The reported starts
  // keep their probes' figures. 0: compared as the probes ended.
  int settle_iterations = 60;

  MultiStartOptions() { probe.max_iterations = 15; }
  bool IsValid(std::string* error) const;
};

struct StartReport {
  std::string label;
  Eigen::Isometry3d T_start = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d T_probe = Eigen::Isometry3d::Identity();  // where its short ICP ended
  double score_mm = 0.0;                                      // truncated RMS at T_probe, lower is better
  double inlier_fraction = 0.0;
  double inlier_share = 0.0;  // of the probe points, within inlier_distance_mm (0 when not scored so)
  double rms_mm = 0.0;        // the probe ICP's RMS at T_probe
  // For a start close in share to the best but elsewhere (inlier scoring): the share of the probe points that are
  // inliers at the best's pose only, and at this start's only; separated: the difference is beyond chance.
  double best_only_share = 0.0;
  double only_share = 0.0;
  bool separated = false;
  // Told apart by the reference's side (MultiStartOptions::gap_min_points): the largest region of reference surface
  // inside the scan with no scan point on it at this start's pose only, and at the best's pose only (mm^2, from the
  // reference points' count and spacing); 0 when not tested.
  double gap_mm2 = 0.0;
  double best_gap_mm2 = 0.0;
  bool separated_by_gaps = false;
  bool same_up_to_free = false;  // differs from the best only along MultiStartResult::free_motions
  // A close start elsewhere whose probe, and the best's, run on to convergence (MultiStartOptions::settle_iterations)
  // meet: the probes had stopped short on the way to one minimum, not at two.
  bool same_when_settled = false;
  // Competes with the best (close, elsewhere, not told apart): every such start makes the result ambiguous, the best
  // of them is the runner-up.
  bool ties_best = false;
};

struct MultiStartResult {
  std::vector<StartReport> starts;  // in the order given, then the best's symmetry probes
  int best = -1;                    // index into starts
  bool ambiguous = false;
  int runner_up = -1;  // the start that made it ambiguous, else -1
  // Motions along which the best pose can move without changing its fit (see free_step_share), in the reference
  // frame at the best's pose, with their predicted std from its probe; empty when none.
  std::vector<DegenerateDirection> free_motions;
};

// Whether T_b differs from T_a (both T_ref_scan) only along the free motions (reference frame, at T_a): with one
// free rotation, the rotation's axis seen from the scan (T^-1 of the axis, an unoriented line: a cylinder's turn end
// for end is its own symmetry too) agrees within max_rad and, nearest to scan_centre, within max_mm once free
// translations are taken out; without one, the rotation between them is within max_rad and scan_centre moves
// within max_mm once free translations are taken out; with several, their axes' common point agrees.
bool same_up_to_free(const Eigen::Isometry3d& T_a, const Eigen::Isometry3d& T_b,
                     const std::vector<DegenerateDirection>& free_motions, const Eigen::Vector3d& scan_centre,
                     double max_rad, double max_mm);

// Throws conform::Error for no starts or invalid options.
MultiStartResult rank_starts(const std::vector<Eigen::Vector3d>& scan, const IcpReference& reference,
                             const std::vector<CoarseStart>& starts, const MultiStartOptions& options);

}  // namespace conform
