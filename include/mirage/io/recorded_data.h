// SPDX-License-Identifier: MIT
// Recorded data in CSV files (docs/recorded_data.md, ROADMAP.md "Recorded data"), ranges,
// acoustic arrival-time stamps or pairwise time differences (Bordoy 2020 issue, item 9):
//   anchors.csv  anchor_id,x_m,y_m[,z_m]
//   ranges.csv   t_s,anchor_id,range_m[,amplitude]   several unlabeled rows per time and anchor
//   mics.csv     receiver_id,x_m,y_m,z_m
//   toa.csv      t_s,receiver_id,toa_s               several unlabeled rows per emission and microphone
//   tdoa.csv     t_s,id_i,id_j,tdoa_m                 tdoa_m = |p - a_j| - |p - a_i|; anchors.csv needs z_m
//   truth.csv    t_s,x_m,y_m[,z_m]                   optional
// Reading is strict: a missing field, an unknown anchor or microphone, time going backwards, a
// negative or non-finite range is an InputError naming the file and line; nothing is guessed or
// dropped. A TDOA far larger than the anchors' baseline is not an error: UWB TDOA systems
// (Bitcraze's Loco Positioning) report outliers of tens of metres, and rejecting them is the
// estimator's job (a gate, a robust weight), not the reader's.
#pragma once

#include <optional>
#include <string>
#include <string_view>

#include "mirage/pipeline/recording.h"

namespace mirage::io {

/// Parses anchors.csv into recording.anchor_ids / anchors_m / anchors_have_z.
/// @param file the name used in messages
void ParseAnchorsCsv(std::string_view text, const std::string& file, pipeline::Recording& recording);

/// Parses ranges.csv into recording.steps; the anchors must be parsed already. Rows with the
/// same t_s form one step (they must be consecutive: t_s never decreases).
void ParseRangesCsv(std::string_view text, const std::string& file, pipeline::Recording& recording);

/// Parses mics.csv into recording.anchor_ids / anchors_m (the microphones, 3-D) and marks the
/// recording as one of stamps.
/// @param file the name used in messages
void ParseMicsCsv(std::string_view text, const std::string& file, pipeline::Recording& recording);

/// Parses toa.csv into recording.steps, one step per emission; the microphones must be parsed
/// already. Rows with the same t_s are one emission (they must be consecutive: t_s never
/// decreases); each step has one ToaStamps record per microphone (receiver_index == its row in
/// mics.csv), empty for a microphone without rows.
void ParseToaCsv(std::string_view text, const std::string& file, pipeline::Recording& recording);

/// Parses tdoa.csv into recording.steps and sets recording.tdoa; the anchors must be parsed
/// already, with a z_m column (a TDOA recording is 3-D). Rows with the same t_s form one step
/// (they must be consecutive: t_s never decreases), its tdoas in file order, each with t_s,
/// id_i, id_j and index_i, index_j (the anchors' rows in anchors.csv) set. id_i and id_j must be
/// known and differ; tdoa_m (m) must be finite and may have any size.
/// @param file the name used in messages
void ParseTdoaCsv(std::string_view text, const std::string& file, pipeline::Recording& recording);

/// Parses truth.csv into recording.truth (t_s strictly increasing).
void ParseTruthCsv(std::string_view text, const std::string& file, pipeline::Recording& recording);

/// The files of one recording: anchors and ranges, mics and toa, or anchors and tdoa (the
/// others empty).
struct RecordingFiles {
  std::string anchors;
  std::string ranges;
  std::optional<std::string> truth;
  std::string mics;
  std::string toa;
  /// tdoa.csv; with anchors (3-D), instead of ranges. The initializer keeps positional
  /// initialisation of the first five members free of missing-initializer warnings.
  std::string tdoa = {};

  /// Whether the recording is one of arrival-time stamps (mics and toa).
  [[nodiscard]] bool toa_stamps() const { return !mics.empty(); }
  /// Whether the recording is one of pairwise time differences (anchors and tdoa).
  [[nodiscard]] bool pairwise_tdoa() const { return !tdoa.empty(); }
};

/// Reads and checks a recording. Giving tdoa together with ranges, mics or toa is an error.
/// Every step must lie inside the truth's time span when a truth file is given (the error needs
/// a true position at every step).
pipeline::Recording LoadRecording(const RecordingFiles& files);

/// Writes anchors.csv and ranges.csv (mics.csv and toa.csv for a recording of stamps; anchors.csv
/// with z_m and tdoa.csv for a TDOA recording) and, with truth, truth.csv into `dir` (created if
/// missing).
/// Numbers are written in their shortest exact form, so reading them back gives the same doubles.
void WriteRecording(const std::string& dir, const pipeline::Recording& recording);

}  // namespace mirage::io
