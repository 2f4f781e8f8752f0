// SPDX-License-Identifier: MIT
// Multipath SLAM (Leitinger, Meissner, Lafer, Witrisal; Lafer 2014 ch. 4): virtual anchors in
// the EKF state next to the agent, corrected by every range associated to them, and new VAs
// discovered from the ranges no VA explains.
//
// Per step: constant-velocity prediction (VAs static, Eq. 13-14); per-anchor cut-off assignment
// of the measured ranges to the expected ranges of the map's VAs (Eq. 7-11), where prior VAs
// from a known floor plan use ray-traced visibility and discovered VAs, which have none, are
// candidates everywhere; online range variance per VA (Eq. 17-18) and the VA filter; one EKF
// update with agent and VA columns (Eq. 16, current rows only); discovery with the rest.
//
// Choices where the paper is silent or inconsistent (digest slam_multipath_leitinger.md Sec. 8):
// - Standard EKF-SLAM: the full joint covariance is kept and only the current ranges update it.
//   The paper's stacking of all past ranges (Eq. 15-16) re-uses information at every step
//   (digest Sec. 2.7.5) and is not offered.
// - A new VA enters with the thesis's augmentation (Lafer Eq. 4.7-4.9): G_x = [I_2 0] (the
//   digest's simplification of Eq. 4.20-4.22, the ranges treated as functions of the current
//   agent position), so the cross-covariance is the agent-position rows of P, and
//   P_new = P_pp + P_rls, the RLS covariance standing for G_z R G_z^T. The paper's zero
//   cross-covariance would make the map overconfident.
// - Prior VAs enter the state when first associated, with their prior covariance and no
//   correlation: exactly what carrying them from the start would give, at a fraction of the cost
//   (830 VAs per anchor up to order 2 in the seminar room, of which a few dozen are ever seen).
// - VA filter (sigma_d > 6.23 cm excludes a VA from the association) only on a VA's own
//   estimate: a VA on the default sigma (0.07 m > 6.23 cm) is exempt until its window is full,
//   otherwise no new VA could ever be associated (digest Sec. 8 item 6). The physical anchors
//   are never filtered: one bad window behind an obstacle would lose the LOS for good.
// - mirage additions, each an option documented below and in docs/methods/slam.md: the amplitude
//   gate (stricter for a blocked anchor's discovered VAs), the VA filter that keeps associating,
//   the batch check before promotion, the shadow cone (off by default: blocked-LOS stand-ins of
//   discovered VAs weakened), the LOS re-acquisition (a missed
//   LOS searched wider, amplitude-checked), track-loss recovery (methods/slam/track_recovery)
//   and discovery only from a well-localised agent (DiscoveryOptions::max_agent_sigma_m).
#pragma once

#include <optional>
#include <span>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "mirage/core/records.h"
#include "mirage/core/options_descriptor.h"
#include "mirage/estimation/block_update.h"
#include "mirage/estimation/ekf_update.h"
#include "mirage/estimation/gates/rician_gate.h"
#include "mirage/estimation/innovation_scale.h"
#include "mirage/estimation/measurement_row.h"
#include "mirage/estimation/motion/constant_velocity.h"
#include "mirage/estimation/motion/random_walk.h"
#include "mirage/estimation/state.h"
#include "mirage/geometry/floor_plan.h"
#include "mirage/geometry/virtual_anchor.h"
#include "mirage/estimation/range_variance_estimator.h"
#include "mirage/methods/slam/track_recovery.h"
#include "mirage/methods/slam/va_discovery.h"

