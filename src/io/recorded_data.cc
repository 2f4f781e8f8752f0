// SPDX-License-Identifier: MIT
#include "mirage/io/recorded_data.h"

#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "mirage/io/csv_reader.h"
#include "mirage/io/input_error.h"
#include "mirage/io/output_file.h"

namespace mirage::io {
namespace {

std::string ReadFile(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw InputError(path + ": is a directory, expected a CSV file");
  // A device, pipe or socket (a link to /dev/zero) would be read without end.
  if (!std::filesystem::is_regular_file(path, ec)) {
    throw InputError(path + (std::filesystem::exists(path, ec) ? ": not a regular file, expected a CSV file"
                                                               : ": cannot open (no such file)"));
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path + ": cannot open");
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw InputError(path + ": read failed");
  return text.str();
}

// mics.csv and toa.csv; fmt's "{}" is the shortest representation that reads back to the same double.
void WriteStamps(const std::string& dir, const pipeline::Recording& recording) {
  {
    OutputFile out_file(dir + "/mics.csv");
    auto& out = out_file.stream();
    out << "receiver_id,x_m,y_m,z_m\n";
    for (std::size_t m = 0; m < recording.anchor_ids.size(); ++m) {
      const Vec3& p = recording.anchors_m[m];
      out << fmt::format("{},{},{},{}\n", recording.anchor_ids[m], p.x(), p.y(), p.z());
    }
    out_file.Commit();
  }
  OutputFile out_file(dir + "/toa.csv");
  auto& out = out_file.stream();
  out << "t_s,receiver_id,toa_s\n";
  for (const auto& step : recording.steps) {
    for (const auto& stamps : step.toas) {
      const std::string& id = recording.anchor_ids[static_cast<std::size_t>(stamps.receiver_index)];
      for (const double toa_s : stamps.toa_s) out << fmt::format("{},{},{}\n", step.t_s, id, toa_s);
    }
  }
  out_file.Commit();
}

// anchors.csv, with z_m when the recording has heights (always for TDOA, which is 3-D).
void WriteAnchors(const std::string& dir, const pipeline::Recording& recording) {
  OutputFile out_file(dir + "/anchors.csv");
  auto& out = out_file.stream();
  const bool with_z = recording.anchors_have_z || recording.tdoa;
  out << (with_z ? "anchor_id,x_m,y_m,z_m\n" : "anchor_id,x_m,y_m\n");
  for (std::size_t a = 0; a < recording.anchor_ids.size(); ++a) {
    out << fmt::format("{},{},{}", recording.anchor_ids[a], recording.anchors_m[a].x(), recording.anchors_m[a].y());
    if (with_z) out << fmt::format(",{}", recording.anchors_m[a].z());
    out << "\n";
  }
  out_file.Commit();
}

void WriteRanges(const std::string& dir, const pipeline::Recording& recording) {
  OutputFile out_file(dir + "/ranges.csv");
  auto& out = out_file.stream();
  out << "t_s,anchor_id,range_m,amplitude\n";
  for (const auto& step : recording.steps) {
    for (const auto& anchor : step.anchors) {
      const std::string& id = recording.anchor_ids[static_cast<std::size_t>(anchor.anchor_index)];
      for (const auto& r : anchor.ranges) {
        // fmt's "{}" is the shortest representation that reads back to the same double.
        out << fmt::format("{},{},{},{}\n", step.t_s, id, r.range_m, r.amplitude ? fmt::format("{}", *r.amplitude) : "");
      }
    }
  }
  out_file.Commit();
}

// tdoa.csv: one row per difference at its step's time, the ids from the indices (as the estimators
// see them), in the shortest exact form.
void WriteTdoa(const std::string& dir, const pipeline::Recording& recording) {
  OutputFile out_file(dir + "/tdoa.csv");
  auto& out = out_file.stream();
  out << "t_s,id_i,id_j,tdoa_m\n";
  for (const auto& step : recording.steps) {
    for (const auto& m : step.tdoas) {
      out << fmt::format("{},{},{},{}\n", step.t_s, recording.anchor_ids[static_cast<std::size_t>(m.index_i)],
                         recording.anchor_ids[static_cast<std::size_t>(m.index_j)], m.tdoa_m);
    }
  }
  out_file.Commit();
}

// An id (anchor or microphone) -> its row in the anchors or mics file.
std::map<std::string, int, std::less<>> IndexOfIds(const std::vector<std::string>& ids) {
  std::map<std::string, int, std::less<>> index;
  for (std::size_t k = 0; k < ids.size(); ++k) index[ids[k]] = static_cast<int>(k);
  return index;
}

// Whether the current row, at t_s, opens a new step: rows with the same t_s share one step, and
// t_s may not decrease (the rows of one step are consecutive).
bool OpensStep(const CsvReader& csv, double t_s, const std::vector<pipeline::RecordedStep>& steps) {
  if (steps.empty() || t_s > steps.back().t_s) return true;
  if (t_s < steps.back().t_s) {
    csv.Fail("t_s", fmt::format("time goes backwards (the previous row has t_s = {})", steps.back().t_s));
  }
  return false;
}

// anchors.csv; a non-empty `z_required_by` makes the z_m column required and says why.
void ParseAnchors(std::string_view text, const std::string& file, const std::string& z_required_by,
                  pipeline::Recording& recording) {
  CsvReader csv(text, file, {{"anchor_id"}, {"x_m"}, {"y_m"}, {"z_m", false}});
  if (!z_required_by.empty() && !csv.Has("z_m")) csv.FailRow("the header lacks the column 'z_m', " + z_required_by);
  recording.anchor_ids.clear();
  recording.anchors_m.clear();
  recording.anchors_have_z = csv.Has("z_m");
  while (csv.Next()) {
    const std::string id(csv.Field("anchor_id"));
    if (id.empty()) csv.Fail("anchor_id", "missing value (expected an anchor id)");
    for (const auto& known : recording.anchor_ids) {
      if (known == id) csv.Fail("anchor_id", "duplicate anchor id");
    }
    recording.anchor_ids.push_back(id);
    recording.anchors_m.emplace_back(csv.Number("x_m"), csv.Number("y_m"), csv.Has("z_m") ? csv.Number("z_m") : 0.0);
  }
  if (recording.anchor_ids.empty()) throw InputError(file + ": no anchors (expected at least one row after the header)");
}

}  // namespace

void ParseAnchorsCsv(std::string_view text, const std::string& file, pipeline::Recording& recording) {
  ParseAnchors(text, file, "", recording);
}

void ParseRangesCsv(std::string_view text, const std::string& file, pipeline::Recording& recording) {
  CsvReader csv(text, file, {{"t_s"}, {"anchor_id"}, {"range_m"}, {"amplitude", false}});
  const auto anchor_index = IndexOfIds(recording.anchor_ids);
  recording.steps.clear();
  while (csv.Next()) {
    const double t_s = csv.Number("t_s");
    const std::string_view id = csv.Field("anchor_id");
    const auto it = anchor_index.find(id);
    if (it == anchor_index.end()) csv.Fail("anchor_id", "unknown anchor (not in the anchors file)");
    const double range_m = csv.Number("range_m");
    if (range_m < 0.0) csv.Fail("range_m", "a range must be >= 0 m");
    core::RangeMeasurement m{range_m, std::nullopt};
    if (csv.Has("amplitude") && !csv.Field("amplitude").empty()) {
      m.amplitude = csv.Number("amplitude");
      if (*m.amplitude < 0.0) csv.Fail("amplitude", "an amplitude magnitude must be >= 0");
    }
    if (OpensStep(csv, t_s, recording.steps)) {
      pipeline::RecordedStep step;
      step.t_s = t_s;
      for (std::size_t a = 0; a < recording.anchor_ids.size(); ++a) {
        core::RangeSet set;
        set.anchor_index = static_cast<int>(a);
        step.anchors.push_back(std::move(set));
      }
      recording.steps.push_back(std::move(step));
    }
    recording.steps.back().anchors[static_cast<std::size_t>(it->second)].ranges.push_back(m);
  }
  if (recording.steps.empty()) throw InputError(file + ": no ranges (expected at least one row after the header)");
}

void ParseMicsCsv(std::string_view text, const std::string& file, pipeline::Recording& recording) {
  CsvReader csv(text, file, {{"receiver_id"}, {"x_m"}, {"y_m"}, {"z_m"}});
  recording.toa_stamps = true;
  recording.anchor_ids.clear();
  recording.anchors_m.clear();
  recording.anchors_have_z = true;
  while (csv.Next()) {
    const std::string id(csv.Field("receiver_id"));
    if (id.empty()) csv.Fail("receiver_id", "missing value (expected a microphone id)");
    for (const auto& known : recording.anchor_ids) {
      if (known == id) csv.Fail("receiver_id", "duplicate microphone id");
    }
    recording.anchor_ids.push_back(id);
    recording.anchors_m.emplace_back(csv.Number("x_m"), csv.Number("y_m"), csv.Number("z_m"));
  }
  if (recording.anchor_ids.empty()) throw InputError(file + ": no microphones (expected at least one row after the header)");
}

void ParseToaCsv(std::string_view text, const std::string& file, pipeline::Recording& recording) {
  CsvReader csv(text, file, {{"t_s"}, {"receiver_id"}, {"toa_s"}});
  const auto receiver_index = IndexOfIds(recording.anchor_ids);
  recording.steps.clear();
  while (csv.Next()) {
    const double t_s = csv.Number("t_s");
    const auto it = receiver_index.find(csv.Field("receiver_id"));
    if (it == receiver_index.end()) csv.Fail("receiver_id", "unknown microphone (not in the mics file)");
    const double toa_s = csv.Number("toa_s");
    if (OpensStep(csv, t_s, recording.steps)) {
      pipeline::RecordedStep step;
      step.t_s = t_s;
      for (std::size_t m = 0; m < recording.anchor_ids.size(); ++m) {
        core::ToaStamps stamps;
        stamps.t_s = t_s;
        stamps.receiver_id = recording.anchor_ids[m];
        stamps.receiver_index = static_cast<int>(m);
        step.toas.push_back(std::move(stamps));
      }
      recording.steps.push_back(std::move(step));
    }
    recording.steps.back().toas[static_cast<std::size_t>(it->second)].toa_s.push_back(toa_s);
  }
  if (recording.steps.empty()) throw InputError(file + ": no stamps (expected at least one row after the header)");
}

void ParseTdoaCsv(std::string_view text, const std::string& file, pipeline::Recording& recording) {
  // A caller's mistake rather than the file's, but the fuzzer and the scenario reader reach it
  // with any anchors, so it is an InputError like the rest.
  if (recording.toa_stamps) {
    throw InputError(file + ": the receivers are the microphones of a recording of stamps; "
                            "a TDOA recording takes anchors.csv");
  }
  if (!recording.anchors_have_z) {
    throw InputError(file + ": the anchors have no z_m column, but a TDOA recording is 3-D "
                            "(give the anchors file a z_m column)");
  }
  CsvReader csv(text, file, {{"t_s"}, {"id_i"}, {"id_j"}, {"tdoa_m"}});
  const auto anchor_index = IndexOfIds(recording.anchor_ids);
  const auto index_of = [&](const std::string& column) {
    const auto it = anchor_index.find(csv.Field(column));
    if (it == anchor_index.end()) csv.Fail(column, "unknown anchor (not in the anchors file)");
    return it->second;
  };
  recording.tdoa = true;
  recording.steps.clear();
  while (csv.Next()) {
    core::TdoaMeasurement m;
    m.t_s = csv.Number("t_s");
    m.index_i = index_of("id_i");
    m.index_j = index_of("id_j");
    if (m.index_i == m.index_j) csv.Fail("id_j", "the same anchor as id_i (a time difference needs two anchors)");
    m.id_i = recording.anchor_ids[static_cast<std::size_t>(m.index_i)];
    m.id_j = recording.anchor_ids[static_cast<std::size_t>(m.index_j)];
    // Finite, of any size and sign: |tdoa_m| beyond the baseline |a_i - a_j| is an outlier the
    // estimator must handle, not a malformed row.
    m.tdoa_m = csv.Number("tdoa_m");
    if (OpensStep(csv, m.t_s, recording.steps)) {
      pipeline::RecordedStep step;
      step.t_s = m.t_s;
      recording.steps.push_back(std::move(step));
    }
    recording.steps.back().tdoas.push_back(std::move(m));
  }
  if (recording.steps.empty()) {
    throw InputError(file + ": no time differences (expected at least one row after the header)");
  }
}

void ParseTruthCsv(std::string_view text, const std::string& file, pipeline::Recording& recording) {
  CsvReader csv(text, file, {{"t_s"}, {"x_m"}, {"y_m"}, {"z_m", false}});
  recording.truth.clear();
  recording.truth_has_z = csv.Has("z_m");
  while (csv.Next()) {
    const double t_s = csv.Number("t_s");
    if (!recording.truth.empty() && !(t_s > recording.truth.back().t_s)) {
      csv.Fail("t_s", fmt::format("time must increase from row to row (the previous row has t_s = {})",
                                  recording.truth.back().t_s));
    }
    recording.truth.push_back({t_s, Vec3(csv.Number("x_m"), csv.Number("y_m"), csv.Has("z_m") ? csv.Number("z_m") : 0.0)});
  }
  if (recording.truth.empty()) throw InputError(file + ": no truth rows (expected at least one row after the header)");
}

pipeline::Recording LoadRecording(const RecordingFiles& files) {
  pipeline::Recording recording;
  const std::string& data_file = files.pairwise_tdoa() ? files.tdoa : files.toa_stamps() ? files.toa : files.ranges;
  if (files.pairwise_tdoa()) {
    std::string also;
    for (const auto& [key, path] :
         {std::pair{"ranges", &files.ranges}, std::pair{"mics", &files.mics}, std::pair{"toa", &files.toa}}) {
      if (!path->empty()) also += fmt::format("{}{} {}", also.empty() ? "" : ", ", key, *path);
    }
    if (!also.empty()) {
      throw InputError(fmt::format("{}: a recording has either tdoa (pairwise time differences), ranges, or mics and toa, "
                                   "not several (also given: {})",
                                   files.tdoa, also));
    }
    ParseAnchors(ReadFile(files.anchors), files.anchors, "which a TDOA recording needs (its anchors are 3-D)",
                 recording);
    ParseTdoaCsv(ReadFile(files.tdoa), files.tdoa, recording);
  } else if (files.toa_stamps()) {
    ParseMicsCsv(ReadFile(files.mics), files.mics, recording);
    ParseToaCsv(ReadFile(files.toa), files.toa, recording);
  } else {
    ParseAnchorsCsv(ReadFile(files.anchors), files.anchors, recording);
    ParseRangesCsv(ReadFile(files.ranges), files.ranges, recording);
  }
  if (files.truth) {
    ParseTruthCsv(ReadFile(*files.truth), *files.truth, recording);
    const double first_s = recording.truth.front().t_s;
    const double last_s = recording.truth.back().t_s;
    for (const auto& step : recording.steps) {
      if (step.t_s < first_s || step.t_s > last_s) {
        throw InputError(fmt::format("{}: covers t_s in [{}, {}] s, but {} has a step at t_s = {} s", *files.truth,
                                     first_s, last_s, data_file, step.t_s));
      }
    }
  }
  return recording;
}

void WriteRecording(const std::string& dir, const pipeline::Recording& recording) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) throw InputError(dir + ": cannot create the directory (" + ec.message() + ")");
  if (recording.toa_stamps) {
    WriteStamps(dir, recording);
  } else {
    WriteAnchors(dir, recording);
    if (recording.tdoa) {
      WriteTdoa(dir, recording);
    } else {
      WriteRanges(dir, recording);
    }
  }
  if (recording.has_truth()) {
    const std::string path = dir + "/truth.csv";
    OutputFile out_file(path);
    auto& out = out_file.stream();
    out << (recording.truth_has_z ? "t_s,x_m,y_m,z_m\n" : "t_s,x_m,y_m\n");
    for (const auto& s : recording.truth) {
      out << fmt::format("{},{},{}", s.t_s, s.position_m.x(), s.position_m.y());
      if (recording.truth_has_z) out << fmt::format(",{}", s.position_m.z());
      out << "\n";
    }
    out_file.Commit();
  }
}

}  // namespace mirage::io
