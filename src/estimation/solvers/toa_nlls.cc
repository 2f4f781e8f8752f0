// SPDX-License-Identifier: MIT
#include "mirage/estimation/solvers/toa_nlls.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include <Eigen/Dense>

#include "mirage/estimation/meas/toa.h"

namespace mirage::estimation {
namespace {

// Eigenvalues of a symmetric matrix below this fraction of the largest count as zero: for the
// pseudo-inverse of Sigma (rank N - 1 over all pairs) and the singularity test of H^T W H.
constexpr double kRelativeEigenFloor = 1e-12;
// LM gives up raising lambda beyond this (the gradient is numerically zero: at a minimum).
constexpr double kMaxLambda = 1e12;

double Infinity() { return std::numeric_limits<double>::infinity(); }

// Symmetric pseudo-inverse and rank.
std::pair<Eigen::MatrixXd, int> PseudoInverse(const Eigen::MatrixXd& S) {
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(S);
  const Eigen::VectorXd& values = eig.eigenvalues();
  const double floor = kRelativeEigenFloor * std::max(values.cwiseAbs().maxCoeff(), 0.0);
  Eigen::VectorXd inverse = Eigen::VectorXd::Zero(values.size());
  int rank = 0;
  for (Eigen::Index k = 0; k < values.size(); ++k) {
    if (values(k) > floor) {
      inverse(k) = 1.0 / values(k);
      ++rank;
    }
  }
  return {eig.eigenvectors() * inverse.asDiagonal() * eig.eigenvectors().transpose(), rank};
}

// A normal matrix: p x p with p <= 4 unknowns, fixed storage (no heap).
using Normal = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 4, 4>;

// The inverse of a symmetric positive (semi)definite normal matrix, or nullopt when singular:
// LDLT of the column-normalised matrix with symmetric pivoting on the largest diagonal of the
// remaining Schur complement, so that the last pivot is the smallest and bounds the smallest
// eigenvalue from above up to a small factor for p <= 4; a pivot below 1e-12 is singular.
// (Eigen::LDLT pivots on the not yet updated diagonal, all ~1 after the normalisation: the two
// decide differently only at condition numbers of 1e12 and more, where this one says singular.)
// Written out for p <= 4: Eigen's solve against the identity goes through its blocked triangular
// solver, which cost 3/4 of a closed-form fix (bench/methods/acoustic_bench.cc).
template <int p>
std::optional<Eigen::Matrix<double, p, p>> InverseIfRegular(const Eigen::Matrix<double, p, p>& A) {
  if (!A.allFinite()) return std::nullopt;
  Eigen::Matrix<double, p, p> C;
  Eigen::Matrix<double, p, 1> scale;
  for (int k = 0; k < p; ++k) {
    if (!(A(k, k) > 0.0)) return std::nullopt;
    scale(k) = 1.0 / std::sqrt(A(k, k));
  }
  for (int r = 0; r < p; ++r) {
    for (int c = 0; c < p; ++c) C(r, c) = A(r, c) * scale(r) * scale(c);
  }
  // In place: C's strict lower triangle becomes L, its diagonal D; order[k] = original index.
  std::array<int, p> order{};
  for (int k = 0; k < p; ++k) order[static_cast<std::size_t>(k)] = k;
  for (int k = 0; k < p; ++k) {
    int pivot = k;
    for (int j = k + 1; j < p; ++j) {
      if (std::abs(C(j, j)) > std::abs(C(pivot, pivot))) pivot = j;
    }
    if (pivot != k) {
      C.row(k).swap(C.row(pivot));
      C.col(k).swap(C.col(pivot));
      std::swap(order[static_cast<std::size_t>(k)], order[static_cast<std::size_t>(pivot)]);
    }
    const double d = C(k, k);
    if (!(d > kRelativeEigenFloor)) return std::nullopt;
    for (int i = k + 1; i < p; ++i) C(i, k) /= d;
    for (int i = k + 1; i < p; ++i) {
      for (int j = k + 1; j <= i; ++j) {
        C(i, j) -= C(i, k) * C(j, k) * d;
        C(j, i) = C(i, j);
      }
    }
  }
  // L^-1 (unit lower triangular), then C^-1 = L^-T D^-1 L^-1 in the pivoted order.
  Eigen::Matrix<double, p, p> L_inv = Eigen::Matrix<double, p, p>::Identity();
  for (int i = 1; i < p; ++i) {
    for (int j = 0; j < i; ++j) {
      double sum = 0.0;
      for (int k = j; k < i; ++k) sum += C(i, k) * L_inv(k, j);
      L_inv(i, j) = -sum;
    }
  }
  Eigen::Matrix<double, p, p> inverse;
  for (int r = 0; r < p; ++r) {
    for (int c = 0; c <= r; ++c) {
      double sum = 0.0;
      for (int k = r; k < p; ++k) sum += L_inv(k, r) * L_inv(k, c) / C(k, k);
      const int orig_r = order[static_cast<std::size_t>(r)];
      const int orig_c = order[static_cast<std::size_t>(c)];
      inverse(orig_r, orig_c) = inverse(orig_c, orig_r) = sum * scale(orig_r) * scale(orig_c);
    }
  }
  return inverse;
}

std::optional<Normal> InverseIfRegular(const Normal& A) {
  const auto dynamic = [](const auto& inverse) { return inverse ? std::optional<Normal>(*inverse) : std::nullopt; };
  switch (A.rows()) {
    case 2: return dynamic(InverseIfRegular<2>(A));
    case 3: return dynamic(InverseIfRegular<3>(A));
    case 4: return dynamic(InverseIfRegular<4>(A));
    default: return std::nullopt;  // the states have 2-4 unknowns
  }
}

// The measurement side of a problem, fixed over the iterations.
struct RowSet {
  std::vector<std::pair<int, int>> pairs;  // TDOA only
  Eigen::VectorXd z;                       // measured row values (m)
  Eigen::MatrixXd sigma;                   // row covariance with the given (or unit) sigmas (m^2)
  Eigen::MatrixXd weight;                  // W
  Eigen::MatrixXd unit_weight;             // (row covariance with unit sigmas)^+, for DOP and sigma-hat
  int independent_rows = 0;                // rank of the row covariance
};

bool InputValid(const NllsProblem& problem) {
  const std::size_t n = problem.receivers_m.size();
  if (problem.values_m.size() != n) return false;
  if (!problem.sigmas_m.empty() && problem.sigmas_m.size() != n) return false;
  for (std::size_t i = 0; i < n; ++i) {
    if (!problem.receivers_m[i].allFinite() || !std::isfinite(problem.values_m[i])) return false;
    if (!problem.sigmas_m.empty() && !(problem.sigmas_m[i] > 0.0 && std::isfinite(problem.sigmas_m[i]))) return false;
  }
  if (problem.model == RowModel::kTdoa && problem.tdoa_reference != kAllPairs &&
      (problem.tdoa_reference < 0 || static_cast<std::size_t>(problem.tdoa_reference) >= n)) {
    return false;
  }
  return true;
}

RowSet BuildRows(const NllsProblem& problem) {
  RowSet rows;
  const int n = static_cast<int>(problem.receivers_m.size());
  const auto variance = [&](int i) {
    return problem.sigmas_m.empty() ? 1.0 : problem.sigmas_m[static_cast<std::size_t>(i)] * problem.sigmas_m[static_cast<std::size_t>(i)];
  };
  const auto value = [&](int i) { return problem.values_m[static_cast<std::size_t>(i)]; };
  if (problem.model != RowModel::kTdoa) {
    rows.z.resize(n);
    Eigen::VectorXd var(n);
    for (int i = 0; i < n; ++i) {
      rows.z(i) = value(i);
      var(i) = variance(i);
    }
    rows.sigma = var.asDiagonal();
    rows.weight = var.cwiseInverse().asDiagonal();
    rows.unit_weight = Eigen::MatrixXd::Identity(n, n);
    rows.independent_rows = n;
    return rows;
  }
  rows.pairs = TdoaPairs(n, problem.tdoa_reference);
  const auto m = static_cast<Eigen::Index>(rows.pairs.size());
  // D (m x n) with +1 at i and -1 at j; Sigma = D R D^T (Eq. 8.54-8.55).
  Eigen::MatrixXd D = Eigen::MatrixXd::Zero(m, n);
  Eigen::VectorXd var(n);
  for (int i = 0; i < n; ++i) var(i) = variance(i);
  rows.z.resize(m);
  for (Eigen::Index k = 0; k < m; ++k) {
    const auto [i, j] = rows.pairs[static_cast<std::size_t>(k)];
    D(k, i) = 1.0;
    D(k, j) = -1.0;
    rows.z(k) = value(i) - value(j);
  }
  rows.sigma = D * var.asDiagonal() * D.transpose();
  auto [unit_pinv, rank] = PseudoInverse(D * D.transpose());
  rows.unit_weight = std::move(unit_pinv);
  rows.independent_rows = rank;
  if (problem.tdoa_correlated_weighting) {
    rows.weight = problem.sigmas_m.empty() ? rows.unit_weight : PseudoInverse(rows.sigma).first;
  } else {
    rows.weight = rows.sigma.diagonal().cwiseInverse().asDiagonal();
  }
  return rows;
}

// Position and offset of a state vector (inverse of PackState).
std::pair<Vec3, double> Unpack(RowModel model, const Eigen::VectorXd& state, std::optional<double> known_height_m) {
  Vec3 position(state(0), state(1), known_height_m ? *known_height_m : state(2));
  const double offset = model == RowModel::kToa ? state(state.size() - 1) : 0.0;
  return {position, offset};
}

double Cost(const Eigen::VectorXd& residual, const Eigen::MatrixXd& weight) { return residual.dot(weight * residual); }

}  // namespace

std::vector<std::string> Validate(const NllsOptions& options) {
  std::vector<std::string> problems;
  if (options.max_iterations < 1) problems.emplace_back("max_iterations must be >= 1");
  if (!(options.tolerance_m > 0.0 && std::isfinite(options.tolerance_m))) {
    problems.emplace_back("tolerance_m must be > 0 and finite");
  }
  if (!(options.lm_initial_lambda > 0.0 && std::isfinite(options.lm_initial_lambda))) {
    problems.emplace_back("lm_initial_lambda must be > 0 and finite");
  }
  if (options.known_height_m && !std::isfinite(*options.known_height_m)) {
    problems.emplace_back("known_height_m must be finite");
  }
  return problems;
}

int StateDimension(RowModel model, bool known_height) {
  return (known_height ? 2 : 3) + (model == RowModel::kToa ? 1 : 0);
}

Eigen::VectorXd PackState(RowModel model, const Vec3& position_m, double offset_m,
                          std::optional<double> known_height_m) {
  Eigen::VectorXd state(StateDimension(model, known_height_m.has_value()));
  state(0) = position_m.x();
  state(1) = position_m.y();
  if (!known_height_m) state(2) = position_m.z();
  if (model == RowModel::kToa) state(state.size() - 1) = offset_m;
  return state;
}

std::vector<std::pair<int, int>> TdoaPairs(int receiver_count, int reference) {
  std::vector<std::pair<int, int>> pairs;
  if (reference == kAllPairs) {
    for (int i = 0; i < receiver_count; ++i) {
      for (int j = i + 1; j < receiver_count; ++j) pairs.emplace_back(i, j);
    }
  } else if (reference >= 0 && reference < receiver_count) {
    for (int i = 0; i < receiver_count; ++i) {
      if (i != reference) pairs.emplace_back(i, reference);
    }
  }
  return pairs;
}

std::optional<Linearization> Linearize(const NllsProblem& problem, const Eigen::VectorXd& state,
                                       std::optional<double> known_height_m) {
  const auto [position, offset] = Unpack(problem.model, state, known_height_m);
  const int n = static_cast<int>(problem.receivers_m.size());
  const int p = static_cast<int>(state.size());
  const int position_columns = known_height_m ? 2 : 3;
  // Per receiver: |S - M_i| (+ b) and u_i (Eq. 8.13).
  std::vector<ToaPrediction> toa(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    const auto prediction = PredictToa(position, problem.receivers_m[static_cast<std::size_t>(i)],
                                       problem.model == RowModel::kToa ? offset : 0.0);
    if (!prediction) return std::nullopt;
    toa[static_cast<std::size_t>(i)] = *prediction;
  }
  Linearization out;
  if (problem.model != RowModel::kTdoa) {
    out.predicted_m.resize(n);
    out.J_pred_state = Eigen::MatrixXd::Zero(n, p);
    for (int i = 0; i < n; ++i) {
      const ToaPrediction& t = toa[static_cast<std::size_t>(i)];
      out.predicted_m(i) = t.predicted_m;
      out.J_pred_state.row(i).head(position_columns) = t.d_sender.head(position_columns).transpose();
      if (problem.model == RowModel::kToa) out.J_pred_state(i, p - 1) = 1.0;
    }
    return out;
  }
  const auto pairs = TdoaPairs(n, problem.tdoa_reference);
  const auto m = static_cast<Eigen::Index>(pairs.size());
  out.predicted_m.resize(m);
  out.J_pred_state = Eigen::MatrixXd::Zero(m, p);
  for (Eigen::Index k = 0; k < m; ++k) {
    const auto [i, j] = pairs[static_cast<std::size_t>(k)];
    const ToaPrediction& ti = toa[static_cast<std::size_t>(i)];
    const ToaPrediction& tj = toa[static_cast<std::size_t>(j)];
    out.predicted_m(k) = ti.range_m - tj.range_m;
    out.J_pred_state.row(k).head(position_columns) = (ti.d_sender - tj.d_sender).head(position_columns).transpose();
  }
  return out;
}

namespace {

// Writes the p x p state covariance into [x, y, z, b] (state entry a is slot used[a]).
template <class Matrix>
void Scatter(const Matrix& covariance, bool known_height, SolverFix& fix) {
  std::array<int, 4> used{0, 1, 2, 3};
  if (known_height) used = {0, 1, 3, 3};
  fix.covariance_m2.setZero();
  for (Eigen::Index a = 0; a < covariance.rows(); ++a) {
    for (Eigen::Index b = 0; b < covariance.cols(); ++b) {
      fix.covariance_m2(used[static_cast<std::size_t>(a)], used[static_cast<std::size_t>(b)]) = covariance(a, b);
    }
  }
}

// The DOP, covariance and status from the normal matrices: unit (H^T R1^+ H) and weighted.
// `middle` is H^T W Sigma W H for the sandwich, or nullopt when W = Sigma^-1 (then the
// covariance is the inverse itself). sigma2_hat scales it when no sigmas were given.
// Matrix: Normal, or a fixed p x p matrix (the independent rows' path).
template <class Matrix>
void Finish(const Matrix& unit_normal, const Matrix& normal, const std::optional<Matrix>& middle, double sigma2_hat,
            bool known_height, SolverFix& fix) {
  const auto unit_inverse = InverseIfRegular(unit_normal);
  // Without given sigmas the two normal matrices are one (the closed-form solvers' case).
  const auto inverse = normal == unit_normal ? unit_inverse : InverseIfRegular(normal);
  if (!unit_inverse || !inverse) {
    fix.status = SolverStatus::kSingularNormalMatrix;
    fix.dop = Infinity();
    fix.covariance_m2.setZero();
    return;
  }
  const int position_columns = known_height ? 2 : 3;
  fix.dop = std::sqrt(unit_inverse->topLeftCorner(position_columns, position_columns).trace());  // Eq. 8.8-8.12
  const Matrix covariance = middle ? Matrix(*inverse * *middle * *inverse) : *inverse;
  Scatter(covariance * sigma2_hat, known_height, fix);
  fix.status = SolverStatus::kOk;
}

// TOA and range rows: independent, W = diag(1 / sigma_i^2). Accumulated in fixed p x p storage
// (no row-covariance matrix, no heap): the path of the closed-form and linear solvers, where
// Eigen's dynamic-size products cost more than the solve itself (bench/methods/acoustic_bench.cc).
template <int p>
void AssessIndependent(const NllsProblem& problem, const Vec3& position, double offset, bool known_height,
                       SolverFix& fix) {
  using Matrix = Eigen::Matrix<double, p, p>;
  const bool with_offset = problem.model == RowModel::kToa;
  const int position_columns = known_height ? 2 : 3;
  Matrix unit_normal = Matrix::Zero();
  Matrix normal = Matrix::Zero();
  Eigen::Matrix<double, p, 1> h = Eigen::Matrix<double, p, 1>::Zero();
  double sum_r2 = 0.0;
  const std::size_t n = problem.receivers_m.size();
  for (std::size_t i = 0; i < n; ++i) {
    const auto prediction = PredictToa(position, problem.receivers_m[i], with_offset ? offset : 0.0);
    if (!prediction) {
      fix.status = SolverStatus::kDegenerateGeometry;
      fix.dop = Infinity();
      return;
    }
    h.head(position_columns) = prediction->d_sender.head(position_columns);
    if (with_offset) h(p - 1) = 1.0;
    const double r = problem.values_m[i] - prediction->predicted_m;
    sum_r2 += r * r;
    unit_normal.noalias() += h * h.transpose();
    if (!problem.sigmas_m.empty()) {
      const double w = 1.0 / (problem.sigmas_m[i] * problem.sigmas_m[i]);
      normal.noalias() += w * h * h.transpose();
    }
  }
  if (problem.sigmas_m.empty()) normal = unit_normal;
  fix.rms_m = std::sqrt(sum_r2 / static_cast<double>(n));
  const int dof = static_cast<int>(n) - p;
  const double sigma2_hat = !problem.sigmas_m.empty() ? 1.0 : (dof > 0 ? sum_r2 / dof : 0.0);
  Finish<Matrix>(unit_normal, normal, std::nullopt, sigma2_hat, known_height, fix);
}

void AssessIndependent(const NllsProblem& problem, const Vec3& position, double offset,
                       std::optional<double> known_height_m, SolverFix& fix) {
  const bool known_height = known_height_m.has_value();
  switch (StateDimension(problem.model, known_height)) {
    case 2: AssessIndependent<2>(problem, position, offset, known_height, fix); break;
    case 3: AssessIndependent<3>(problem, position, offset, known_height, fix); break;
    default: AssessIndependent<4>(problem, position, offset, known_height, fix); break;
  }
}

// Fills rms, covariance, dop and status of `fix` at `state`, any model.
void Assess(const NllsProblem& problem, const RowSet& rows, const Eigen::VectorXd& state,
            std::optional<double> known_height_m, SolverFix& fix) {
  const auto [position, offset] = Unpack(problem.model, state, known_height_m);
  fix.position_m = position;
  fix.offset_m = offset;
  fix.offset_estimated = problem.model == RowModel::kToa;
  fix.covariance_m2.setZero();
  if (problem.model != RowModel::kTdoa) {
    AssessIndependent(problem, position, offset, known_height_m, fix);
    return;
  }
  const auto lin = Linearize(problem, state, known_height_m);
  if (!lin) {
    fix.status = SolverStatus::kDegenerateGeometry;
    fix.dop = Infinity();
    return;
  }
  const Eigen::VectorXd residual = rows.z - lin->predicted_m;
  fix.rms_m = std::sqrt(residual.squaredNorm() / static_cast<double>(residual.size()));
  const Eigen::MatrixXd& H = lin->J_pred_state;
  const Eigen::MatrixXd WH = rows.weight * H;
  double sigma2_hat = 1.0;
  if (problem.sigmas_m.empty()) {
    // Unknown equal sigma: sigma-hat^2 = r^T Sigma1^+ r / (rank - p), zero without redundancy.
    const int dof = rows.independent_rows - static_cast<int>(state.size());
    sigma2_hat = dof > 0 ? Cost(residual, rows.unit_weight) / dof : 0.0;
  }
  Finish<Normal>(Normal(H.transpose() * rows.unit_weight * H), Normal(H.transpose() * WH),
         Normal(WH.transpose() * rows.sigma * WH), sigma2_hat, known_height_m.has_value(), fix);
}

}  // namespace

SolverFix AssessFix(const NllsProblem& problem, const Vec3& position_m, double offset_m,
                    std::optional<double> known_height_m) {
  SolverFix fix;
  fix.position_m = position_m;
  fix.offset_m = offset_m;
  if (!InputValid(problem) || !position_m.allFinite() || !std::isfinite(offset_m)) {
    fix.status = SolverStatus::kInvalidInput;
    return fix;
  }
  if (problem.model != RowModel::kTdoa) {
    // Independent rows need no state vector nor row set (no heap): the closed-form solvers' path.
    fix.position_m.z() = known_height_m.value_or(position_m.z());
    if (problem.model != RowModel::kToa) fix.offset_m = 0.0;
    fix.offset_estimated = problem.model == RowModel::kToa;
    AssessIndependent(problem, fix.position_m, fix.offset_m, known_height_m, fix);
  } else {
    Assess(problem, BuildRows(problem), PackState(problem.model, position_m, offset_m, known_height_m), known_height_m,
           fix);
  }
  fix.converged = fix.status == SolverStatus::kOk;
  return fix;
}

SolverFix SolveNlls(const NllsProblem& problem, const Vec3& start_m, double start_offset_m,
                    const NllsOptions& options) {
  SolverFix fix;
  fix.position_m = start_m;
  fix.offset_m = start_offset_m;
  if (!InputValid(problem) || !Validate(options).empty() || !start_m.allFinite() || !std::isfinite(start_offset_m)) {
    fix.status = SolverStatus::kInvalidInput;
    return fix;
  }
  const RowSet rows = BuildRows(problem);
  const int p = StateDimension(problem.model, options.known_height_m.has_value());
  if (rows.independent_rows < p) {
    fix.status = SolverStatus::kTooFewRows;
    return fix;
  }
  Eigen::VectorXd state = PackState(problem.model, start_m, start_offset_m, options.known_height_m);
  double lambda = options.lm_initial_lambda;
  bool converged = false;
  int iteration = 0;
  while (iteration < options.max_iterations && !converged) {
    ++iteration;
    const auto lin = Linearize(problem, state, options.known_height_m);
    if (!lin) {
      Assess(problem, rows, state, options.known_height_m, fix);
      fix.iterations = iteration;
      return fix;  // kDegenerateGeometry: the iterate sits on a receiver
    }
    const Eigen::VectorXd residual = rows.z - lin->predicted_m;
    const Eigen::MatrixXd& H = lin->J_pred_state;
    const Eigen::MatrixXd A = H.transpose() * rows.weight * H;
    const Eigen::VectorXd g = H.transpose() * rows.weight * residual;
    if (options.method == NllsMethod::kGaussNewton) {
      const auto inverse = InverseIfRegular(Normal(A));
      if (!inverse) {
        Assess(problem, rows, state, options.known_height_m, fix);
        fix.status = SolverStatus::kSingularNormalMatrix;
        fix.iterations = iteration;
        return fix;
      }
      const Eigen::VectorXd step = Eigen::MatrixXd(*inverse) * g;
      state += step;
      converged = step.norm() < options.tolerance_m;
    } else {
      const double cost = Cost(residual, rows.weight);
      Eigen::VectorXd damping = A.diagonal();
      damping.array() += 1e-9 * A.trace() / p;
      while (true) {
        Eigen::MatrixXd damped = A;
        damped.diagonal() += lambda * damping;
        const Eigen::VectorXd step = damped.ldlt().solve(g);
        if (step.norm() < options.tolerance_m || lambda > kMaxLambda) {
          converged = true;  // no further descent is possible at this tolerance
          break;
        }
        const Eigen::VectorXd candidate = state + step;
        const auto next = Linearize(problem, candidate, options.known_height_m);
        if (next && Cost(rows.z - next->predicted_m, rows.weight) < cost) {
          state = candidate;
          lambda = std::max(lambda / 10.0, 1e-12);
          break;
        }
        lambda *= 10.0;
      }
    }
    if (!state.allFinite()) break;
  }
  fix.iterations = iteration;
  if (!state.allFinite()) {
    fix.status = SolverStatus::kNotConverged;
    fix.converged = false;
    return fix;
  }
  Assess(problem, rows, state, options.known_height_m, fix);
  fix.converged = converged;
  if (fix.status == SolverStatus::kOk && !converged) fix.status = SolverStatus::kNotConverged;
  return fix;
}

SolverFix SolveToaNlls(std::span<const Vec3> receivers_m, std::span<const double> pseudo_ranges_m,
                       std::span<const double> sigmas_m, const Vec3& start_m, double start_offset_m,
                       const NllsOptions& options) {
  NllsProblem problem;
  problem.model = RowModel::kToa;
  problem.receivers_m = receivers_m;
  problem.values_m = pseudo_ranges_m;
  problem.sigmas_m = sigmas_m;
  return SolveNlls(problem, start_m, start_offset_m, options);
}

SolverFix SolveRangeNlls(std::span<const Vec3> receivers_m, std::span<const double> ranges_m,
                         std::span<const double> sigmas_m, const Vec3& start_m, const NllsOptions& options) {
  NllsProblem problem;
  problem.model = RowModel::kRange;
  problem.receivers_m = receivers_m;
  problem.values_m = ranges_m;
  problem.sigmas_m = sigmas_m;
  return SolveNlls(problem, start_m, 0.0, options);
}

SolverFix SolveTdoaNlls(std::span<const Vec3> receivers_m, std::span<const double> pseudo_ranges_m,
                        std::span<const double> sigmas_m, int reference, const Vec3& start_m,
                        const NllsOptions& options) {
  NllsProblem problem;
  problem.model = RowModel::kTdoa;
  problem.receivers_m = receivers_m;
  problem.values_m = pseudo_ranges_m;
  problem.sigmas_m = sigmas_m;
  problem.tdoa_reference = reference;
  return SolveNlls(problem, start_m, 0.0, options);
}

}  // namespace mirage::estimation