namespace mirage::methods::slam {

/// Parameters of the SLAM tracker.
struct SlamOptions {
  /// Cut-off distance d_c of the data association (m), > 0. 0.15 m (Lafer Tab. 3.1). Derived
  /// (methods/tracker_options.h): 3 range sigmas plus one step of motion.
  double cutoff_m = 0.15;
  /// Range standard deviation when variance estimation is off (m), > 0. 0.07 m; derived: the
  /// scenario's range noise.
  double range_sigma_m = 0.07;
  /// Standard deviation of the initial position (m), > 0. 0.1 m (Lafer Tab. 3.1).
  double initial_position_sigma_m = 0.1;
  /// Standard deviation of the initial velocity (m/s), > 0; the filter starts at rest. 0.5 m/s;
  /// derived: the walker's speed.
  double initial_velocity_sigma_mps = 0.5;
  /// Highest order of the VAs known at the start from the known floor plan, in [0, 6]: 0 = only
  /// the physical anchors (the paper's SLAM), 2 or 3 = the paper's known-VA baseline.
  int prior_max_order = 0;
  /// Prior standard deviation of each known VA's position (m), > 0 [GAP: digest Sec. 3.3
  /// suggests 5-10 cm]. The physical anchors are exact and not in the state.
  double prior_va_sigma_m = 0.05;
  /// Prior VAs (and the anchors' LOS) are associated only where the known floor plan makes them
  /// visible (the baseline's ray-traced visibility regions). Off: the floor plan is not used.
  bool prior_visibility = true;
  /// Two-stage association as in MINT (mirage): the LOS ranges first, then all VAs at that
  /// estimate.
  bool reassociate = true;
  /// Innovation gate inside the assignment (mirage; 0 = off), chi^2 with 1 degree of freedom;
  /// the innovation variance includes the VA's covariance.
  double innovation_gate_chi2 = 9.0;
  /// Innovation gate for the VAs without a visibility model (mirage; 0 = off, >= 0), chi^2 with
  /// 1 degree of freedom: a discovered VA, or a prior one without a floor-plan visibility region
  /// (prior_visibility off or no walls), is associated only within the tighter of this and
  /// innovation_gate_chi2 (this alone when innovation_gate_chi2 is 0); the anchors' LOS and prior
  /// VAs with a visibility region keep innovation_gate_chi2. Why: such a VA is a candidate at
  /// every step, also where its path is not extracted (weak, or merged with a neighbouring path)
  /// or blocked, and then a diffuse-multipath or clutter range inside the 3-sigma gate takes its
  /// place. In the seminar room (trajectory 2, run 0 of seeds 1-40, ranges labelled with the
  /// true paths by temporary instrumentation) 8 % of the discovered VAs' associations were such
  /// ranges of a visible but not extracted path, 5-8 cm off the path (innovations 4.9-7.6 cm,
  /// quartiles) against 0.9-3.1 cm for the right ones; dropping only these (an oracle) took p90
  /// from 3.8 to 3.3 cm, dropping every wrong association to 2.75 (the known-VA run: 2.9). 4
  /// (2 sigma: keeps 95 % of a consistent VA's ranges) halves them and loses 3 % of the right
  /// ones (docs/methods/slam.md).
  double no_visibility_model_gate_chi2 = 4.0;
  /// The VA filter (Leitinger Sec. III-C): a VA whose estimated range std exceeds
  /// va_filter_sigma_m takes no part in the association.
  bool va_filter = true;
  /// sigma_d,max (m), > 0: 6.23 cm, the CRLB at SINR 0 dB (Leitinger Sec. IV).
  double va_filter_sigma_m = 0.0623;
  /// mirage: a filtered VA still takes part in the association, so its range variance keeps
  /// being estimated from the ranges it claims (and they go to no other VA and not to the
  /// discovery), but those ranges do not update the state. A VA whose ranges become reliable
  /// again (the agent left the obstacle's shadow) comes back; with false (the paper) a filtered
  /// VA never gets another range and stays out for good.
  bool va_filter_keeps_associating = true;
  /// mirage: apply the VA filter to the physical anchors' LOS too, i.e. detect a blocked LOS
  /// by its range variance instead of trusting it. Only with va_filter_keeps_associating (else a
  /// blocked LOS would be lost for good).
  bool va_filter_anchors = true;
  /// Amplitude gate (mirage; 0 = off): a range is not associated to a VA if its amplitude is
  /// this improbable, P(|alpha| <= measured), under the Rician law fitted to the VA's amplitude
  /// window (the variance estimator's, Lafer Eq. 3.27) when the VA was last estimated. A blocked path's range is
  /// then a weak diffuse-multipath peak, which passes any range gate but not this one.
  double amplitude_gate_probability = 1e-3;
  /// Start-up amplitude law (mirage; 0 = off), its Rician K-factor, >= 0. Until a VA's amplitude
  /// window first fills (0.9 m of associations, RangeVarianceOptions) the amplitude gates
  /// (amplitude_gate_probability, blocked_amplitude_probability) have no law. With this, a VA
  /// with at least one positive amplitude associated so far is tested against a provisional law:
  /// specular amplitude the mean of amplitude x range over those associations, divided by the
  /// expected range (the 1/d of the fitted law), scatter power 1/K of its square. Like the fitted
  /// law it holds within two window lengths (2 x window_max_m) of where its first amplitude was
  /// taken, so a VA it shuts out is let in again farther on; a track restart clears it.
  /// Why: a run starts with the velocity unknown, so the first predictions lag the walker by
  /// several cm, and a later, weaker peak can be nearer to them than the LOS. Seminar room, seed
  /// 14, trajectory 1, run 12, step 2: A1's LOS at 5.506 m (amplitude 0.18) and a diffuse peak at
  /// 5.643 m (0.04), 2 cm from the lagging prediction; the peak was taken, the track held on to
  /// the peaks behind the LOS and stayed near the start while the walker left (diverged, no
  /// recovery: the map had no VAs yet). K = 10: at amplitude_gate_probability 1e-3 a range whose
  /// amplitude is below 0.35 of the expected one is rejected (0.74 at blocked_amplitude_probability
  /// 0.1). Stricter than the fitted law for a fading reflection: of a Rayleigh path's (K = 0)
  /// amplitudes 9 % fail at 1e-3, 35 % at 0.1; of a K = 10 path's 0.1 % and 12 %. The
  /// LOS re-acquisition (los_reacquire_m) still waits for a fitted law: on range-level input
  /// (seed 3) the start-up law let it take a reflection 36 cm behind a twice-missed LOS.
  double startup_amplitude_k_factor = 10.0;
  /// Amplitude gate in a blocked anchor's shadow (mirage; 0 = off), in [0, 0.5]. While an
  /// anchor's LOS found no range at this step (stage 1: missing, gated out or filtered), a range
  /// is associated to one of its VAs without a visibility model (a discovered one, or a prior
  /// one when prior_visibility is off) only if its amplitude has probability
  /// P(|alpha| <= measured) >= this under the VA's Rician law, instead of
  /// amplitude_gate_probability. Why: the obstacle that blocks the LOS often blocks some of
  /// the anchor's reflections too, and their diffuse stand-ins are weaker than the paths: in the
  /// seminar room (seed 1, discovered VAs while their anchor's LOS was blocked) the median of
  /// that probability was 0.15 for ranges of paths not visible and 0.48 for the paths' own; 0.1
  /// rejects 37 % of the former and 7 % of the latter. Unlike the shadow cone it needs no
  /// obstacle geometry. Needs reassociate and a fitted law within reach (GateLaw: a VA without
  /// one, or whose law was fitted more than two window lengths away, is not tested).
  double blocked_amplitude_probability = 0.1;
  /// Shadow cone (mirage; 0 = off), half-width in degrees. A VA without a visibility model (a
  /// discovered one, or a prior one when prior_visibility is off) whose path reaches the agent
  /// from within this angle of an anchor whose LOS found no range at this step (stage 1 of the
  /// two-stage association: missing, gated out by the amplitude gate, or filtered) is taken to
  /// be in the same obstacle's shadow: its range is most likely the diffuse-multipath stand-in
  /// of the blocked path, a few to 20 cm late and as strong as a weak reflection, so no gate can
  /// tell. Such a range is still associated (it is no new VA), but its variance is inflated by
  /// shadow_sigma_m^2 and its amplitude enters neither the VA's variance window nor its
  /// amplitude-gate law. 30 deg covers a 0.3 m pillar 0.5 m from the agent. Off by default:
  /// since the sweep (DiscoveryOptions::sweep) fills the map, most ranges in the cone are the
  /// VAs' own (the same pillar 2.7 m away hides 6 deg, not 30); off, the seminar room's p90 is
  /// better on 17 of 18 seed-trajectory pairs and no run diverges, against two
  /// (docs/methods/slam.md). Without the sweep the cone is still needed. Needs reassociate.
  double shadow_cone_deg = 0.0;
  /// Standard deviation added to a shadowed range (m), > 0: the stand-in's typical lag. 5 cm.
  double shadow_sigma_m = 0.05;
  /// LOS re-acquisition window (mirage; m, >= 0, no effect unless above cutoff_m). When an
  /// anchor's LOS found no range at the last step (stage 1: blocked, missed, gated or filtered),
  /// its LOS is searched this far from the predicted range instead of cutoff_m, and a range
  /// there is taken only if its amplitude passes the amplitude gate under the LOS's own law
  /// scaled to that range (so only with the amplitude gate on and a fitted law). Why: in an
  /// obstacle's shadow the track drifts along the other anchor's range circle, 20-60 cm in the
  /// seminar room; once it is more than cutoff_m off, the returning LOS - the strongest path,
  /// with an exactly known anchor - falls outside the window for good and the track stays
  /// off until the recovery restarts it, 50+ steps later. 0.4 m: above the drift of most
  /// shadowed runs, and measured 0.3-0.6 m all help; at 1 m other strong paths were taken for
  /// the LOS (docs/methods/slam.md).
  double los_reacquire_m = 0.4;
  /// Innovation-scaled range variance (mirage; 0 = off, >= 0, in updates): each VA's range
  /// variance in the update is multiplied by the mean normalised innovation squared of its last
  /// nis_window_updates updates when that mean exceeds 1 and at least 5 were recorded
  /// (estimation/innovation_scale; NIS = nu^2 / (H P H^T + R) with R this update's variance
  /// before scaling; the gates keep the unscaled variance; a track restart clears the records).
  /// Why: the variance estimator's range std follows the SINR, but some paths' ranges are off
  /// by more: in the seminar room a path 9 cm from a second-order one is often extracted as one
  /// merged peak between the two, and a VA fitted between two wall offsets (a window and its
  /// pier, 2.8 cm apart) gets ranges of either. Such a VA's own innovations show it, and its
  /// updates are weighted down by that excess. It applies to every map entry, known or
  /// discovered; with reassociate the anchors' LOS is in effect not scaled (its stage-2
  /// innovation is what its own stage-1 update left). Seeds 1-9, mean p90: anchors only 3.49 /
  /// 3.43 -> 3.45 / 3.37 cm, the known-VA run 2.86 / 2.84 -> 2.70 / 2.69 cm; windows of 10 and
  /// 40 gave about the same (docs/methods/slam.md).
  int nis_window_updates = 20;
  /// Random walk of the discovered VAs (mirage; m / sqrt(s), >= 0, 0 = off): each discovered
  /// VA in the state gets q^2 dt I added to its covariance at every prediction (the anchors and
  /// the floor plan's VAs never). Why: the discovered map is overconfident - in the seminar room
  /// the matched VAs' NEES was 24-34 (2 expected), their std about a third of their error - as a
  /// VA is a fit of ranges whose reflection point moves along the wall and whose paths merge
  /// with neighbours, which a fixed point with white range noise does not describe. 6.3 mm /
  /// sqrt(s) (2 mm per 0.1 s step) brings the NEES to a median of 2.5-3.2 and the tracks
  /// change: trajectory 1 improves on 8 of 9 seeds, trajectory 2 gets worse at its corner next
  /// to A2; off by default for that reason (docs/methods/slam.md).
  double discovered_va_walk_m_per_sqrt_s = 0.0;
  /// Covariance update of the EKF (mirage): the standard form P - K H P halves the O(n^2 m)
  /// cost that dominates a step with tens of VAs in the state (bench/methods/slam_step_bench.cc
  /// measures both); the Joseph form as in MINT is the alternative.
  bool joseph_update = false;
  /// Motion model of the agent.
  estimation::ConstantVelocityOptions motion;
  /// A walker's speed limit (mirage; 0 = off, >= 0), m/s: after each step's update a faster
  /// velocity estimate is scaled back onto this speed (estimation/motion/speed_limit.h). 1.5 m/s,
  /// a brisk walk, as the recovery's chain limit (the scenarios walk at 0.5). Why: in the seminar
  /// room (seed 30, trajectory 2, run 19) the track-loss recovery restarted a track 1 m off at
  /// step 164, in the pillar's shadow; the track then took clutter at a speed growing to 3.5 m/s,
  /// was 3 m off within 7 steps, beyond the recovery's max_jump_m, and 19.6 m off at the end.
  /// With the limit it stays within 2.2 m and the recovery restarts it right at step 171.
  /// Seeds 1-30, both configurations: no other run changes, bit for bit (a good track never
  /// comes near 1.5 m/s). Derived: 3 times the walker's speed (1.5 m/s at 0.5 m/s).
  double max_speed_mps = 1.5;
  /// Online variance estimation per VA (Lafer Sec. 3.6 / Leitinger Sec. III-C).
  estimation::RangeVarianceOptions variance;
  /// Discovery of new VAs.
  DiscoveryOptions discovery;
  /// Track-loss detection and restart (mirage).
  TrackRecoveryOptions recovery;
};

/// The options' descriptor (keys, units, ranges, docs; core/options_descriptor.h). The number of
/// VAs that prior_max_order gives depends on the floor plan and is checked where the plan is known.
const core::OptionsDescriptor<SlamOptions>& SlamOptionsDescriptor();

/// Problems with the options ("key: message"), empty if valid; see the descriptor.
std::vector<std::string> Validate(const SlamOptions& options);

/// Where a map VA came from.
enum class MapVaOrigin {
  kAnchor,      ///< a physical anchor (fixed, not in the state)
  kPrior,       ///< a VA of the known floor plan
  kDiscovered,  ///< found by discovery
};

/// One VA of the map.
struct MapVa {
  int id = 0;                ///< prior VAs: their id in the known VA set; discovered: 1'000'000 + n
  int anchor_index = 0;
  MapVaOrigin origin = MapVaOrigin::kDiscovered;
  int order = -1;            ///< reflection order for anchors and prior VAs, -1 if discovered
  Vec2 position_m = Vec2::Zero();                              ///< current estimate
  Eigen::Matrix2d covariance_m2 = Eigen::Matrix2d::Zero();     ///< marginal covariance
  int associations = 0;      ///< steps at which a range was associated to it
  int discovered_step = -1;  ///< step of promotion (discovered VAs)
  bool filtered = false;     ///< excluded by the VA filter at the last step
  std::optional<double> sigma_m;  ///< last estimated range std, if any
};

/// One association made at a step.
struct SlamAssociation {
  int anchor_index = 0;
  int va_id = 0;
  double measured_range_m = 0.0;
  double variance_m2 = 0.0;  ///< the range variance of the update (scaled: nis_window_updates)
  std::optional<double> sinr;
};

/// What one step produced.
struct SlamStepResult {
  Vec2 position_m = Vec2::Zero();
  Vec2 velocity_mps = Vec2::Zero();
  Eigen::Matrix2d position_covariance = Eigen::Matrix2d::Zero();
  std::vector<SlamAssociation> associations;
  estimation::UpdateResult update;
  int discovered = 0;   ///< VAs promoted into the state at this step
  int state_vas = 0;    ///< VAs in the state after the step
  bool relocalized = false;  ///< the track was lost and restarted at a recovered position
  /// Anchors whose missed LOS was taken back in the widened window at stage 1 (los_reacquire_m).
  int reacquired_los = 0;
};

/// Id of the first discovered VA (prior VA ids are below it).
inline constexpr int kFirstDiscoveredVaId = 1'000'000;

/// The SLAM tracker for one agent. Not thread-safe; one instance per run.
class SlamTracker {
 public:
  /// @param known_vas VAs of the known floor plan, at least the order-0 ones (the anchors).
  /// @param plan      the known floor plan (visibility of the prior VAs; may be empty when
  ///                  prior_visibility is off).
  /// @param range_sigma_at_unit_sinr_m c / (sqrt(8) pi beta) of the pulse (m).
  SlamTracker(const SlamOptions& options, const geometry::VirtualAnchorSet& known_vas, const geometry::FloorPlan& plan,
              double range_sigma_at_unit_sinr_m);

