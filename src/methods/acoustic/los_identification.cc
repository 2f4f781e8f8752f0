// SPDX-License-Identifier: MIT
#include "mirage/methods/acoustic/los_identification.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>
#include <optional>
#include <utility>

#include <Eigen/Geometry>

#include "mirage/estimation/meas/toa.h"
#include "mirage/estimation/robust/regression_diagnostics.h"
#include "mirage/estimation/solvers/closed_form_tdoa_2d.h"
#include "mirage/estimation/solvers/toa_nlls.h"

namespace mirage::methods::acoustic {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();
// Cook's divisor: x, y and the emission offset b (see the header).
constexpr int kCookPPrime = 3;
// A cofactor below this fraction of |n| means leverage 1 (as regression_diagnostics: 1 - l <= 1e-10).
constexpr double kMinResidualWeight = 1e-10;

// The stamps of the receivers, prepared once per call: the K earliest per receiver (flat, K slots
// each) with their input indices, and the earliest of all.
struct StampTable {
  int k = 0;
  std::vector<double> rho_m;      // N * k
  std::vector<int> input_index;   // N * k
  std::vector<int> count;         // N
  std::vector<double> earliest_m; // N (+inf without stamps)
};

StampTable PrepareStamps(const std::vector<std::vector<double>>& pseudo_ranges_m, int k) {
  const std::size_t n = pseudo_ranges_m.size();
  StampTable table;
  table.k = k;
  table.rho_m.assign(n * static_cast<std::size_t>(k), kNaN);
  table.input_index.assign(n * static_cast<std::size_t>(k), -1);
  table.count.assign(n, 0);
  table.earliest_m.assign(n, kInf);
  std::vector<int> order;
  for (std::size_t i = 0; i < n; ++i) {
    const std::vector<double>& stamps = pseudo_ranges_m[i];
    order.clear();
    for (std::size_t s = 0; s < stamps.size(); ++s) {
      if (std::isfinite(stamps[s])) order.push_back(static_cast<int>(s));
    }
    const auto by_value = [&](int a, int b) { return stamps[static_cast<std::size_t>(a)] < stamps[static_cast<std::size_t>(b)]; };
    const std::size_t take = std::min(order.size(), static_cast<std::size_t>(k));
    std::partial_sort(order.begin(), order.begin() + static_cast<std::ptrdiff_t>(take), order.end(), by_value);
    table.count[i] = static_cast<int>(take);
    for (std::size_t s = 0; s < take; ++s) {
      const std::size_t slot = i * static_cast<std::size_t>(k) + s;
      table.rho_m[slot] = stamps[static_cast<std::size_t>(order[s])];
      table.input_index[slot] = order[s];
    }
    if (take > 0) table.earliest_m[i] = table.rho_m[i * static_cast<std::size_t>(k)];
  }
  return table;
}

// The best candidate so far.
struct Best {
  int votes = -1;
  double cost = kInf;
  Vec3 position_m = Vec3::Zero();
  double offset_m = 0.0;
  std::array<int, 3> triplet{-1, -1, -1};
  std::vector<int> slot;  // per receiver: the chosen stamp slot (0..k-1), or -1
};

// The descriptor; without the keys a host method shares (the stamp sigma and the TDOA bound),
// which it copies into the options itself.
core::OptionsDescriptor<LosIdentificationOptions> MakeDescriptor(bool with_shared_keys) {
  using core::ValueRange;
  using O = LosIdentificationOptions;
  core::OptionsDescriptor<O> d("methods::acoustic::LosIdentificationOptions");
  if (with_shared_keys) {
    d.Number(&O::range_sigma_m, {.key = "range_sigma_m",
                                 .unit = "m",
                                 .range = ValueRange::Above(0.0),
                                 .doc = "Standard deviation of one stamp as a distance. 0.103 m = 0.3 ms at 343 m/s, "
                                        "the ch. 5 synthetic regime."});
    d.Boolean(&O::tdoa_bound, {.key = "tdoa_bound",
                               .doc = "Skip stamp choices that break the TDOA bound (Eq. 5.5); saves closed-form "
                                      "solves, never changes the fix."});
    d.Number(&O::tdoa_bound_sigmas, {.key = "tdoa_bound_sigmas",
                                     .range = ValueRange::AtLeast(0.0),
                                     .doc = "Margin of the TDOA bound in sigmas of a stamp difference. 3."});
  }
  d.Integer(&O::max_stamps_per_receiver,
            {.key = "max_stamps_per_receiver",
             .range = ValueRange::Closed(1.0, 16.0),
             .doc = "K: the K earliest stamps of each receiver enter the combinations (C(N,3) K^3 closed forms). "
                    "2: the direct path and one echo."});
  d.Boolean(&O::causality_test, {.key = "causality_test",
                                 .doc = "Reject fixes before whose direct path some stamp arrives (Eq. 5.4): "
                                        "virtual senders."});
  d.Number(&O::causality_sigmas, {.key = "causality_sigmas",
                                  .range = ValueRange::AtLeast(0.0),
                                  .doc = "Margin of the causality test in stamp sigmas. 3."});
  d.Boolean(&O::cook_voting, {.key = "cook_voting",
                              .doc = "Vote by Cook's distance of the 4-row problem (the thesis's Sec. 5.1 steps 4-7); "
                                     "false (default): by a window of window_sigmas around the predicted stamp."});
  d.Number(&O::cook_probability, {.key = "cook_probability",
                                  .range = ValueRange::Open(0.0, 1.0),
                                  .doc = "Probability of the F quantile used as Cook's threshold (cook_voting). 0.5: the usual "
                                         "rule of thumb D > F_0.5(p', m - p')."});
  d.Number(&O::window_sigmas, {.key = "window_sigmas",
                               .range = ValueRange::Above(0.0),
                               .doc = "Half-width of the voting window around the fix's predicted stamp (cook_voting "
                                      "false), in stamp sigmas. 3."});
  d.Boolean(&O::final_test, {.key = "final_test",
                             .doc = "After the refinement, leave out the stamp furthest from the fit (studentised "
                                    "residual) while it lies beyond window_sigmas, and refit."});
  d.Integer(&O::min_votes, {.key = "min_votes",
                            .range = ValueRange::AtLeast(0.0),
                            .doc = "Fewest voters beyond the triplet for a fix. 1: a triplet alone is verified by "
                                   "nothing."});
  d.Integer(&O::max_triplets, {.key = "max_triplets",
                               .range = ValueRange::AtLeast(0.0),
                               .doc = "Most receiver triplets enumerated, those of the earliest receivers first; "
                                      "0: all."});
  d.Integer(&O::max_refine_iterations, {.key = "max_refine_iterations",
                                        .range = ValueRange::AtLeast(1.0),
                                        .doc = "Iteration limit of the final Levenberg-Marquardt refinement. 50."});
  return d;
}

// The row of the planar TOA fit (unknowns x, y, b) with the largest studentised residual
// |e_i| / (sigma sqrt(1 - l_ii)) (Eq. 5.12, the known sigma) at (sender, offset), and that value;
// {-1, 0} when nothing can be tested (H^T H singular, or every row of leverage 1).
std::pair<int, double> WorstStudentisedResidual(const std::vector<Vec3>& mics_m, const std::vector<double>& rho_m,
                                                const Vec3& sender_m, double offset_m, double sigma_m) {
  const auto m = static_cast<Eigen::Index>(mics_m.size());
  Eigen::MatrixXd H(m, 3);
  Eigen::VectorXd e(m);
  for (Eigen::Index i = 0; i < m; ++i) {
    const Vec3& mic = mics_m[static_cast<std::size_t>(i)];
    const auto row = ToaJacobianXyb(sender_m, mic);
    if (!row) return {-1, 0.0};  // the fix sits on a receiver
    H.row(i) = *row;
    e(i) = rho_m[static_cast<std::size_t>(i)] - offset_m - (sender_m - mic).norm();
  }
  const auto diagnostics = estimation::DiagnoseRegression(H, e, {.sigma = sigma_m});
  if (!diagnostics) return {-1, 0.0};
  int worst = -1;
  double largest = 0.0;
  for (Eigen::Index i = 0; i < m; ++i) {
    const double w = std::abs(diagnostics->studentized(i));
    if (w > largest) {  // NaN (leverage 1) compares false
      largest = w;
      worst = static_cast<int>(i);
    }
  }
  return {worst, largest};
}

}  // namespace

