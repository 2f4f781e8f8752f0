// SPDX-License-Identifier: MIT
#include "mirage/methods/acoustic/multipath_fix.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <numbers>
#include <optional>
#include <tuple>
#include <utility>

#include "mirage/methods/acoustic/path_association.h"

namespace mirage::methods::acoustic {
namespace {

/// A searched cell: its centre, the best window's offset and its count of distinct stamps.
struct Cell {
  Vec3 centre_m = Vec3::Zero();
  double offset_m = 0.0;
  int score = 0;
};

/// One stamp paired with a predicted path at the linearisation point.
struct PairedRow {
  int receiver = 0;
  int stamp = 0;
  int path = 0;
  double innovation_m = 0.0;  ///< stamp - prediction (m)
  double s_m2 = 0.0;          ///< the innovation's variance (m^2)
  Eigen::RowVectorXd h;       ///< d prediction / d [p, b]
};

/// The likelihood of one emission's stamps at a candidate.
struct Explained {
  int stamps = 0;      ///< paired stamps within 3 innovation sigmas
  int receivers = 0;   ///< microphones with one
  double log_likelihood = 0.0;
  double sum_sq_m2 = 0.0;  ///< the squared innovations of those stamps (m^2)
  /// Better than other: the larger log-likelihood; without a clutter model (every candidate pairs
  /// as many stamps) the more stamps within 3 sigma, then the smaller sum of their squares.
  [[nodiscard]] bool BetterThan(const Explained& other, bool scored) const {
    if (scored) return log_likelihood > other.log_likelihood;
    if (stamps != other.stamps) return stamps > other.stamps;
    return sum_sq_m2 < other.sum_sq_m2;
  }
};

/// The window of width width_m over the sorted (value, stamp) pairs that holds the most distinct
/// stamps: that count and the window's centre. in_window: scratch, one counter per stamp.
std::pair<int, double> DensestWindow(const std::vector<std::pair<double, int>>& values, std::vector<int>& in_window,
                                     double width_m) {
  std::fill(in_window.begin(), in_window.end(), 0);
  int distinct = 0, best = 0;
  double centre_m = 0.0;
  std::size_t left = 0;
  for (std::size_t right = 0; right < values.size(); ++right) {
    if (in_window[static_cast<std::size_t>(values[right].second)]++ == 0) ++distinct;
    while (values[right].first - values[left].first > width_m) {
      if (--in_window[static_cast<std::size_t>(values[left].second)] == 0) --distinct;
      ++left;
    }
    if (distinct > best) {
      best = distinct;
      centre_m = 0.5 * (values[left].first + values[right].first);
    }
  }
  return {best, centre_m};
}

/// The search of one emission (the steps of the header's comment).
class MultipathSearch {
 public:
  MultipathSearch(std::span<const geometry::Reflector3> reflectors, std::span<const Vec3> mics_m,
                  const std::vector<std::vector<double>>& stamps_m, const MultipathSearchRegion& region,
                  const MultipathFixOptions& options)
      : reflectors_(reflectors),
        mics_m_(mics_m),
        stamps_m_(stamps_m),
        region_(region),
        options_(options),
        dim_(region.hi_m.z() > region.lo_m.z() ? 3 : 2),
        r2_m2_(options.range_sigma_m * options.range_sigma_m) {
    for (const auto& list : stamps_m_) stamps_ += list.size();
  }

  [[nodiscard]] int unknowns() const { return dim_ + 1; }
  [[nodiscard]] std::size_t stamps() const { return stamps_; }