  /// Starts at p0_m at rest; the map holds the anchors and the prior VAs up to prior_max_order.
  void Initialize(double t_s, const Vec2& p0_m);

  /// Predicts to t_s and updates with the ranges of all anchors.
  SlamStepResult Step(double t_s, std::span<const core::RangeSet> measurements);

  /// The map with positions and covariances read from the state.
  [[nodiscard]] std::vector<MapVa> Map() const;

  [[nodiscard]] const estimation::State& state() const { return state_; }
  [[nodiscard]] const VaDiscovery& discovery() const { return discovery_; }
  /// The linearised range to map VA va_id (MapVa::id) at `state` (Leitinger Eq. 16, a current
  /// row): the agent's position block and, when the VA is in `state`, its block; a VA outside it
  /// (an anchor, a prior VA not yet associated) is fixed at its prior position. variance_m2
  /// becomes its R. Every update row (both stages) is built here. Empty when va_id is not in the
  /// map or the agent sits on the VA.
  [[nodiscard]] std::optional<estimation::MeasurementRow> VaRow(const estimation::State& state, int va_id,
                                                                double variance_m2) const;

 private:
  struct Pairing {
    int anchor_index = 0;
    std::size_t map_index = 0;
    const core::RangeMeasurement* measurement = nullptr;
    bool overlapped = false;
    bool shadowed = false;  // in the shadow cone of a blocked LOS
    bool reacquired = false;  // a missed LOS taken outside cutoff_m (los_reacquire_m)
    double innovation_m = 0.0;            // measured minus expected range at the association
    double predicted_variance_m2 = 0.0;  // the agent's and the VA's part of its variance, H P H^T
  };
  // Where stage 2 associates: the joint state after stage 1's LOS update, whose rows touch only
  // the agent position (the anchors are not in the state). Without stage 1 (or when it had no
  // rows), the prior.
  struct Reference {
    Vec2 position_m = Vec2::Zero();  // the agent's mean
    Eigen::Matrix2d covariance_m2 = Eigen::Matrix2d::Zero();
    std::optional<estimation::BlockUpdate> stage_one;  // the update, for the VAs' blocks
  };
  // A VA's mean, covariance and cross-covariance with the agent position at the reference.
  struct VaAtReference {
    Vec2 mean_m = Vec2::Zero();
    Eigen::Matrix2d covariance_m2 = Eigen::Matrix2d::Zero();  // P_vv'
    Eigen::Matrix2d cross_m2 = Eigen::Matrix2d::Zero();       // P_pv' (zero for a VA not in the state)
  };
  // The linearised rows of an update (Leitinger Eq. 16): H, innovation and R.
  struct Rows {
    std::vector<estimation::MeasurementRow> rows;
    std::vector<double> innovations_m;  // measured minus predicted range, one per row
  };
  [[nodiscard]] Vec2 VaPosition(std::size_t map_index) const;
  [[nodiscard]] bool InState(std::size_t map_index) const;
  [[nodiscard]] bool Filtered(std::size_t map_index) const;
  // A prior VA whose visibility region the known floor plan gives.
  [[nodiscard]] bool HasVisibility(std::size_t map_index) const;
  // A VA that may be associated where its path is blocked: neither an anchor nor a VA with a
  // visibility region (discovered VAs, prior ones without prior_visibility). The shadow cone and
  // the blocked-anchor amplitude gate apply to these.
  [[nodiscard]] bool LacksVisibilityModel(std::size_t map_index) const;
  [[nodiscard]] double CurrentVariance(int va_id) const;
  // Map entries of one anchor that may be associated at the reference position.
  [[nodiscard]] std::vector<std::size_t> Candidates(int anchor_index, const Vec2& at_m, bool los_only) const;
  [[nodiscard]] std::vector<Pairing> Associate(const Reference& reference,
                                               std::span<const core::RangeSet> measurements, bool los_only,
                                               double gate) const;
  // The reference without stage 1: the agent's predicted position.
  [[nodiscard]] Reference PriorReference() const;
  [[nodiscard]] VaAtReference VaAt(const Reference& reference, std::size_t map_index) const;
  // VaRow of map entry map_index.
  [[nodiscard]] std::optional<estimation::MeasurementRow> MapRow(const estimation::State& state, std::size_t map_index,
                                                                 double variance_m2) const;
  [[nodiscard]] Rows Linearize(const estimation::State& state, const std::vector<Pairing>& pairings,
                               const std::vector<double>& variances_m2) const;
  estimation::UpdateResult Update(estimation::State& state, const std::vector<Pairing>& pairings,
                                  const std::vector<double>& variances_m2) const;
  // Stage 1's reference: the joint update with the anchors' LOS pairings (Reference), or the
  // prior when there are none or S is not positive definite.
  [[nodiscard]] Reference StageOne(const std::vector<Pairing>& los, const std::vector<double>& variances_m2) const;
  void AddToState(std::size_t map_index);
  // The discovered VAs in the state: the blocks of their random walk
  // (SlamOptions::discovered_va_walk_m_per_sqrt_s).
  [[nodiscard]] std::vector<estimation::BlockKey> DiscoveredVaBlocks() const;
  // Marks the anchors without an unfiltered LOS pairing among `pairings` (Entry::los_missed): the
  // pairings of stage 1, or of the joint association without reassociate. Remembers the step of
  // such a miss, at time t_s (last_los_miss_t_s_, the recovery's watch window).
  void NoteLosMisses(const std::vector<Pairing>& pairings, double t_s);
  // Whether the anchor's LOS found no range at this step's stage 1 (Entry::los_missed).
  [[nodiscard]] bool LosMissed(int anchor_index) const;
  // Shadow cone: positions of the anchors whose LOS was missed at this step.
  [[nodiscard]] std::vector<Vec2> BlockedAnchors() const;
  // Shadow cone: flags the pairings of VAs without a visibility region whose path arrives at
  // at_m from within the cone around a blocked anchor's direction.
  void MarkShadowed(std::vector<Pairing>& pairings, std::span<const Vec2> blocked_m, const Vec2& at_m) const;
  // Track-loss check after the update; restarts the agent and returns true when it was lost.
  bool RecoverTrack(double t_s, std::span<const core::RangeSet> measurements);
  // How far from where an amplitude law was formed it still holds: two window lengths, enough to
  // bridge an obstacle's shadow (m).
  [[nodiscard]] double LawReachM() const { return 2.0 * options_.variance.window_max_m; }
  // The amplitude gate's law for a VA seen from at_m at the expected range, if any.
  [[nodiscard]] std::optional<estimation::RicianLaw> GateLaw(std::size_t map_index, const Vec2& at_m,
                                                             double expected_range_m) const;
  // Before the VA has a fitted law: the start-up law at the expected range, if any
  // (SlamOptions::startup_amplitude_k_factor).
  [[nodiscard]] std::optional<estimation::RicianLaw> StartUpLaw(std::size_t map_index, const Vec2& at_m,
                                                                double expected_range_m) const;

