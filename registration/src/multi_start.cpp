#include "conform/registration/multi_start.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <optional>
#include <string>
#include <utility>

#include "conform/core/error.h"
#include "conform/core/parallel.h"
#include "conform/registration/downsample.h"
#include "conform/registration/thin_walls.h"
#include "scan_coverage.h"
#include "start_scoring.h"
#include "start_screening.h"
#include "symmetry_starts.h"

namespace conform {

namespace {

using detail::better;
using detail::inliers;
using detail::one_sided;
using detail::OneSided;
using detail::screened_starts;
using detail::starts_to_probe;
using detail::separated;
using detail::share_of;
using detail::size_of;
using detail::truncated_rms;

// A start's figures against the best (set by the competition in rank_starts) back to none.
void clear_judgement(StartReport& s) {
  const StartReport fresh;
  s.best_only_share = fresh.best_only_share;
  s.only_share = fresh.only_share;
  s.separated = fresh.separated;
  s.gap_mm2 = fresh.gap_mm2;
  s.best_gap_mm2 = fresh.best_gap_mm2;
  s.separated_by_gaps = fresh.separated_by_gaps;
  s.same_up_to_free = fresh.same_up_to_free;
  s.same_when_settled = fresh.same_when_settled;
  s.ties_best = fresh.ties_best;
}

// The finite screw motion of a scaled twist x = (w L, v) about c: rotation |w| about the axis through
// c + w x v / |w|^2 along w, with translation (w . v / |w|^2) |w| along it; a translation v when w = 0. (The
// linearised step of icp_step.h turns about c instead: wrong by (angle^2 / 2) x the axis' distance for a large turn.)
Eigen::Isometry3d screw_motion(const Vector6d& x, const Eigen::Vector3d& c, double length_scale_mm) {
  const Eigen::Vector3d w = x.head<3>() / length_scale_mm, v = x.tail<3>();
  Eigen::Isometry3d m = Eigen::Isometry3d::Identity();
  const double angle = w.norm();
  if (!(angle > 1e-12)) {
    m.translation() = v;
    return m;
  }
  const Eigen::Vector3d k = w / angle;
  const Eigen::Vector3d a = c + w.cross(v) / (angle * angle);
  m.linear() = Eigen::AngleAxisd(angle, k).toRotationMatrix();
  m.translation() = a - m.linear() * a + (k.dot(v) / angle) * angle * k;
  return m;
}

// The best's loose (or held) directions along which a step of step_mm (at the probe points' RMS radius) both ways
// keeps the fit: not told apart from the unmoved pose by the inlier test. Their motions, reference frame.
std::vector<DegenerateDirection> symmetric_motions(const std::vector<Eigen::Vector3d>& subset,
                                                   const IcpReference& reference, const Eigen::Isometry3d& T_best,
                                                   const DegeneracyReport& degeneracy, const std::vector<char>& mask,
                                                   double step_mm, double reach, const MultiStartOptions& o) {
  const double L = degeneracy.length_scale_mm;
  std::vector<Vector6d> free;
  if (!(L > 0.0)) return {};
  for (const ConstraintDirection& d : degeneracy.eigen_directions) {
    const bool loose = d.held || d.std_mm > o.probe.free_tolerance_mm || d.std_rad > o.probe.free_tolerance_rad;
    if (!loose) continue;
    Vector6d u;
    u.head<3>() = d.rotation * L;
    u.tail<3>() = d.translation;
    const double reach_per_unit = u.head<3>().norm() + u.tail<3>().norm();  // displacement at the RMS radius
    if (!(reach_per_unit > 0.0)) continue;
    // Both ways, and at four times the step: a weak but real constraint (a handful of points on a wall) may hide
    // within chance at one step; a symmetry keeps the fit at any step.
    bool keeps = true;
    for (double step : {-step_mm, step_mm, -4.0 * step_mm, 4.0 * step_mm}) {
      const Eigen::Isometry3d moved = screw_motion(step / reach_per_unit * u, degeneracy.centre, L);
      const std::vector<char> m = inliers(subset, moved * T_best, reference, o.inlier_distance_mm, reach);
      const OneSided c = one_sided(mask, m);
      keeps = keeps && !separated(c.best_only, c.other_only, subset.size(), o);
    }
    if (keeps) free.push_back(u);
  }
  std::vector<DegenerateDirection> motions = motions_of(free, degeneracy, Matrix6d::Zero());
  return motions;
}

}  // namespace

bool MultiStartOptions::IsValid(std::string* error) const {
  std::string why;
  if (!probe.IsValid(&why)) {
    why = "probe: " + why;
  } else if (!std::isfinite(probe.max_correspondence_distance_mm)) {
    why = "probe.max_correspondence_distance_mm must be finite: it caps the score of a point that found nothing";
  } else if (probe_points < probe.min_correspondences) {
    why = "probe_points must be at least probe.min_correspondences";
  } else if (!(ambiguity >= 0.0) || !std::isfinite(ambiguity)) {
    why = "ambiguity must be finite and >= 0";
  } else if (!(inlier_distance_mm >= 0.0) || !std::isfinite(inlier_distance_mm)) {
    why = "inlier_distance_mm must be finite and >= 0 (0: score by truncated RMS)";
  } else if (!(share_margin >= 0.0 && share_margin < 1.0)) {
    why = "share_margin must be in [0, 1)";
  } else if (!(separation_z >= 0.0) || !std::isfinite(separation_z) || !(separation_ratio >= 1.0) ||
             !std::isfinite(separation_ratio) || !(separation_min_share >= 0.0 && separation_min_share <= 1.0)) {
    why = "separation_z must be finite and >= 0, separation_ratio finite and >= 1, separation_min_share in [0, 1]";
  } else if (!(slide_step_share >= 0.0) || !std::isfinite(slide_step_share)) {
    why = "slide_step_share must be finite and >= 0 (0: slides not probed)";
  } else if (!(free_step_share >= 0.0) || !std::isfinite(free_step_share)) {
    why = "free_step_share must be finite and >= 0";
  } else if (!(symmetry_similarity >= 0.0 && symmetry_similarity < 1.0)) {
    why = "symmetry_similarity must be in [0, 1)";
  } else if (!(distinct_deg > 0.0) || !std::isfinite(distinct_deg) || !(distinct_mm >= 0.0) ||
             !std::isfinite(distinct_mm)) {
    why = "distinct_deg must be finite and > 0, distinct_mm finite and >= 0";
  } else if (settle_iterations < 0) {
    why = "settle_iterations must be >= 0";
  } else if (!(wall_max_thickness_mm >= 0.0) || !std::isfinite(wall_max_thickness_mm)) {
    why = "wall_max_thickness_mm must be finite and >= 0 (0: thin walls not probed)";
  } else if (wall_screen_points < probe.min_correspondences || wall_screen_iterations < 1) {
    why = "wall_screen_points must be at least probe.min_correspondences and wall_screen_iterations >= 1";
  } else if (gap_min_points > 0 && (gap_scan_points < 9 || !(gap_min_area >= 0.0) || !std::isfinite(gap_min_area))) {
    why = "gap_scan_points must be at least 9 and gap_min_area finite and >= 0 when gap_min_points > 0";
  }
  if (why.empty()) return true;
  if (error != nullptr) *error = why;
  return false;
}

MultiStartResult rank_starts(const std::vector<Eigen::Vector3d>& scan, const IcpReference& reference,
                             const std::vector<CoarseStart>& starts, const MultiStartOptions& options) {
  std::string why;
  if (!options.IsValid(&why)) throw Error("multi-start options: " + why);
  if (starts.empty()) throw Error("multi-start: no starts given");
  const std::vector<Eigen::Vector3d> subset = stride_downsample(scan, options.probe_points);
  const double cap = options.probe.max_correspondence_distance_mm;
  const bool by_share = options.inlier_distance_mm > 0.0;
  const double reach =
      by_share ? 3.0 * median_spacing(reference.points(), reference.tree()) + options.inlier_distance_mm : 0.0;
  MultiStartResult result;
  std::vector<std::vector<char>> masks;
  std::vector<DegeneracyReport> constraints;  // each probe's, for the best's free motions
  struct Probe {
    StartReport report;
    std::vector<char> mask;
    DegeneracyReport constraint;
  };
  // A probe from `from` (the start itself, or where an earlier probe of it ended) for at most `iterations`.
  const auto run_probe = [&](const CoarseStart& start, const Eigen::Isometry3d& from, int iterations) {
    IcpOptions probe = options.probe;
    probe.progress = nullptr;
    probe.max_iterations = iterations;
    const IcpResult r = icp(subset, reference, from, probe);
    Probe out;
    out.report.label = start.label;
    out.report.T_start = start.T_ref_scan;
    out.report.T_probe = r.T_ref_scan;
    out.report.score_mm = truncated_rms(subset, r.T_ref_scan, reference, cap);
    out.report.inlier_fraction = r.inlier_fraction;
    out.report.rms_mm = r.rms_mm;
    out.constraint = r.degeneracy;
    if (by_share) {
      out.mask = inliers(subset, r.T_ref_scan, reference, options.inlier_distance_mm, reach);
      out.report.inlier_share = share_of(out.mask);
    }
    return out;
  };
  const auto probe_start = [&](const CoarseStart& start) {
    return run_probe(start, start.T_ref_scan, options.probe.max_iterations);
  };
  // Start i's probe run on to convergence from where it ended (MultiStartOptions::settle_iterations).
  const auto settled = [&](std::size_t i) {
    const StartReport& s = result.starts[i];
    return run_probe({s.label, s.T_start}, s.T_probe, options.settle_iterations);
  };
  // The probes are independent and each too small to share out (icp() runs a few thousand points on one thread):
  // one start a thread, merged in the order given, so the result is the same for any number of threads.
  const auto probe_all = [&](const std::vector<CoarseStart>& batch) {
    std::vector<Probe> probes(batch.size());
    for_each_in_parallel(batch.size(), [&](std::size_t i) { probes[i] = probe_start(batch[i]); });
    for (Probe& p : probes) {
      result.starts.push_back(p.report);
      masks.push_back(std::move(p.mask));
      constraints.push_back(std::move(p.constraint));
      if (result.best < 0 || better(p.report, result.starts[static_cast<std::size_t>(result.best)])) {
        result.best = static_cast<int>(result.starts.size()) - 1;
      }
    }
  };
  // The probe points the screened starts (CoarseStart::screen, wall shifts, slides) are screened on.
  const std::vector<Eigen::Vector3d> few = stride_downsample(subset, options.wall_screen_points);
  const Eigen::Vector3d centre =
      std::accumulate(subset.begin(), subset.end(), Eigen::Vector3d(Eigen::Vector3d::Zero())) /
      static_cast<double>(subset.size());
  const double size_mm = size_of(subset);
  probe_all(starts_to_probe(starts, few, reference, options, reach, centre, size_mm));
  if (options.probe_reference_symmetry) {
    // The best pose turned by the reference's own candidate symmetries: if the reference (or the part of it the scan
    // covers) looks the same turned, the turned pose fits as well and the ambiguity test below finds it, whether or
    // not any start happened to land there (a partial scan of a symmetric plate: every FPFH run may agree).
    const StartReport best_given = result.starts[static_cast<std::size_t>(result.best)];
    probe_all(detail::symmetry_starts(best_given, reference.points(), options.symmetry_similarity));
  }
  // The reference's thin walls (wall_max_thickness_mm), looked for once: the shifted starts below, and the distance
  // that makes two poses distinct.
  std::vector<ThinWall> walls;
  if (by_share && options.wall_max_thickness_mm > 0.0 && options.wall_bases > 0) {
    ThinWallOptions wall_options;
    wall_options.max_thickness_mm = options.wall_max_thickness_mm;
    walls = thin_walls(reference, wall_options);
  }
  double far_mm = !by_share                   ? 0.01 * size_mm
                  : options.distinct_mm > 0.0 ? options.distinct_mm
                                              : std::max(10.0 * options.inlier_distance_mm, 0.01 * size_mm);
  // A pose a wall's thickness off (the scan on the far face) is another answer, not the same one within slack: on a
  // 2 mm panel whose inlier distance (from its size) made 6.3 mm the same answer, the far face won by 0.1 % of the
  // share.
  if (!(options.distinct_mm > 0.0)) {  // walls are looked for only with inlier scoring
    for (const ThinWall& wall : walls) far_mm = std::min(far_mm, 0.5 * wall.thickness_mm);
  }
  const double far_rad = (by_share ? options.distinct_deg : 2.0) * M_PI / 180.0;
  const auto apart = [&](const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
    return rotation_angle(b * a.inverse()) > far_rad || (b * centre - a * centre).norm() > far_mm;
  };
  // The best distinct poses so far, best first (at most wall_bases).
  const auto best_distinct = [&]() {
    std::vector<std::size_t> order(result.starts.size());
    std::iota(order.begin(), order.end(), std::size_t{0});
    std::stable_sort(order.begin(), order.end(),
                     [&](std::size_t a, std::size_t b) { return better(result.starts[a], result.starts[b]); });
    std::vector<StartReport> bases;
    for (const std::size_t i : order) {
      const StartReport& s = result.starts[i];
      const bool seen = std::any_of(bases.begin(), bases.end(),
                                    [&](const StartReport& b) { return !apart(b.T_probe, s.T_probe); });
      if (!seen) bases.push_back(s);
      if (bases.size() == options.wall_bases) break;
    }
    return bases;
  };
  if (!walls.empty()) {
    // A scan shifted through a wall may also be turned by a near-symmetry, and the turn's probe is not always the
    // best.
    const std::vector<StartReport> bases = best_distinct();
    const StartReport& best_so_far = result.starts[static_cast<std::size_t>(result.best)];
    const double best_share = share_of(inliers(few, best_so_far.T_probe, reference, options.inlier_distance_mm, reach));
    const std::vector<CoarseStart> kept =
        screened_starts(detail::wall_starts(bases, walls), few, reference, options, reach, best_share);
    if (!kept.empty()) probe_all(kept);
  }
  if (by_share && options.slide_step_share > 0.0) {
    // From the best distinct poses: a scan turned end for end may fit its wrong place as well as the right one.
    const std::vector<CoarseStart> slid = detail::slide_starts(
        best_distinct(), reference.points(), subset,
        std::max(options.slide_step_share * size_mm, 3.0 * options.inlier_distance_mm), options.slide_max_shifts);
    if (!slid.empty()) {
      const StartReport& best_so_far = result.starts[static_cast<std::size_t>(result.best)];
      const double best_share =
          share_of(inliers(few, best_so_far.T_probe, reference, options.inlier_distance_mm, reach));
      const std::vector<CoarseStart> kept = screened_starts(slid, few, reference, options, reach, best_share, apart);
      if (!kept.empty()) probe_all(kept);
    }
  }
  // The best's free motions (free_step_share), for the competition below.
  const auto find_free_motions = [&]() {
    result.free_motions.clear();
    if (!by_share || !(options.free_step_share > 0.0)) return;
    const auto b = static_cast<std::size_t>(result.best);
    const double step_mm = std::max(options.free_step_share * size_mm, 3.0 * options.inlier_distance_mm);
    result.free_motions = symmetric_motions(subset, reference, result.starts[b].T_probe, constraints[b], masks[b],
                                            step_mm, reach, options);
  };
  // The reference's side of the test (gap_min_points): whether the scan's holes tell pose `here` apart from `there`
  // (here has a region of gaps that there has not), its regions' areas set on `other` (here: other's pose).
  std::optional<detail::GapComparison> holes;
  const auto holes_tell = [&](const Eigen::Isometry3d& here, const Eigen::Isometry3d& there, StartReport* other) {
    if (!holes) holes.emplace(scan, reference, options.gap_scan_points, 3.0 * options.inlier_distance_mm);
    const detail::GapComparison::Regions r = holes->compare(here, there);
    if (other != nullptr) {
      other->gap_mm2 = static_cast<double>(r.a_only) * holes->area_per_point_mm2();
      other->best_gap_mm2 = static_cast<double>(r.b_only) * holes->area_per_point_mm2();
    }
    const double s = holes->scan_spacing_mm();
    return r.a_only >= options.gap_min_points &&
           static_cast<double>(r.a_only) * holes->area_per_point_mm2() >= options.gap_min_area * s * s &&
           static_cast<double>(r.a_only) >= options.separation_ratio * static_cast<double>(r.b_only);
  };
  // The points a close start's tie is counted again on (separation_recount_points).
  const std::vector<Eigen::Vector3d> recount =
      options.separation_recount_points > subset.size() && by_share
          ? stride_downsample(scan, options.separation_recount_points)
          : std::vector<Eigen::Vector3d>{};
  // The best's inlier mask on them, kept for its pose (every rival is counted against the same best).
  std::optional<std::pair<Eigen::Matrix4d, std::vector<char>>> recount_best;
  const auto recount_best_mask = [&](const Eigen::Isometry3d& T) -> const std::vector<char>& {
    if (!recount_best || recount_best->first != T.matrix()) {
      recount_best.emplace(T.matrix(), inliers(recount, T, reference, options.inlier_distance_mm, reach));
    }
    return recount_best->second;
  };
  // Whether start j (as `o`, its probe's figures and inlier mask `m`) competes with the best (`b`, mask `bm`): close
  // in score, elsewhere, not along a free motion, not told apart. The flags are set on start j.
  const auto competes = [&](std::size_t j, const StartReport& b, const std::vector<char>& bm, const StartReport& o,
                            const std::vector<char>& m) {
    StartReport& other = result.starts[j];
    const bool close = by_share ? o.inlier_share >= (1.0 - options.share_margin) * b.inlier_share
                                : o.score_mm <= (1.0 + options.ambiguity) * b.score_mm;
    if (!close || !apart(b.T_probe, o.T_probe)) return false;
    if (!result.free_motions.empty() &&
        same_up_to_free(b.T_probe, o.T_probe, result.free_motions, centre, far_rad, far_mm)) {
      other.same_up_to_free = true;
      return false;
    }
    if (by_share) {
      const OneSided c = one_sided(bm, m);
      other.best_only_share = static_cast<double>(c.best_only) / static_cast<double>(subset.size());
      other.only_share = static_cast<double>(c.other_only) / static_cast<double>(subset.size());
      other.separated = separated(c.best_only, c.other_only, subset.size(), options);
      if (!other.separated && recount.size() > subset.size()) {
        const OneSided again = one_sided(recount_best_mask(b.T_probe),
                                         inliers(recount, o.T_probe, reference, options.inlier_distance_mm, reach));
        other.separated = separated(again.best_only, again.other_only, recount.size(), options);
      }
      if (!other.separated && options.gap_min_points > 0) {
        other.separated_by_gaps = holes_tell(o.T_probe, b.T_probe, &other);
        other.separated = other.separated_by_gaps;
      }
      if (other.separated) return false;
    }
    return true;
  };
  // Every start against the best: which compete with it (ties_best), the runner-up, ambiguous.
  const auto judge = [&]() {
    find_free_motions();
    const auto b = static_cast<std::size_t>(result.best);
    const StartReport best = result.starts[b];
    std::optional<Probe> best_settled;  // the best's probe run on, once, when a start competes with it as probed
    for (std::size_t j = 0; j < result.starts.size(); ++j) {
      if (j == b || !competes(j, best, masks[b], result.starts[j], masks[j])) continue;
      if (options.settle_iterations > 0) {
        // Both run on to convergence: the same minimum, or elsewhere and judged again there (the reported figures
        // stay the probes'; the coarse pose is the best's probe, finished by the coarse stage).
        if (!best_settled) best_settled = settled(b);
        const Probe other = settled(j);
        if (!apart(best_settled->report.T_probe, other.report.T_probe)) {
          result.starts[j].same_when_settled = true;
          continue;
        }
        if (!competes(j, best_settled->report, best_settled->mask, other.report, other.mask)) continue;
      }
      StartReport& other = result.starts[j];
      other.ties_best = true;
      if (result.runner_up < 0 || better(other, result.starts[static_cast<std::size_t>(result.runner_up)])) {
        result.ambiguous = true;
        result.runner_up = static_cast<int>(j);
      }
    }
  };
  judge();
  // A tie the scan's holes settle the other way: the best's pose has a region of gaps that a tied start's has not
  // (the scan's hole over solid reference at the best, over the reference's own hole at the other), and the points
  // inlying at one of the two only are as many either way within chance (2 standard deviations of a fair coin: the
  // best won by a coin toss). That start is the best, judged again. A start the best beat by more (a worse fit, whose
  // scan does not lie on the surface closely enough to leave gaps) is not.
  if (result.ambiguous && by_share && options.gap_min_points > 0) {
    const Eigen::Isometry3d T_best = result.starts[static_cast<std::size_t>(result.best)].T_probe;
    const auto n = static_cast<double>(subset.size());
    int swap = -1;
    for (std::size_t j = 0; j < result.starts.size(); ++j) {
      const StartReport& s = result.starts[j];
      const double best_only = s.best_only_share * n, only = s.only_share * n;
      const bool coin_toss = best_only - only <= 2.0 * std::sqrt(best_only + only);
      if (!s.ties_best || !coin_toss || !holes_tell(T_best, s.T_probe, nullptr)) continue;
      if (swap < 0 || better(s, result.starts[static_cast<std::size_t>(swap)])) swap = static_cast<int>(j);
    }
    if (swap >= 0) {
      for (StartReport& s : result.starts) clear_judgement(s);
      result.ambiguous = false;
      result.runner_up = -1;
      result.best = swap;
      judge();
    }
  }
  return result;
}

}  // namespace conform
