// SPDX-License-Identifier: MIT
#include "mirage/channel/acoustic_stamps.h"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <cstddef>
#include <optional>
#include <string>

#include "mirage/core/medium.h"

namespace mirage::channel {
namespace {

constexpr int kMaxStampOrder = 3;

// Faced reflector of the episode active at t_s: nullopt when none is active; -1 when its name is
// not a reflector (the caller should have rejected it; then no path survives).
std::optional<int> FacedReflector(const AcousticStampOptions& options, std::span<const geometry::Reflector3> reflectors,
                                  double t_s) {
  for (const FacingEpisode& episode : options.facing) {
    if (!(t_s >= episode.t_start_s && t_s < episode.t_end_s)) continue;
    for (std::size_t i = 0; i < reflectors.size(); ++i) {
      if (reflectors[i].name == episode.reflector) return static_cast<int>(i);
    }
    assert(false && "a facing episode names an unknown reflector");
    return -1;
  }
  return std::nullopt;
}

// The person holding the phone: a vertical cylinder from the floor to height_m.
struct Body {
  Vec2 axis_m = Vec2::Zero();
  double radius_m = 0.0;
  double height_m = 0.0;

  // True if the leg a -> b passes through the cylinder: the part of its horizontal projection
  // inside the circle has a point below the top. The height is linear along the leg, so the
  // lowest point of that part is at one of its ends.
  [[nodiscard]] bool Blocks(const Vec3& a_m, const Vec3& b_m) const {
    const Vec2 p0 = a_m.head<2>() - axis_m;
    const Vec2 d = (b_m - a_m).head<2>();
    const double qa = d.squaredNorm();
    const double qb = 2.0 * d.dot(p0);
    const double qc = p0.squaredNorm() - radius_m * radius_m;
    double t0 = 0.0, t1 = 1.0;
    if (qa < 1e-18) {
      if (qc >= 0.0) return false;  // a vertical leg outside the circle
    } else {
      const double disc = qb * qb - 4.0 * qa * qc;
      if (disc <= 0.0) return false;  // misses or grazes the circle
      const double root = std::sqrt(disc);
      t0 = std::max(0.0, (-qb - root) / (2.0 * qa));
      t1 = std::min(1.0, (-qb + root) / (2.0 * qa));
      if (t0 >= t1) return false;  // the circle lies beyond either end
    }
    const double z0 = a_m.z() + t0 * (b_m.z() - a_m.z());
    const double z1 = a_m.z() + t1 * (b_m.z() - a_m.z());
    return std::min(z0, z1) < height_m;
  }
};

// The candidate surface sequences of order 0 .. max_order without back-to-back repeats, in
// SpecularPaths3's order (by order, then lexicographically), so that the two can be walked side
// by side.
std::vector<std::vector<int>> CandidateSequences(int n_reflectors, int max_order) {
  std::vector<std::vector<int>> out{{}};
  std::size_t begin = 0;
  for (int order = 1; order <= max_order; ++order) {
    const std::size_t end = out.size();
    for (std::size_t i = begin; i < end; ++i) {
      for (int s = 0; s < n_reflectors; ++s) {
        if (!out[i].empty() && out[i].back() == s) continue;
        std::vector<int> next = out[i];
        next.push_back(s);
        out.push_back(std::move(next));
      }
    }
    begin = end;
  }
  return out;
}

}  // namespace

const core::OptionsDescriptor<AcousticStampOptions>& AcousticStampOptionsDescriptor() {
  using core::ValueRange;
  using O = AcousticStampOptions;
  static const auto descriptor = [] {
    const ValueRange bias_range = ValueRange::AtLeast(0.0);
    const ValueRange length_range = ValueRange::AtLeast(0.0);
    core::OptionsDescriptor<O> d("channel::AcousticStampOptions");
    d.Number(&O::temperature_c,
             {.key = "temperature_c",
              .unit = "degC",
              .range = ValueRange::Closed(-50.0, 60.0),
              .doc = "Air temperature: the true sound speed is 331.3 sqrt(1 + theta / 273.15) m/s (Eq. 3.31). 20 C "
                     "(343.2 m/s), the thesis's halls."});
    d.Integer(&O::max_order, {.key = "max_order",
                              .range = ValueRange::Closed(0.0, 3.0),
                              .doc = "Highest reflection order simulated. 2: first- and second-order echoes are the "
                                     "ones mistaken for the line of sight (Sec. 3.2)."});
    d.Number(&O::stamp_sigma_s, {.key = "stamp_sigma_s",
                                 .unit = "s",
                                 .range = ValueRange::Above(0.0),
                                 .doc = "Standard deviation of a stamp. 0.3 ms, the ch. 5 synthetic regime."});
    d.Number(&O::heavy_tail_fraction,
             {.key = "heavy_tail_fraction",
              .range = ValueRange::Closed(0.0, 1.0),
              .doc = "Fraction of stamps drawn with heavy_tail_scale times the sigma (heavy-tailed histograms from "
                     "synchronisation and detection errors). 0: Gaussian."});
    d.Number(&O::heavy_tail_scale, {.key = "heavy_tail_scale",
                                    .range = ValueRange::Above(0.0),
                                    .doc = "Sigma of the heavy-tail stamps over stamp_sigma_s. 10."});
    d.Number(&O::detection_probability, {.key = "detection_probability",
                                         .range = ValueRange::Closed(0.0, 1.0),
                                         .doc = "Detection probability of a path at zero length. 1."});
    d.Number(&O::half_detection_range_m,
             {.key = "half_detection_range_m",
              .unit = "m",
              .range = ValueRange::Above(0.0),
              .doc = "Path length at which the detection probability has halved: P_d = detection_probability * gain "
                     "/ (1 + (d / half_detection_range_m)^4). 30 m (48 % of chirps detected at 30 m)."});
    d.Number(&O::max_range_m, {.key = "max_range_m",
                               .unit = "m",
                               .range = ValueRange::Above(0.0),
                               .doc = "Paths longer than this are never detected; also the listening window of "
                                      "false alarms (max_range_m / c). 40 m."});
    d.Number(&O::false_alarm_rate,
             {.key = "false_alarm_rate",
              .range = ValueRange::AtLeast(0.0),
              .doc = "Mean number of false alarms per microphone and emission (Poisson), uniform over the listening "
                     "window. 0: none."});
    d.Number(&O::nlos_fraction,
             {.key = "nlos_fraction",
              .range = ValueRange::Closed(0.0, 1.0),
              .doc = "Probability that a microphone's detected direct stamp is delayed by U(nlos_bias_min_s, "
                     "nlos_bias_max_s) (the synthetic NLOS regime of Sec. 5.3, 0.4 there). 0: none."});
    d.Number(&O::nlos_bias_min_s, {.key = "nlos_bias_min_s",
                                   .unit = "s",
                                   .range = bias_range,
                                   .doc = "Smallest synthetic NLOS bias. 3 ms (Sec. 5.3)."});
    d.Number(&O::nlos_bias_max_s, {.key = "nlos_bias_max_s",
                                   .unit = "s",
                                   .range = bias_range,
                                   .doc = "Largest synthetic NLOS bias, >= nlos_bias_min_s. 13 ms (Sec. 5.3)."});
    d.Number(&O::body_radius_m,
             {.key = "body_radius_m",
              .unit = "m",
              .range = length_range,
              .doc = "Radius of the body cylinder behind the sender that blocks the paths leaving through it. 0: no "
                     "body."});
    d.Number(&O::body_offset_m, {.key = "body_offset_m",
                                 .unit = "m",
                                 .range = length_range,
                                 .doc = "Distance of the body's axis behind the sender, opposite to its heading. "
                                        "0.25 m, a phone held in front of the chest."});
    d.Number(&O::body_height_m, {.key = "body_height_m",
                                 .unit = "m",
                                 .range = length_range,
                                 .doc = "Height of the body cylinder's top above the floor. 1.8 m."});
    d.Number(&O::clock_drift_ppm,
             {.key = "clock_drift_ppm",
              .unit = "ppm",
              .range = ValueRange::Closed(-1000.0, 1000.0),
              .doc = "The sender's clock rate error: emission k leaves at t_0 + k I (1 + ppm 1e-6); applied by the "
                     "caller that schedules the emissions. 0."});
    d.Boolean(&O::emission_time_known,
              {.key = "emission_time_known",
               .doc = "The system knows each emission's true time (a synchronised sender, or a reference system as "
                      "the thesis's motion capture, Sec. 8.5): the stamp records carry it, for methods that take the "
                      "sending time as known. false."});
    d.Check("nlos_bias_max_s >= nlos_bias_min_s", [=](const O& o) -> std::vector<std::string> {
      if (!bias_range.Contains(o.nlos_bias_min_s) || !bias_range.Contains(o.nlos_bias_max_s) ||
          o.nlos_bias_max_s >= o.nlos_bias_min_s) {
        return {};
      }
      return {"nlos_bias_max_s: " + core::FormatNumber(o.nlos_bias_max_s) + " s must be at least nlos_bias_min_s (" +
              core::FormatNumber(o.nlos_bias_min_s) + " s)"};
    });
    d.Check("body_offset_m > body_radius_m when body_radius_m > 0", [=](const O& o) -> std::vector<std::string> {
      if (!(o.body_radius_m > 0.0) || !length_range.Contains(o.body_radius_m) ||
          !length_range.Contains(o.body_offset_m) || o.body_offset_m > o.body_radius_m) {
        return {};
      }
      return {"body_offset_m: " + core::FormatNumber(o.body_offset_m) + " m must exceed body_radius_m (" +
              core::FormatNumber(o.body_radius_m) + " m): the sender would stand inside the body"};
    });
    return d;
  }();
  return descriptor;
}

std::vector<std::string> Validate(const AcousticStampOptions& options) {
  std::vector<std::string> problems = AcousticStampOptionsDescriptor().Validate(options);
  for (std::size_t i = 0; i < options.facing.size(); ++i) {
    const FacingEpisode& e = options.facing[i];
    const std::string key = "facing[" + std::to_string(i) + "]";
    if (!std::isfinite(e.t_start_s) || !std::isfinite(e.t_end_s)) {
      problems.push_back(key + ": t_start_s and t_end_s must be finite");
    } else if (!(e.t_end_s > e.t_start_s)) {
      problems.push_back(key + ".t_end_s: " + core::FormatNumber(e.t_end_s) + " s must exceed t_start_s (" +
                         core::FormatNumber(e.t_start_s) + " s)");
    }
  }
  return problems;
}

double SoundSpeedMps(double theta_c) { return core::Medium::Sound(theta_c).speed_mps; }  // Eq. (3.31), dry air

AcousticEmission SimulateEmission(const AcousticStampOptions& options, std::span<const geometry::Reflector3> reflectors,
                                  std::span<const Vec3> mics_m, const Vec3& sender_m, const Vec2& heading,
                                  double t_emit_s, core::Rng& rng) {
  assert(options.max_order >= 0 && options.max_order <= kMaxStampOrder);
  const double c_mps = SoundSpeedMps(options.temperature_c);
  const std::optional<int> faced = FacedReflector(options, reflectors, t_emit_s);
  std::optional<Body> body;
  if (options.body_radius_m > 0.0 && heading.norm() > 1e-12) {
    body = Body{sender_m.head<2>() - options.body_offset_m * heading.normalized(), options.body_radius_m,
                options.body_height_m};
  }
  const auto candidates = CandidateSequences(static_cast<int>(reflectors.size()), options.max_order);
  const double window_s = options.max_range_m / c_mps;

  AcousticEmission emission;
  emission.t_emit_s = t_emit_s;
  emission.stamps.resize(mics_m.size());
  emission.direct_visible.assign(mics_m.size(), false);
  for (std::size_t m = 0; m < mics_m.size(); ++m) {
    // One draw of the caller's stream per microphone; all the rest from the microphone's own.
    core::Rng mic_rng(rng.NextU64());
    const bool nlos = mic_rng.Bernoulli(options.nlos_fraction);
    const double bias_s = mic_rng.Uniform(options.nlos_bias_min_s, options.nlos_bias_max_s);

    const auto paths = geometry::SpecularPaths3(reflectors, sender_m, mics_m[m], options.max_order);
    std::vector<AcousticStamp>& stamps = emission.stamps[m];
    std::size_t next = 0;
    for (const auto& sequence : candidates) {
      // Three draws per candidate, whatever happens to it.
      const double detect_u = mic_rng.Uniform();
      const bool heavy = mic_rng.Bernoulli(options.heavy_tail_fraction);
      const double z = mic_rng.Normal();
      if (next >= paths.size() || paths[next].surfaces != sequence) continue;
      const geometry::SpecularPath3& path = paths[next++];
      const bool direct = path.surfaces.empty();
      bool visible = !(body && body->Blocks(path.vertices_m[0], path.vertices_m[1]));
      if (faced) visible = visible && !direct && path.surfaces.front() == *faced;
      if (direct) emission.direct_visible[m] = visible;
      if (!visible || path.length_m > options.max_range_m) continue;
      const double ratio = path.length_m / options.half_detection_range_m;
      const double p_detect =
          options.detection_probability * path.reflection_gain / (1.0 + ratio * ratio * ratio * ratio);
      if (!(detect_u < p_detect)) continue;
      const double sigma_s = options.stamp_sigma_s * (heavy ? options.heavy_tail_scale : 1.0);
      AcousticStamp stamp;
      stamp.toa_s = t_emit_s + path.length_m / c_mps + sigma_s * z;
      if (direct) {
        stamp.label = nlos ? StampLabel::kDirectBiased : StampLabel::kDirect;
        if (nlos) stamp.toa_s += bias_s;
      } else {
        stamp.label = StampLabel::kEcho;
        stamp.surfaces = path.surfaces;
      }
      stamps.push_back(std::move(stamp));
    }
    assert(next == paths.size());
    const int false_alarms = mic_rng.Poisson(options.false_alarm_rate);
    for (int k = 0; k < false_alarms; ++k) {
      stamps.push_back({t_emit_s + mic_rng.Uniform(0.0, window_s), StampLabel::kFalseAlarm, {}});
    }
    std::stable_sort(stamps.begin(), stamps.end(),
                     [](const AcousticStamp& a, const AcousticStamp& b) { return a.toa_s < b.toa_s; });
  }
  return emission;
}

}  // namespace mirage::channel