  // The amplitudes of a VA's associations before it has a fitted law, as amplitude x expected
  // range (the specular amplitude falls as 1 / d), from the agent position of the first.
  struct StartUpAmplitudes {
    double amplitude_range_sum_m = 0.0;
    int count = 0;
    Vec2 first_at_m = Vec2::Zero();
    // Records an amplitude (only > 0) seen from at_m at range_m; a record formed farther than
    // reach_m away starts again here.
    void Add(double amplitude, double range_m, const Vec2& at_m, double reach_m);
    // The mean amplitude x range, while the record holds at at_m (within reach_m of its first).
    [[nodiscard]] std::optional<double> MeanAmplitudeRange(const Vec2& at_m, double reach_m) const;
    void Clear() { *this = StartUpAmplitudes{}; }
  };

  struct Entry {
    MapVa va;
    Vec2 prior_m = Vec2::Zero();
    /// The Rician law of the VA's amplitudes at its last moment-based estimate: the amplitude
    /// gate's reference, kept while the VA is not seen (the window itself moves with the agent
    /// and expires in an obstacle's shadow, exactly when the gate is needed).
    std::optional<estimation::RicianLaw> amplitude_law;
    Vec2 amplitude_law_at_m = Vec2::Zero();  ///< agent position of that estimate
    double amplitude_law_range_m = 0.0;       ///< expected range there
    /// Before amplitude_law exists, the amplitudes the start-up law is formed from
    /// (SlamOptions::startup_amplitude_k_factor).
    StartUpAmplitudes startup;
    /// An anchor whose LOS found no range at stage 1: read at the next step's stage 1 (LOS
    /// re-acquisition) and, once stage 1 has set it, at this step's stage 2 (shadow cone,
    /// blocked_amplitude_probability). Without reassociate it is set from the joint association,
    /// where only the recovery's watch window uses it (through last_los_miss_t_s_).
    bool los_missed = false;
    /// The mean NIS of the last updates (SlamOptions::nis_window_updates): the factor on the range
    /// variance of the next one.
    estimation::InnovationScale innovation_scale;
  };
  // A map entry with the per-entry state the options configure (the innovation scale's window);
  // every entry is made here.
  [[nodiscard]] Entry NewEntry() const;

  SlamOptions options_;
  const geometry::VirtualAnchorSet* known_vas_;
  const geometry::FloorPlan* plan_;
  estimation::RangeVarianceEstimator variance_;
  estimation::ConstantVelocity motion_;
  VaDiscovery discovery_;
  TrackRecovery recovery_;
  estimation::State state_;
  std::vector<Entry> map_;
  int step_ = 0;
  std::optional<double> last_los_miss_t_s_;  // the last time an anchor's LOS found no range (s)
  int next_discovered_id_ = kFirstDiscoveredVaId;
};

}  // namespace mirage::methods::slam