  /// 1. The best cells after the coarse-to-fine search.
  std::vector<Cell> Search() {
    const Vec3 span_m = (region_.hi_m - region_.lo_m).cwiseMax(0.0);
    const auto cells_along = [&](double extent_m) {
      return std::max(1, static_cast<int>(std::ceil(extent_m / options_.cell_m)));
    };
    const int nx = cells_along(span_m.x()), ny = cells_along(span_m.y()), nz = dim_ == 2 ? 1 : cells_along(span_m.z());
    step_m_ = Vec3(span_m.x() / nx, span_m.y() / ny, dim_ == 2 ? 0.0 : span_m.z() / nz);
    std::vector<Cell> cells;
    for (int ix = 0; ix < nx; ++ix) {
      for (int iy = 0; iy < ny; ++iy) {
        const Vec2 xy = region_.lo_m.head<2>() + Vec2((ix + 0.5) * step_m_.x(), (iy + 0.5) * step_m_.y());
        if (region_.plan != nullptr && !region_.plan->walls().empty() && !region_.plan->Encloses(xy)) continue;
        for (int iz = 0; iz < nz; ++iz) {
          const double z_m = dim_ == 2 ? region_.lo_m.z() : region_.lo_m.z() + (iz + 0.5) * step_m_.z();
          cells.push_back(Score({xy.x(), xy.y(), z_m}));
        }
      }
    }
    std::vector<Cell> best = Best(std::move(cells));
    // Halve the best cells until a cell's half-diagonal is within 3 sigma: a coarse cell's wide
    // window also gathers chance coincidences, and the refinement converges only from within
    // about the echoes' spacing.
    while (!best.empty() && HalfDiagonal() > 3.0 * options_.range_sigma_m) {
      step_m_ *= 0.5;
      std::vector<Cell> children;
      for (const auto& parent : best) {
        for (int child = 0; child < (dim_ == 2 ? 4 : 8); ++child) {
          const Vec3 sign((child & 1) ? 0.5 : -0.5, (child & 2) ? 0.5 : -0.5, (child & 4) ? 0.5 : -0.5);
          children.push_back(Score(parent.centre_m + sign.cwiseProduct(step_m_)));
        }
      }
      best = Best(std::move(children));
    }
    return best;
  }

  /// 2. The iterated robust update from a cell; the estimate [p, b] and its covariance.
  std::optional<std::pair<Eigen::VectorXd, Eigen::MatrixXd>> Refine(const Cell& cell) const {
    const int n = unknowns();
    Eigen::VectorXd x0(n);
    x0.head(dim_) = cell.centre_m.head(dim_);
    x0(dim_) = cell.offset_m;
    // The cell as the prior: the sender anywhere in it, b anywhere in its window.
    Eigen::MatrixXd P0 = Eigen::MatrixXd::Zero(n, n);
    P0.diagonal().head(dim_).setConstant(HalfDiagonal() * HalfDiagonal() + r2_m2_);
    P0(dim_, dim_) = 0.25 * Window() * Window();
    Eigen::VectorXd x = x0;
    Eigen::MatrixXd P = P0;
    std::optional<estimation::IrlsResult> update;
    std::vector<std::tuple<int, int, int>> last_pairs;
    for (int iteration = 0; iteration < kMaxIterations; ++iteration) {
      const auto rows = Associate(x, P);
      std::vector<std::tuple<int, int, int>> pairs;
      for (const auto& row : rows) pairs.emplace_back(row.receiver, row.stamp, row.path);
      if (rows.size() < static_cast<std::size_t>(n + 1)) break;
      if (iteration > 0 && pairs == last_pairs) break;  // the association settled
      last_pairs = std::move(pairs);
      // Linearised at x, as innovations against the cell: y = z - h(x) + H (x - x0).
      const long m = static_cast<long>(rows.size());
      Eigen::MatrixXd H(m, n);
      Eigen::VectorXd y(m);
      for (long r = 0; r < m; ++r) {
        const auto& row = rows[static_cast<std::size_t>(r)];
        H.row(r) = row.h;
        y(r) = row.innovation_m + (row.h * (x - x0))(0, 0);
      }
      auto candidate = estimation::IrlsUpdate(P0, H, y, r2_m2_ * Eigen::MatrixXd::Identity(m, m), options_.irls);
      if (!candidate) break;
      update = std::move(candidate);
      x = x0 + update->dx;
      P = update->P;
    }
    if (!update) return std::nullopt;
    return std::make_pair(x, P);
  }

