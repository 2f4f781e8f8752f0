// SPDX-License-Identifier: MIT
#include "mirage/methods/acoustic/ground_echo_fix.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "mirage/estimation/gates/chi2_gate.h"
#include "mirage/estimation/robust/hampel.h"
#include "mirage/estimation/solvers/toa_nlls.h"

namespace mirage::methods::acoustic {
namespace {

// How fixes of one emission's selection rank in the consensus over smallest sets (and, after the
// MSAC score of all the stamps, between the vote's clusters): more microphones within 3 sigma,
// then more of the emission's stamps explained (a microphone's modelled arrivals among all its
// stamps, SupportAt), then the smaller sum of squared misses. Three nearly collinear microphones
// and a false alarm fit a point on a circle around their line as closely as four true stamps fit
// the sender; the other stamps of the emission do not follow the wrong point. The last key is
// the caller's: the supported stamps' squared misses in the consensus, the fit's own squared
// residuals between clusters.
struct FixRank {
  std::size_t mics = 0;
  int support_rows = 0;
  double tie_sum_sq_m2 = 0.0;
  [[nodiscard]] bool Beats(const FixRank& other) const {
    if (mics != other.mics) return mics > other.mics;
    if (support_rows != other.support_rows) return support_rows > other.support_rows;
    return tie_sum_sq_m2 < other.tie_sum_sq_m2;
  }
};

}  // namespace

const core::OptionsDescriptor<GroundEchoOptions>& GroundEchoOptionsDescriptor() {
  using core::ValueRange;
  using O = GroundEchoOptions;
  static const auto descriptor = [] {
    core::OptionsDescriptor<O> d("methods::acoustic::GroundEchoOptions");
    d.Boolean(&O::echoes, {.key = "echoes",
                           .doc = "Use the floor-echo rows (microphones mirrored in the floor, Sec. 8.4); false: the "
                                  "line-of-sight rows only."});
    d.Choice(&O::sending_time,
             {.key = "sending_time",
              .doc = "estimated: t_0 from the vote over 4-tuples of LOS and floor-echo stamps (Eq. 8.77-8.79); "
                     "known: the records' emission time (a synchronised sender or a reference system); unknown: an "
                     "offset solved with the position (the TDOA variants, Sec. 8.3)."},
             {"estimated", "known", "unknown"});
    d.Boolean(&O::vote_prior,
              {.key = "vote_prior",
               .doc = "With sending_time estimated: true, the vote's t_0 is a prior (its robust sigma) on an "
                      "offset solved with the fix, and the DOPs are those of the rows plus that prior; false, the "
                      "thesis's plug-in (Eq. 8.80 with t_0 fixed), whose t_0 error (noise gain 10-50 of Eq. 8.77) "
                      "lands in the height, with the range model's DOPs."});
    d.Number(&O::vote_window_s,
             {.key = "vote_window_s",
              .unit = "s",
              .range = ValueRange::Above(0.0),
              .doc = "Longest span of emissions voted together; shortened so that the clock drift moves t_0 by at "
                     "most half a stamp sigma across it. 1 s."});
    d.Number(&O::max_sender_height_m, {.key = "max_sender_height_m",
                                       .unit = "m",
                                       .range = ValueRange::Above(0.0),
                                       .doc = "Largest height of the sender above the floor: the echo delay is at "
                                              "most 2 h_s / c. 2.5 m."});
    d.Number(&O::max_noise_gain, {.key = "max_noise_gain",
                                  .range = ValueRange::Above(0.0),
                                  .doc = "The vote drops 4-tuples whose t_0 noise gain (Eq. 8.77) exceeds this. 20."});
    d.Boolean(&O::floor_ceiling_echoes,
              {.key = "floor_ceiling_echoes",
               .doc = "With the ceiling known: the echo off the floor and then the ceiling is a second row of the "
                      "vote's (t_0, sender height) and, with echoes, a row of the fix (the microphone mirrored in "
                      "the ceiling, then the floor); false: the floor echo only, as the thesis (its pairs with the "
                      "LOS then compete with the floor pairs in the vote)."});
    return d;
  }();
  return descriptor;
}

GroundEchoFixer::GroundEchoFixer(std::vector<Vec3> mics_m, double floor_z_m, double speed_mps, double range_sigma_m,
                                 double interval_s, double clock_drift_ppm, const GroundEchoOptions& options,
                                 std::optional<double> ceiling_z_m)
    : mics_m_(std::move(mics_m)),
      floor_z_m_(floor_z_m),
      c_mps_(speed_mps),
      sigma_m_(range_sigma_m),
      interval_s_(interval_s),
      window_s_(options.vote_window_s),
      options_(options) {
  if (mics_m_.size() < 3 ||
      std::any_of(mics_m_.begin(), mics_m_.end(), [&](const Vec3& m) { return !(m.z() > floor_z_m); }) || !(speed_mps > 0.0) || !(range_sigma_m > 0.0) || !(interval_s > 0.0)) {
    throw std::invalid_argument(
        "ground_echo: needs >= 3 microphones, all above the floor, and positive speed, sigma and interval");
  }
  // The drift moves t_0 by ppm 1e-6 per second of window: keep that below half a stamp sigma.
  const double sigma_s = sigma_m_ / c_mps_;
  if (clock_drift_ppm > 0.0) window_s_ = std::min(window_s_, 0.5 * sigma_s / (clock_drift_ppm * 1e-6));
  double lowest_m = mics_m_.front().z(), highest_m = lowest_m;
  for (const auto& m : mics_m_) {
    lowest_m = std::min(lowest_m, m.z());
    highest_m = std::max(highest_m, m.z());
  }
  vote_.method = estimation::SendingTimeVoteMethod::kConsensus;
  vote_.speed_mps = c_mps_;
  vote_.stamp_sigma_s = sigma_s;
  vote_.max_sender_height_m = options_.max_sender_height_m;
  vote_.max_noise_gain = options_.max_noise_gain;
  vote_.max_mic_height_m = std::max(highest_m - floor_z_m_, 1e-3);
  vote_.mic_height_spread_m = highest_m - lowest_m;
  vote_.los_is_first_arrival = true;
  for (const auto& m : mics_m_) vote_.mic_heights_m.push_back(m.z() - floor_z_m_);
  for (const auto& m : mics_m_) mic_plane_z_m_ += m.z() / static_cast<double>(mics_m_.size());
  ceiling_z_m_ = ceiling_z_m;
  // The ceiling pairs are excluded for senders higher above the floor than the microphones are
  // below the ceiling; when that gap exceeds the largest sender height the bound would exclude
  // every sender, and the two families cannot be told apart: no bound then.
  if (ceiling_z_m && *ceiling_z_m > highest_m && *ceiling_z_m - lowest_m < options_.max_sender_height_m) {
    const double below_ceiling_m = *ceiling_z_m - lowest_m;
    vote_.min_excess_m2 = 4.0 * below_ceiling_m * (lowest_m - floor_z_m_);
  }
  if (options_.floor_ceiling_echoes && ceiling_z_m && *ceiling_z_m > highest_m) {
    vote_.ceiling_height_m = *ceiling_z_m - floor_z_m_;
  }
  for (const auto& m : mics_m_) {
    floor_images_m_.emplace_back(m.x(), m.y(), 2.0 * floor_z_m_ - m.z());
    if (ceiling_z_m && *ceiling_z_m > highest_m) ceiling_images_m_.emplace_back(m.x(), m.y(), 2.0 * *ceiling_z_m - m.z());
    if (vote_.ceiling_height_m > 0.0) {
      floor_ceiling_images_m_.emplace_back(m.x(), m.y(), 2.0 * floor_z_m_ - (2.0 * *ceiling_z_m - m.z()));
    }
  }
}

std::optional<estimation::SolverFix> GroundEchoFixer::Solve(const std::vector<Vec3>& receivers_m,
                                                            const std::vector<double>& values_m, bool offset_unknown,
                                                            const std::optional<Vec3>& start_m,
                                                            const Vec3& fallback_start_m) const {
  const std::vector<double> sigmas_m(receivers_m.size(), sigma_m_);
  std::vector<Vec3> starts;
  if (start_m) starts.push_back(*start_m);
  starts.push_back(fallback_start_m);
  estimation::NllsOptions nlls;
  nlls.method = estimation::NllsMethod::kLevenbergMarquardt;
  for (const Vec3& s : starts) {
    estimation::SolverFix f;
    if (offset_unknown) {
      std::vector<double> implied_m;
      for (std::size_t i = 0; i < receivers_m.size(); ++i) implied_m.push_back(values_m[i] - (s - receivers_m[i]).norm());
      f = estimation::SolveToaNlls(receivers_m, values_m, sigmas_m, s, estimation::Median(implied_m), nlls);
    } else {
      f = estimation::SolveRangeNlls(receivers_m, values_m, sigmas_m, s, nlls);
    }
    if (f.converged && !f.degenerate()) return f;
  }
  return std::nullopt;
}

std::optional<GroundEchoFixer::SelectionFit> GroundEchoFixer::FitSelection(
    const std::vector<estimation::MicStampChoice>& chosen, const std::vector<std::vector<double>>& stamps_s,
    const std::optional<double>& t0_s) const {
  // The rows: each chosen microphone's LOS stamp and, with echoes, its floor-echo stamp (the
  // microphone mirrored in the floor), as ranges from t_0 or pseudo-ranges without it.
  std::vector<Vec3> receivers_m;
  std::vector<double> values_m;
  std::vector<int> row_mic;  // per row: its microphone
  // Per row: whether it is a floor-ceiling row. Such a row is left out alone when it misses (a
  // wrong pick of a late, weak echo says nothing about the microphone's LOS and floor rows); the
  // microphones are tested on their LOS and floor rows (a microphone an alternative reads from
  // its floor-ceiling echo alone, its floor echo missed, on its LOS row).
  std::vector<bool> row_optional;
  for (std::size_t m = 0; m < mics_m_.size(); ++m) {
    const auto& c = chosen[m];
    if (c.los_index < 0) continue;
    receivers_m.push_back(mics_m_[m]);
    values_m.push_back(c_mps_ * (stamps_s[m][static_cast<std::size_t>(c.los_index)] - t0_s.value_or(0.0)));
    row_mic.push_back(static_cast<int>(m));
    row_optional.push_back(false);
    if (options_.echoes && c.ground_index >= 0) {
      receivers_m.push_back(floor_images_m_[m]);
      values_m.push_back(c_mps_ * (stamps_s[m][static_cast<std::size_t>(c.ground_index)] - t0_s.value_or(0.0)));
      row_mic.push_back(static_cast<int>(m));
      row_optional.push_back(false);
    }
    // The floor-ceiling echo (only chosen with the ceiling known): the microphone mirrored in the
    // ceiling (its last reflection), then in the floor.
    if (options_.echoes && c.floor_ceiling_index >= 0 && !floor_ceiling_images_m_.empty()) {
      receivers_m.push_back(floor_ceiling_images_m_[m]);
      values_m.push_back(c_mps_ * (stamps_s[m][static_cast<std::size_t>(c.floor_ceiling_index)] - t0_s.value_or(0.0)));
      row_mic.push_back(static_cast<int>(m));
      row_optional.push_back(true);
    }
  }
  if (receivers_m.empty()) return std::nullopt;
  std::vector<bool> row_on(receivers_m.size(), true);  // optional rows not yet left out
  const bool offset_unknown = !t0_s.has_value();
  const std::size_t unknowns = offset_unknown ? 4 : 3;
  // The fallback start: below the chosen microphones' centroid, halfway to the floor.
  Vec3 centroid_m = Vec3::Zero();
  int chosen_mics = 0;
  for (std::size_t m = 0; m < mics_m_.size(); ++m) {
    if (chosen[m].los_index < 0) continue;
    centroid_m += mics_m_[m];
    ++chosen_mics;
  }
  centroid_m /= static_cast<double>(chosen_mics);
  centroid_m.z() = floor_z_m_ + 0.5 * (centroid_m.z() - floor_z_m_);

  // The fix on the rows of the microphones in `use`, from start_m, else below the centroid.
  std::vector<Vec3> rx_m;
  std::vector<double> z_m;
  const auto fit = [&](const std::vector<bool>& use,
                       const std::optional<Vec3>& start_m) -> std::optional<estimation::SolverFix> {
    rx_m.clear();
    z_m.clear();
    for (std::size_t r = 0; r < receivers_m.size(); ++r) {
      if (!use[static_cast<std::size_t>(row_mic[r])] || !row_on[r]) continue;
      rx_m.push_back(receivers_m[r]);
      z_m.push_back(values_m[r]);
    }
    if (rx_m.size() < unknowns) return std::nullopt;
    auto f = Solve(rx_m, z_m, offset_unknown, start_m, centroid_m);
    if (!f) return std::nullopt;
    // A fix below the floor by more than 3 sigma (its own vertical sigma, at least a stamp's) is
    // no sender: three nearly collinear microphones fit any point of a circle around their line.
    const double sigma_z_m = std::max(sigma_m_, std::sqrt(std::max(f->covariance_m2(2, 2), 0.0)));
    if (f->position_m.z() < floor_z_m_ - 3.0 * sigma_z_m) return std::nullopt;
    // Coplanar microphones (LOS rows only) fit the sender and its mirror image in their plane
    // alike: a fix above the ceiling, or higher than any sender, is that mirror; start again from
    // below the microphones.
    const auto implausible = [&](const Vec3& p) {
      return (ceiling_z_m_ && p.z() > *ceiling_z_m_) || p.z() - floor_z_m_ > options_.max_sender_height_m;
    };
    if (implausible(f->position_m)) {
      Vec3 mirrored_m = f->position_m;
      mirrored_m.z() = 2.0 * mic_plane_z_m_ - f->position_m.z();
      f = Solve(rx_m, z_m, offset_unknown, mirrored_m, centroid_m);
      if (!f || implausible(f->position_m)) return std::nullopt;
    }
    return f;
  };
  // A row's residual at a fix (m); an offset solved on a subset applies to every row (it is the
  // sender's).
  const auto residual_of = [&](const estimation::SolverFix& f, std::size_t r) {
    return std::abs(values_m[r] - (f.position_m - receivers_m[r]).norm() - f.offset_m);
  };
  // Each microphone's largest residual of its LOS and floor rows at a fix (m).
  const auto mic_residuals_m = [&](const estimation::SolverFix& f) {
    std::vector<double> worst_m(mics_m_.size(), 0.0);
    for (std::size_t r = 0; r < receivers_m.size(); ++r) {
      if (row_optional[r]) continue;
      auto& worst = worst_m[static_cast<std::size_t>(row_mic[r])];
      worst = std::max(worst, residual_of(f, r));
    }
    return worst_m;
  };
  const double gate_m = 3.0 * sigma_m_;
  // The stamps' origin at a fix (m): c t_0 when t_0 is given, else the fix's solved offset.
  const auto origin_m = [&](const estimation::SolverFix& f) { return t0_s ? c_mps_ * *t0_s : f.offset_m; };
  const auto within = [&](const estimation::SolverFix& f) {
    const auto residual_m = mic_residuals_m(f);
    std::vector<bool> in(residual_m.size(), false);
    for (const int m : row_mic) in[static_cast<std::size_t>(m)] = residual_m[static_cast<std::size_t>(m)] <= gate_m;
    return in;
  };
  // The smallest set: the fewest microphones whose rows cover the unknowns, and with a solved
  // offset at least three: two microphones and their floor mirrors are four receivers in one
  // vertical plane, whose position-and-offset fix has a twin across the plane and is
  // ill-conditioned. A fix of no more microphones fits them exactly (or nearly) whatever their
  // stamps are and verifies nothing: at least one microphone beyond it must agree, whether or
  // not the consensus search ran. (Three microphones with echoes and a solved offset leave two
  // redundant rows, but their wrong clusters fit too: in the example the three-microphone fixes
  // were the largest errors; a fix then needs four.)
  std::vector<int> mics;
  std::vector<std::size_t> rows_per_mic;
  for (std::size_t m = 0; m < mics_m_.size(); ++m) {
    const auto rows = static_cast<std::size_t>(std::count(row_mic.begin(), row_mic.end(), static_cast<int>(m)));
    if (rows == 0) continue;
    mics.push_back(static_cast<int>(m));
    rows_per_mic.push_back(rows);
  }
  std::sort(rows_per_mic.rbegin(), rows_per_mic.rend());
  std::size_t smallest_set = 0;
  for (std::size_t covered = 0; smallest_set < rows_per_mic.size() && covered < unknowns; ++smallest_set) {
    covered += rows_per_mic[smallest_set];
  }
  if (offset_unknown) smallest_set = std::max<std::size_t>(smallest_set, std::min<std::size_t>(3, mics.size()));
  // One microphone's receivers (itself and its images) lie on one vertical line: no horizontal fix.
  smallest_set = std::max<std::size_t>(smallest_set, std::min<std::size_t>(2, mics.size()));
  std::vector<bool> used(mics_m_.size(), false);
  for (const int m : row_mic) used[static_cast<std::size_t>(m)] = true;
  std::optional<estimation::SolverFix> fix = fit(used, last_m_);
  if (!fix || within(*fix) != used) {
    // A stamp off by more than 3 sigma (a wrong pick, a heavy-tail stamp) pulls the fit of all
    // rows towards it, so the largest residual need not be its own (masking): dropping
    // microphones one at a time from that fit can end on a few consistent but wrong ones. The
    // largest consensus instead (Fischler & Bolles, the thesis's [84]): every smallest set of
    // microphones with rows for the unknowns is solved, the microphones within 3 sigma of its
    // fix are its consensus, and the largest one is refitted and checked once more against all
    // microphones. Ties go by FixRank (the stamps of the whole emission the fix explains, then
    // the sum of their squared misses). Up to C(12, 4) = 495 solves
    // for twelve microphones without echoes, only at emissions whose full fit fails the test.
    // With echo rows and t_0 given the smallest set is two microphones, whose four receivers
    // (each with its floor mirror) lie in one vertical plane: its fit has a mirror solution
    // across that plane, and the one found depends on the start (the last fix); the consensus of
    // the wrong one is the smaller. With the offset solved too it is three (above).
    const std::size_t k = smallest_set;
    std::vector<bool> pick(mics.size(), false);
    std::fill(pick.begin(), pick.begin() + static_cast<std::ptrdiff_t>(k), true);
    std::vector<bool> best_in;
    FixRank best;
    const std::optional<Vec3> start_m = fix ? std::optional<Vec3>(fix->position_m) : last_m_;
    do {
      std::vector<bool> subset(mics_m_.size(), false);
      for (std::size_t i = 0; i < mics.size(); ++i) subset[static_cast<std::size_t>(mics[i])] = pick[i];
      const auto f = fit(subset, start_m);
      if (!f) continue;
      const auto in = within(*f);
      const auto count = static_cast<std::size_t>(std::count(in.begin(), in.end(), true));
      if (count == 0 || count < best.mics) continue;
      const StampSupport support = SupportAt(f->position_m, origin_m(*f), stamps_s);
      const FixRank rank{count, support.rows, support.sum_sq_m2};
      if (rank.Beats(best)) {
        best_in = in;
        best = rank;
      }
    } while (std::prev_permutation(pick.begin(), pick.end()));
    if (best.mics <= k) return std::nullopt;
    used = best_in;
    fix = fit(used, start_m);
    if (fix) {
      // The consensus fit may admit a microphone the smallest set's noisier fix had left out.
      const auto again = within(*fix);
      if (std::count(again.begin(), again.end(), true) > std::count(used.begin(), used.end(), true)) {
        if (auto wider = fit(again, fix->position_m)) {
          used = again;
          fix = std::move(wider);
        }
      }
    }
  }
  // Then, within the consensus, the microphone with the largest residual beyond 3 sigma is left
  // out (all its rows: a wrong LOS pick makes its echoes wrong too), or the floor-ceiling row
  // when its own residual is the largest, and the fix repeated, while rows for the unknowns
  // remain.
  for (;;) {
    if (!fix) return std::nullopt;
    const auto residual_m = mic_residuals_m(*fix);
    int worst = -1;
    int worst_row = -1;
    double worst_m = gate_m;
    for (std::size_t m = 0; m < residual_m.size(); ++m) {
      if (used[m] && residual_m[m] > worst_m) {
        worst_m = residual_m[m];
        worst = static_cast<int>(m);
      }
    }
    for (std::size_t r = 0; r < receivers_m.size(); ++r) {
      if (!row_optional[r] || !row_on[r] || !used[static_cast<std::size_t>(row_mic[r])]) continue;
      if (const double e_m = residual_of(*fix, r); e_m > worst_m) worst_m = e_m, worst_row = static_cast<int>(r);
    }
    if (worst_row >= 0) {
      row_on[static_cast<std::size_t>(worst_row)] = false;
    } else if (worst >= 0) {
      used[static_cast<std::size_t>(worst)] = false;
    } else {
      break;
    }
    fix = fit(used, fix->position_m);
  }
  if (static_cast<std::size_t>(std::count(used.begin(), used.end(), true)) <= smallest_set) {
    return std::nullopt;
  }
  SelectionFit out{*fix};
  Vec3 sum_u = Vec3::Zero();  // the rows' unit vectors receiver -> sender
  for (std::size_t r = 0; r < receivers_m.size(); ++r) {
    const auto m = static_cast<std::size_t>(row_mic[r]);
    if (!used[m] || !row_on[r]) continue;
    const bool is_echo = r > 0 && row_mic[r - 1] == row_mic[r];
    (is_echo ? out.echo_rows : out.los_rows) += 1;
    const Vec3 leg_m = fix->position_m - receivers_m[r];
    const double e_m = values_m[r] - leg_m.norm() - fix->offset_m;
    out.sum_sq_m2 += e_m * e_m;
    sum_u += leg_m.normalized();
  }
  out.mics = static_cast<int>(std::count(used.begin(), used.end(), true));
  const StampSupport support = SupportAt(fix->position_m, origin_m(*fix), stamps_s);
  out.support_rows = support.rows;
  out.support_score = support.score;
  // (H^T R^-1 H)^-1 H^T R^-1 1 with equal sigmas: the covariance times sum u_r / sigma^2.
  out.common_shift_gain = fix->covariance_m2.topLeftCorner<3, 3>() * sum_u / (sigma_m_ * sigma_m_);
  return out;
}

GroundEchoFixer::StampSupport GroundEchoFixer::SupportAt(const Vec3& position_m, double origin_m,
                                                        const std::vector<std::vector<double>>& stamps_s) const {
  const double gate_m = 3.0 * sigma_m_;
  StampSupport out;
  // Each microphone's modelled arrivals in order: the LOS, the floor echo, and (when known) the
  // ceiling and the floor-ceiling echo; each takes the nearest stamp within the gate that an
  // earlier arrival of the microphone has not taken.
  const std::vector<Vec3>* receivers[] = {&mics_m_, &floor_images_m_, &ceiling_images_m_, &floor_ceiling_images_m_};
  std::vector<int> taken;
  for (std::size_t m = 0; m < mics_m_.size(); ++m) {
    const std::vector<double>& list_s = stamps_s[m];
    taken.clear();
    for (const std::vector<Vec3>* images : receivers) {
      if (images->empty()) continue;
      const double range_m = (position_m - (*images)[m]).norm();
      double nearest_m = gate_m;
      int index = -1;
      for (std::size_t i = 0; i < list_s.size(); ++i) {
        const double miss_m = std::abs(c_mps_ * list_s[i] - origin_m - range_m);
        const bool free = std::find(taken.begin(), taken.end(), static_cast<int>(i)) == taken.end();
        if (free && miss_m <= nearest_m) nearest_m = miss_m, index = static_cast<int>(i);
      }
      if (index < 0) continue;
      taken.push_back(index);
      out.rows += 1;
      out.sum_sq_m2 += nearest_m * nearest_m;
      out.score += 9.0 - nearest_m * nearest_m / (sigma_m_ * sigma_m_);
    }
  }
  return out;
}

OffsetPriorUpdate UpdateWithOffsetPrior(const Eigen::Matrix4d& covariance_m2, double offset_m, double prior_m,
                                        double prior_sigma_m) {
  OffsetPriorUpdate out;
  const Vec3 cross_m2 = covariance_m2.block<3, 1>(0, 3);
  const double offset_var_m2 = covariance_m2(3, 3);
  out.covariance_m2 = covariance_m2.topLeftCorner<3, 3>();
  out.offset_m = offset_m;
  const double innovation_m = prior_m - offset_m;
  const double innovation_var_m2 = offset_var_m2 + prior_sigma_m * prior_sigma_m;
  if (!(prior_sigma_m > 0.0) || !(innovation_var_m2 > 0.0) ||
      !estimation::InsideChi2Gate(innovation_m, innovation_var_m2, 9.0)) {
    return out;  // no prior, or one that contradicts the stamps (beyond 3 sigma)
  }
  out.used = true;
  out.shift_m = cross_m2 * innovation_m / innovation_var_m2;
  out.covariance_m2 -= cross_m2 * cross_m2.transpose() / innovation_var_m2;
  out.offset_m = offset_m + offset_var_m2 * innovation_m / innovation_var_m2;
  return out;
}

GroundEchoFix GroundEchoFixer::Process(const core::Epoch& epoch) {
  GroundEchoFix out;
  Emission emission;
  emission.t_s = epoch.t_s;
  emission.stamps_s.resize(mics_m_.size());
  std::optional<double> known_emission_s;
  for (const auto& record : epoch.toas) {
    auto& list = emission.stamps_s.at(static_cast<std::size_t>(record.receiver_index));
    list.insert(list.end(), record.toa_s.begin(), record.toa_s.end());
    if (record.emission_s && !known_emission_s) known_emission_s = record.emission_s;
  }
  window_.push_back(std::move(emission));
  while (window_.front().t_s < epoch.t_s - window_s_) window_.pop_front();

  // 1. The vote over the window, every emission's stamps relative to this epoch's time minus its
  //    elapsed intervals (Eq. 8.79), so that all share this emission's t_0.
  std::vector<estimation::EmissionStamps> voted;
  for (const auto& e : window_) {
    // Elapsed intervals from the epochs' times (each its emission's earliest stamp): an emission
    // whose time falls far between two interval counts (a false alarm before every arrival) is
    // left out of the vote rather than shifted by a whole interval.
    const double intervals = (e.t_s - epoch.t_s) / interval_s_;
    if (std::abs(intervals - std::round(intervals)) > 0.25) continue;
    const double elapsed_s = std::round(intervals) * interval_s_;
    estimation::EmissionStamps stamps;
    for (const auto& list : e.stamps_s) {
      std::vector<double> relative;
      for (const double t_s : list) relative.push_back(t_s - epoch.t_s - elapsed_s);
      stamps.mic_stamps_s.push_back(std::move(relative));
    }
    voted.push_back(std::move(stamps));
  }
  // A tracked sending time predicts this one (the last t_0 plus the elapsed intervals; the drift
  // over them is far below a stamp sigma); the full search runs only without a recent t_0.
  std::optional<estimation::SendingTimeVote> vote;
  if (options_.sending_time == "known" && known_emission_s) {
    // The known t_0 is the hypothesis: only the stamps are selected.
    vote = estimation::VoteSendingTimeAt(voted, *known_emission_s - epoch.t_s, vote_);
  } else if (track_ && epoch.t_s - track_->epoch_s <= window_s_) {
    const double elapsed_s = std::round((epoch.t_s - track_->epoch_s) / interval_s_) * interval_s_;
    vote = estimation::VoteSendingTimeAt(voted, track_->t0_s + elapsed_s - epoch.t_s, vote_);
  } else {
    vote = estimation::VoteSendingTime(voted, vote_);
  }
  if (!vote) return out;
  const auto& chosen = vote->chosen.back();
  const auto heard = std::count_if(chosen.begin(), chosen.end(), [](const auto& c) { return c.los_index >= 0; });
  if (heard < 3) return out;  // this emission has no consistent LOS / floor-echo set
  track_ = Track{epoch.t_s, epoch.t_s + vote->t0_s};
  if (options_.sending_time == "estimated") {
    out.voted_sending_time_s = epoch.t_s + vote->t0_s;
    out.voted_sending_time_sigma_s = vote->t0_sigma_s;
  }

  // 2. The sending time, relative to epoch.t_s.
  std::optional<double> t0_s;
  // With the vote as a prior the stamps are fitted with a solved offset (as "unknown"), and the
  // vote's t_0 enters afterwards (step 5).
  const bool vote_prior = options_.sending_time == "estimated" && options_.vote_prior;
  if (options_.sending_time == "estimated" && !vote_prior) t0_s = vote->t0_s;
  if (options_.sending_time == "known") {
    if (!known_emission_s) return out;  // the records do not carry it: no fix
    t0_s = *known_emission_s - epoch.t_s;
  }

  // 3-4. The fix of the vote's K cluster, and of each of its other clusters: a wall echo and its
  //      floor echo share K like the LOS and the floor echo (and at a sender on a symmetry line
  //      of the room, LOS / wall-echo pairs of several microphones share one K), and the vote's
  //      tie-break between clusters of as many microphones (the spread of K) is weak; the
  //      geometry decides (Fischler & Bolles's verification step) over all of the emission's
  //      stamps, not only the selection's: the fix whose modelled arrivals (LOS, floor, ceiling
  //      and floor-ceiling echo at every microphone, SupportAt) explain the stamps best by the
  //      MSAC score (Torr & Zisserman: each explained arrival 9 - (miss / sigma)^2, within
  //      3 sigma) wins, on an exact tie the one keeping more microphones of its selection, then
  //      the smaller sum of squared misses. Every cluster is fitted: a smaller cluster's fit still
  //      has to explain the other microphones' stamps to win (ranked by its own microphones, a
  //      smaller cluster fitted its own geometry too easily to overrule the vote's count, and
  //      only the clusters as large as the vote's were fitted).
  const auto& stamps = voted.back().mic_stamps_s;
  // With the vote's t_0 as a prior (step 5) it is one more arrival of the MSAC score: the
  // solved offset's miss over the prior's and the fix's variance, 9 - z^2 within 3 sigma (the
  // prior's gate below). A selection that reads the floor-ceiling echoes as floor echoes fits a
  // sender higher by (C - h) (C + z) / h with a later offset: nearly consistent as
  // pseudo-ranges, not with the vote's t_0. (It replaced ranking every fix that contradicts the
  // prior last: a vote t_0 3 sigma off its track then kept the true fix out.)
  const bool prior_check = vote_prior && vote->t0_sigma_s > 0.0;
  const auto prior_score = [&](const SelectionFit& f) {
    if (!prior_check) return 0.0;
    const double sigma_m = c_mps_ * vote->t0_sigma_s;
    const double miss_m = c_mps_ * vote->t0_s - f.fix.offset_m;
    return std::max(0.0, 9.0 - miss_m * miss_m / (f.fix.covariance_m2(3, 3) + sigma_m * sigma_m));
  };
  // Ranked by the MSAC score of the emission's stamps (with the prior's term), then as in the
  // consensus (FixRank), by the fit's own sum of squared residuals last.
  const auto better = [&](const SelectionFit& a, const SelectionFit& b) {
    const double score_a = a.support_score + prior_score(a), score_b = b.support_score + prior_score(b);
    if (score_a != score_b) return score_a > score_b;
    const auto rank = [](const SelectionFit& f) {
      return FixRank{static_cast<std::size_t>(f.mics), f.support_rows, f.sum_sq_m2};
    };
    return rank(a).Beats(rank(b));
  };
  std::optional<SelectionFit> best = FitSelection(chosen, stamps, t0_s);
  // The thesis's plug-in t_0 (Eq. 8.80) is the exception: its fits take the vote's t_0 as exact,
  // whose error (~3 stamp sigmas) shifts every fit's misses alike, and the comparison over all
  // stamps then prefers wrong smaller clusters (the plug-in variant's height RMSE 15 -> 23 mm,
  // 0.66 m at worst): with it only the clusters of as many microphones as the vote's are fitted.
  const bool plug_in = options_.sending_time == "estimated" && !vote_prior;
  for (const auto& alternative : vote->alternatives) {
    const auto mics = std::count_if(alternative.begin(), alternative.end(), [](const auto& c) { return c.los_index >= 0; });
    if (plug_in && mics < heard) continue;
    auto fit = FitSelection(alternative, stamps, t0_s);
    if (fit && (!best || better(*fit, *best))) {
      best = std::move(fit);
    }
  }
  if (!best) return out;
  const estimation::SolverFix* fix = &best->fix;
  // The DOPs of the rows used (Eq. 8.10-8.12): the solver's covariance is (H^T R^-1 H)^-1 at the
  // fix, the CRLB of the range model (t_0 given) or of the pseudo-range model (t_0 unknown: the
  // position block of [x, y, z, b]), each row with sigma.
  Eigen::Matrix3d dop_crlb_m2 = fix->covariance_m2.topLeftCorner<3, 3>();
  Eigen::Matrix3d covariance_m2 = dop_crlb_m2;
  Vec3 position_m = fix->position_m;
  double sending_time_s = epoch.t_s + (t0_s ? *t0_s : fix->offset_m / c_mps_);
  if (vote_prior) {
    // 5. The vote's t_0 as a prior on the solved offset b: one linear (Kalman) update of the fix
    //    [x, b] with the pseudo-measurement b = c t_0 of variance (c sigma_t0)^2, which enters the
    //    position through the fix's own covariance of x with b. The vote's t_0 carries the noise
    //    gain of Eq. 8.77 (10-50 per stamp, reduced by the window's pooling); the offset solved
    //    with floor echoes is far tighter, so the prior mostly checks it. The vote uses these
    //    stamps too (and the window's earlier ones), so the update counts them twice: the
    //    reported covariance is somewhat tight without echoes. A prior more than 3 sigma from the
    //    solved offset, or without a sigma (the vote's refinement failed), is left out: the
    //    stamps' fix stands. The DOPs are those of the information used, the rows and the vote's
    //    t_0 at its sigma (the updated covariance; without the prior the pseudo-range model's):
    //    the range model's (t_0 given) would credit the fix with a t_0 the vote cannot deliver
    //    (its error enters the height almost 1:1 without echoes; docs/results/acoustic.md).
    const OffsetPriorUpdate update =
        UpdateWithOffsetPrior(fix->covariance_m2, fix->offset_m, c_mps_ * vote->t0_s, c_mps_ * vote->t0_sigma_s);
    dop_crlb_m2 = update.covariance_m2;
    covariance_m2 = update.covariance_m2;
    position_m += update.shift_m;
    sending_time_s = epoch.t_s + update.offset_m / c_mps_;
  } else if (options_.sending_time == "estimated") {
    // The plugged-in t_0's own error (the vote's sigma over the window) enters every row
    // alike: the reported covariance adds it; the DOPs stay those of the geometry.
    const Vec3 gain_m = best->common_shift_gain * c_mps_ * vote->t0_sigma_s;
    covariance_m2 += gain_m * gain_m.transpose();
  }
  const double hdop = std::sqrt(dop_crlb_m2(0, 0) + dop_crlb_m2(1, 1)) / sigma_m_;
  const double vdop = std::sqrt(dop_crlb_m2(2, 2)) / sigma_m_;
  if (!std::isfinite(hdop) || !std::isfinite(vdop)) return out;

  out.found = true;
  out.los_rows = best->los_rows;
  out.echo_rows = best->echo_rows;
  out.position_m = position_m;
  out.covariance_m2 = covariance_m2;
  out.hdop = hdop;
  out.vdop = vdop;
  out.sending_time_s = sending_time_s;
  last_m_ = position_m;
  return out;
}

}  // namespace mirage::methods::acoustic