const core::OptionsDescriptor<LosIdentificationOptions>& LosIdentificationOptionsDescriptor() {
  static const auto descriptor = MakeDescriptor(true);
  return descriptor;
}

const core::OptionsDescriptor<LosIdentificationOptions>& LosIdentificationSectionDescriptor() {
  static const auto descriptor = MakeDescriptor(false);
  return descriptor;
}

std::vector<std::string> Validate(const LosIdentificationOptions& options) {
  return LosIdentificationOptionsDescriptor().Validate(options);
}

std::optional<Eigen::RowVector3d> ToaJacobianXyb(const Vec3& sender_m, const Vec3& receiver_m) {
  const auto prediction = estimation::PredictToa(sender_m, receiver_m, 0.0);
  if (!prediction) return std::nullopt;
  return Eigen::RowVector3d(prediction->d_sender.x(), prediction->d_sender.y(), 1.0);
}

double MaxCookDistance4x3(const Eigen::Matrix<double, 4, 3>& J_pred_state, const Eigen::Vector4d& prediction_residual_m,
                          double sigma_m, int p_prime) {
  assert(sigma_m > 0.0 && p_prime >= 1);
  using Row = Eigen::RowVector3d;
  const Row h0 = J_pred_state.row(0);
  const Row h1 = J_pred_state.row(1);
  const Row h2 = J_pred_state.row(2);
  const Row h3 = J_pred_state.row(3);
  // n_j = (-1)^j det(H without row j), det(a, b, c) = c . (a x b): n^T H = 0 (cofactor expansion
  // of [H, H_col] with a repeated column), so n spans the residual space when rank H = 3.
  const Row c01 = h0.cross(h1);
  const Eigen::Vector4d n(h3.dot(h1.cross(h2)), -h3.dot(h0.cross(h2)), h3.dot(c01), -h2.dot(c01));
  const double n2 = n.squaredNorm();
  if (!(n2 > 0.0)) return kNaN;
  // e = (I - L) r0 = n (n . r0) / |n|^2, l_jj = 1 - n_j^2 / |n|^2, so
  // D_j = e_j^2 l_jj / (p' sigma^2 (1 - l_jj)^2) = (n . r0)^2 (|n|^2 - n_j^2) / (|n|^2 p' sigma^2 n_j^2).
  const double nr = n.dot(prediction_residual_m);
  const double scale = nr * nr / (n2 * p_prime * sigma_m * sigma_m);
  double worst = 0.0;
  for (int j = 0; j < 4; ++j) {
    const double nj2 = n(j) * n(j);
    if (nj2 <= kMinResidualWeight * n2) return kNaN;  // leverage 1: untestable
    worst = std::max(worst, scale * (n2 - nj2) / nj2);
  }
  return worst;
}