  /// 3. The stamps' log-likelihood at x under the association's model: per paired stamp
  /// ln(P_d N(nu; 0, s) / lambda), per predicted path without a stamp ln(1 - P_d) (the terms of
  /// path_association.h's gate). With P_d = 1 or lambda = 0 (no clutter model) only the stamps
  /// within 3 sigma and their squared innovations count (Explained::BetterThan).
  [[nodiscard]] Explained Likelihood(const Eigen::VectorXd& x, const Eigen::MatrixXd& P) const {
    Explained e;
    const double p_d = options_.detection_probability;
    const double lambda = options_.clutter_density_per_m;
    const bool scored = p_d < 1.0 && lambda > 0.0;
    const auto rows = Associate(x, P, &e.log_likelihood);
    std::vector<bool> heard(mics_m_.size(), false);
    for (const auto& row : rows) {
      if (std::abs(row.innovation_m) <= 3.0 * std::sqrt(row.s_m2)) {
        ++e.stamps;
        e.sum_sq_m2 += row.innovation_m * row.innovation_m;
        heard[static_cast<std::size_t>(row.receiver)] = true;
      }
      e.log_likelihood += scored ? std::log(p_d / (lambda * std::sqrt(2.0 * std::numbers::pi * row.s_m2))) -
                                       0.5 * row.innovation_m * row.innovation_m / row.s_m2
                                 : 1.0;
    }
    e.receivers = static_cast<int>(std::count(heard.begin(), heard.end(), true));
    return e;
  }

  [[nodiscard]] Vec3 SenderOf(const Eigen::VectorXd& x) const {
    return dim_ == 2 ? Vec3(x(0), x(1), region_.lo_m.z()) : Vec3(x.head<3>());
  }
  [[nodiscard]] int dim() const { return dim_; }

 private:
  static constexpr int kMaxIterations = 8;

  [[nodiscard]] double HalfDiagonal() const { return 0.5 * step_m_.norm(); }
  /// A sender anywhere in the cell moves every path length by at most the half-diagonal.
  [[nodiscard]] double Window() const { return 2.0 * (HalfDiagonal() + 3.0 * options_.range_sigma_m); }

  /// A cell's count: the paths to first order at its centre (the second order multiplies the
  /// cost by the surfaces' count, and the direct path with the first order explains most stamps).
  Cell Score(const Vec3& centre_m) {
    values_.clear();
    int stamp = 0;
    for (std::size_t i = 0; i < mics_m_.size(); ++i) {
      const auto paths = PredictPaths(reflectors_, centre_m, mics_m_[i], 0.0, std::min(options_.echo_order, 1));
      for (const double z_m : stamps_m_[i]) {
        for (const auto& path : paths) values_.emplace_back(z_m - path.predicted_m, stamp);
        ++stamp;
      }
    }
    std::sort(values_.begin(), values_.end());
    in_window_.resize(stamps_);
    const auto [score, offset_m] = DensestWindow(values_, in_window_, Window());
    return {centre_m, offset_m, score};
  }

  /// The best cells, one per neighbourhood: a cell next to a chosen one (within one step on every
  /// axis) whose offset falls in the chosen one's window is the same candidate.
  [[nodiscard]] std::vector<Cell> Best(std::vector<Cell> cells) const {
    std::stable_sort(cells.begin(), cells.end(), [](const Cell& a, const Cell& b) { return a.score > b.score; });
    std::vector<Cell> chosen;
    for (const auto& cell : cells) {
      if (static_cast<int>(chosen.size()) >= options_.refine_candidates) break;
      const bool near = std::any_of(chosen.begin(), chosen.end(), [&](const Cell& c) {
        const Vec3 d = (c.centre_m - cell.centre_m).cwiseAbs();
        return (d.array() <= 1.01 * step_m_.array()).all() && std::abs(c.offset_m - cell.offset_m) <= Window();
      });
      if (!near) chosen.push_back(cell);
    }
    return chosen;
  }

  /// Every microphone's stamps paired with its paths up to echo_order at x (covariance P), by the
  /// filters' association. missed_log_likelihood, if given, gains ln(1 - P_d) per path left
  /// without a stamp.
  std::vector<PairedRow> Associate(const Eigen::VectorXd& x, const Eigen::MatrixXd& P,
                                   double* missed_log_likelihood = nullptr) const {
    const Vec3 sender_m = SenderOf(x);
    std::vector<PairedRow> rows;
    const PathStateLayout layout{.position_columns = dim_, .offset_column = dim_};
    const bool scored = options_.detection_probability < 1.0 && options_.clutter_density_per_m > 0.0;
    for (std::size_t i = 0; i < mics_m_.size(); ++i) {
      int unpaired = 0;
      for (auto& a : AssociateMicrophone(reflectors_, sender_m, mics_m_[i], x(dim_), options_.echo_order, stamps_m_[i], P,
                                         layout, r2_m2_, options_.detection_probability,
                                         options_.clutter_density_per_m, &unpaired)) {
        rows.push_back({static_cast<int>(i), a.stamp, a.path_index,
                        stamps_m_[i][static_cast<std::size_t>(a.stamp)] - a.path.predicted_m, a.innovation_var_m2,
                        std::move(a.h)});
      }
      if (missed_log_likelihood != nullptr && scored) {
        *missed_log_likelihood += static_cast<double>(unpaired) * std::log(1.0 - options_.detection_probability);
      }
    }
    return rows;
  }

  std::span<const geometry::Reflector3> reflectors_;
  std::span<const Vec3> mics_m_;
  const std::vector<std::vector<double>>& stamps_m_;
  const MultipathSearchRegion& region_;
  const MultipathFixOptions& options_;
  int dim_;
  double r2_m2_;
  std::size_t stamps_ = 0;
  Vec3 step_m_ = Vec3::Zero();
  std::vector<std::pair<double, int>> values_;  // scratch of Score
  std::vector<int> in_window_;
};

}  // namespace

MultipathFix FixFromAllStamps(std::span<const geometry::Reflector3> reflectors, std::span<const Vec3> mics_m,
                              const std::vector<std::vector<double>>& stamps_m, const MultipathSearchRegion& region,
                              const MultipathFixOptions& options) {
  assert(stamps_m.size() == mics_m.size() && options.range_sigma_m > 0.0 && options.cell_m > 0.0 &&
         options.refine_candidates >= 1);
  MultipathFix out;
  MultipathSearch search(reflectors, mics_m, stamps_m, region, options);
  const int n = search.unknowns();
  if (search.stamps() < static_cast<std::size_t>(n + 2)) return out;
  std::optional<Explained> best;
  for (const auto& cell : search.Search()) {
    const auto refined = search.Refine(cell);
    if (!refined) continue;
    const auto& [x, P] = *refined;
    const Explained e = search.Likelihood(x, P);
    const bool scored = options.detection_probability < 1.0 && options.clutter_density_per_m > 0.0;
    if (best && !e.BetterThan(*best, scored)) continue;
    best = e;
    const int d = search.dim();
    out.position_m = search.SenderOf(x);
    out.offset_m = x(d);
    out.covariance.setZero();
    out.covariance.topLeftCorner(d, d) = P.topLeftCorner(d, d);
    out.covariance.block(0, 3, d, 1) = P.block(0, d, d, 1);
    out.covariance.block(3, 0, 1, d) = P.block(d, 0, 1, d);
    out.covariance(3, 3) = P(d, d);
    out.explained_stamps = e.stamps;
    out.explained_receivers = e.receivers;
  }
  out.found = best && best->stamps >= n + 2 && best->receivers >= (search.dim() == 2 ? 3 : 4);
  return out;
}

}  // namespace mirage::methods::acoustic