LosIdentification IdentifyLos(std::span<const Vec3> receivers_m, const std::vector<std::vector<double>>& pseudo_ranges_m,
                              double sender_height_m, const LosIdentificationOptions& options) {
  assert(receivers_m.size() == pseudo_ranges_m.size());
  assert(Validate(options).empty());
  LosIdentification out;
  const int n = static_cast<int>(receivers_m.size());
  out.los_stamp_index.assign(static_cast<std::size_t>(n), -1);
  if (receivers_m.size() != pseudo_ranges_m.size() || !std::isfinite(sender_height_m)) return out;

  const int k = options.max_stamps_per_receiver;
  const double sigma_m = options.range_sigma_m;
  const StampTable table = PrepareStamps(pseudo_ranges_m, k);
  const auto rho_at = [&](int receiver, int slot) {
    return table.rho_m[static_cast<std::size_t>(receiver * k + slot)];
  };

  // Step 1: receivers with stamps, ranked by their earliest stamp (ties: index).
  std::vector<int> ranked;
  for (int i = 0; i < n; ++i) {
    if (table.count[static_cast<std::size_t>(i)] > 0 && receivers_m[static_cast<std::size_t>(i)].allFinite()) {
      ranked.push_back(i);
    }
  }
  std::stable_sort(ranked.begin(), ranked.end(), [&](int a, int b) {
    return table.earliest_m[static_cast<std::size_t>(a)] < table.earliest_m[static_cast<std::size_t>(b)];
  });
  const int active = static_cast<int>(ranked.size());
  if (active < 3) return out;

  // Receiver baselines for (5.5), once.
  std::vector<double> baseline_m(static_cast<std::size_t>(n * n), 0.0);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      baseline_m[static_cast<std::size_t>(i * n + j)] =
          (receivers_m[static_cast<std::size_t>(i)] - receivers_m[static_cast<std::size_t>(j)]).norm();
    }
  }
  const double tdoa_margin_m = options.tdoa_bound_sigmas * std::sqrt(2.0) * sigma_m;
  const double causality_margin_m = options.causality_sigmas * sigma_m;
  const double window_m = options.window_sigmas * sigma_m;
  const double cook_threshold = estimation::CookThreshold(options.cook_probability, kCookPPrime, 4);

  // Scratch, sized once: the candidate's ranges to every receiver and its voters' stamp slots.
  std::vector<double> range_m(static_cast<std::size_t>(n), 0.0);
  std::vector<int> slot(static_cast<std::size_t>(n), -1);
  Best best;
  best.slot.assign(static_cast<std::size_t>(n), -1);

  const auto pair_breaks_bound = [&](int a, double rho_a, int b, double rho_b) {
    return std::abs(rho_a - rho_b) > baseline_m[static_cast<std::size_t>(a * n + b)] + tdoa_margin_m;
  };

  // Evaluates one closed-form root of the triplet (steps 3-7) and keeps it if it is the best.
  const auto evaluate = [&](const std::array<int, 3>& tri, const std::array<int, 3>& tri_slot, const Vec3& sender_m,
                            double offset_m) {
    // Step 3, Eq. (5.4): no receiver's earliest stamp may precede the direct path by more than the margin.
    for (int r = 0; r < active; ++r) {
      const int i = ranked[static_cast<std::size_t>(r)];
      const double d = (sender_m - receivers_m[static_cast<std::size_t>(i)]).norm();
      range_m[static_cast<std::size_t>(i)] = d;
      if (options.causality_test && table.earliest_m[static_cast<std::size_t>(i)] - offset_m < d - causality_margin_m) {
        ++out.virtual_senders_rejected;
        return;
      }
    }
    ++out.candidates_evaluated;
    // Steps 4-7: the triplet's rows once, then each other receiver's 4-row problem.
    Eigen::Matrix<double, 4, 3> J;
    Eigen::Vector4d r0;
    for (int t = 0; t < 3; ++t) {
      const int i = tri[static_cast<std::size_t>(t)];
      const auto row = ToaJacobianXyb(sender_m, receivers_m[static_cast<std::size_t>(i)]);
      if (!row) return;  // the fix sits on a receiver
      J.row(t) = *row;
      r0(t) = rho_at(i, tri_slot[static_cast<std::size_t>(t)]) - offset_m - range_m[static_cast<std::size_t>(i)];
    }
    int votes = 0;
    double cost = 0.0;
    for (int r = 0; r < active; ++r) {
      const int i = ranked[static_cast<std::size_t>(r)];
      slot[static_cast<std::size_t>(i)] = -1;
      if (i == tri[0] || i == tri[1] || i == tri[2]) continue;
      // The stamp nearest the prediction among the K earliest.
      const double predicted_m = range_m[static_cast<std::size_t>(i)] + offset_m;
      int nearest = 0;
      for (int s = 1; s < table.count[static_cast<std::size_t>(i)]; ++s) {
        if (std::abs(rho_at(i, s) - predicted_m) < std::abs(rho_at(i, nearest) - predicted_m)) nearest = s;
      }
      const double residual_m = rho_at(i, nearest) - predicted_m;
      bool agrees = false;
      if (options.cook_voting) {
        const auto row = ToaJacobianXyb(sender_m, receivers_m[static_cast<std::size_t>(i)]);
        if (!row) continue;
        J.row(3) = *row;
        r0(3) = residual_m;
        // NaN (untestable row) compares false: no vote.
        agrees = MaxCookDistance4x3(J, r0, sigma_m, kCookPPrime) < cook_threshold;
      } else {
        agrees = std::abs(residual_m) <= window_m;
      }
      if (!agrees) continue;
      slot[static_cast<std::size_t>(i)] = nearest;
      ++votes;
      cost += residual_m * residual_m / (sigma_m * sigma_m);
    }
    if (votes > best.votes || (votes == best.votes && cost < best.cost)) {
      best.votes = votes;
      best.cost = cost;
      best.position_m = sender_m;
      best.offset_m = offset_m;
      best.triplet = tri;
      std::copy(slot.begin(), slot.end(), best.slot.begin());
      for (int t = 0; t < 3; ++t) {
        best.slot[static_cast<std::size_t>(tri[static_cast<std::size_t>(t)])] = tri_slot[static_cast<std::size_t>(t)];
      }
    }
  };

  // Steps 1-2: triplets of ranks (a < b < c) in co-lexicographic order, then the stamp choices.
  int triplets = 0;
  for (int c = 2; c < active; ++c) {
    for (int b = 1; b < c; ++b) {
      for (int a = 0; a < b; ++a) {
        if (options.max_triplets > 0 && triplets >= options.max_triplets) break;
        ++triplets;
        const std::array<int, 3> tri{ranked[static_cast<std::size_t>(a)], ranked[static_cast<std::size_t>(b)],
                                     ranked[static_cast<std::size_t>(c)]};
        const std::array<Vec3, 3> mics{receivers_m[static_cast<std::size_t>(tri[0])],
                                       receivers_m[static_cast<std::size_t>(tri[1])],
                                       receivers_m[static_cast<std::size_t>(tri[2])]};
        for (int s0 = 0; s0 < table.count[static_cast<std::size_t>(tri[0])]; ++s0) {
          for (int s1 = 0; s1 < table.count[static_cast<std::size_t>(tri[1])]; ++s1) {
            for (int s2 = 0; s2 < table.count[static_cast<std::size_t>(tri[2])]; ++s2) {
              const std::array<double, 3> rho{rho_at(tri[0], s0), rho_at(tri[1], s1), rho_at(tri[2], s2)};
              if (options.tdoa_bound &&
                  (pair_breaks_bound(tri[0], rho[0], tri[1], rho[1]) || pair_breaks_bound(tri[0], rho[0], tri[2], rho[2]) ||
                   pair_breaks_bound(tri[1], rho[1], tri[2], rho[2]))) {
                ++out.combinations_pruned;
                continue;
              }
              ++out.closed_form_solves;
              const estimation::TdoaRoots2d roots =
                  estimation::SolveTdoa2dFromPseudoRanges(mics, rho, sender_height_m);
              for (int q = 0; q < roots.count; ++q) {
                const auto qi = static_cast<std::size_t>(q);
                evaluate(tri, {s0, s1, s2}, roots.positions_m[qi], rho[0] - roots.reference_range_m[qi]);
              }
            }
          }
        }
      }
    }
  }
  if (best.votes < options.min_votes) return out;

  // Step 8: Levenberg-Marquardt over the triplet and its voters, from the closed-form fix; with
  // the final test, while the stamp furthest from the fit (studentised) lies beyond window_sigmas
  // it is left out and the rest refit (Eq. 5.3 at the refined fix).
  std::vector<int> rows;  // receivers in the fix
  for (int i = 0; i < n; ++i) {
    if (best.slot[static_cast<std::size_t>(i)] >= 0) rows.push_back(i);
  }
  estimation::NllsOptions nlls;
  nlls.max_iterations = options.max_refine_iterations;
  nlls.method = estimation::NllsMethod::kLevenbergMarquardt;
  nlls.known_height_m = sender_height_m;
  Vec3 start_m = best.position_m;
  double start_offset_m = best.offset_m;
  estimation::SolverFix fix;
  for (;;) {
    std::vector<Vec3> mics;
    std::vector<double> rho;
    for (int i : rows) {
      mics.push_back(receivers_m[static_cast<std::size_t>(i)]);
      rho.push_back(rho_at(i, best.slot[static_cast<std::size_t>(i)]));
    }
    const std::vector<double> sigmas(mics.size(), sigma_m);
    fix = estimation::SolveToaNlls(mics, rho, sigmas, start_m, start_offset_m, nlls);
    out.refine_status = fix.status;
    if (fix.status != estimation::SolverStatus::kOk) {
      // Keep the starting fix, with the covariance and rms linearised there.
      estimation::NllsProblem problem;
      problem.model = estimation::RowModel::kToa;
      problem.receivers_m = mics;
      problem.values_m = rho;
      problem.sigmas_m = sigmas;
      fix = estimation::AssessFix(problem, start_m, start_offset_m, sender_height_m);
      fix.position_m = start_m;
      fix.offset_m = start_offset_m;
    }
    // The studentised residuals need the least-squares solution: no test at a kept start.
    if (!options.final_test || fix.status != estimation::SolverStatus::kOk) break;
    const auto [worst, w] = WorstStudentisedResidual(mics, rho, fix.position_m, fix.offset_m, sigma_m);
    if (worst < 0 || !(w > options.window_sigmas)) break;
    if (static_cast<int>(rows.size()) - 1 < 3 + options.min_votes) return out;  // nothing consistent is verified
    rows.erase(rows.begin() + worst);
    ++out.stamps_left_out;
    start_m = fix.position_m;
    start_offset_m = fix.offset_m;
  }
  for (int i : rows) {
    out.los_receivers.push_back(i);
    const int s = best.slot[static_cast<std::size_t>(i)];
    out.los_stamp_index[static_cast<std::size_t>(i)] = table.input_index[static_cast<std::size_t>(i * k + s)];
  }
  out.position_m = fix.position_m;
  out.offset_m = fix.offset_m;
  out.covariance_m2 = fix.covariance_m2.topLeftCorner<3, 3>();
  out.rms_m = fix.rms_m;
  out.triplet = best.triplet;
  out.votes = best.votes;
  out.found = true;
  return out;
}

}  // namespace mirage::methods::acoustic
