#include "io/c3d_reader.h"

#include <algorithm>
#include <cctype>
#include <climits>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <memory>
#include <utility>
#include <vector>

#include "io/atomic_file.h"
#include "io/c3d_points.h"
#include "io/input_limits.h"
#include "kinematics/quote_token.h"

namespace mocapsolve {
namespace {

constexpr std::uint64_t kBlockBytes = 512;
constexpr std::uint8_t kC3dKey = 0x50;  // Header byte 1 of every C3D file.

// Scalar decoding in the file's processor format. Callers check the bounds.
class Decoder {
 public:
  Decoder(std::string_view bytes, C3dProcessor processor)
      : bytes_(bytes), processor_(processor) {}

  std::uint16_t U16(std::uint64_t offset) const {
    unsigned char b[2];
    std::memcpy(b, bytes_.data() + offset, 2);
    if (processor_ == C3dProcessor::kSgiMips) return static_cast<std::uint16_t>(b[0] << 8 | b[1]);
    return static_cast<std::uint16_t>(b[1] << 8 | b[0]);
  }
  std::int16_t I16(std::uint64_t offset) const { return static_cast<std::int16_t>(U16(offset)); }

  float F32(std::uint64_t offset) const {
    unsigned char b[4];
    std::memcpy(b, bytes_.data() + offset, 4);
    std::uint32_t bits = 0;
    switch (processor_) {
      case C3dProcessor::kIntel:
        bits = std::uint32_t{b[3]} << 24 | std::uint32_t{b[2]} << 16 | std::uint32_t{b[1]} << 8 | b[0];
        break;
      case C3dProcessor::kSgiMips:
        bits = std::uint32_t{b[0]} << 24 | std::uint32_t{b[1]} << 16 | std::uint32_t{b[2]} << 8 | b[3];
        break;
      case C3dProcessor::kDec:
        // VAX F-float: the 16-bit words are swapped relative to little-endian IEEE and
        // the exponent bias is 2 higher, hence the division by 4.
        bits = std::uint32_t{b[1]} << 24 | std::uint32_t{b[0]} << 16 | std::uint32_t{b[3]} << 8 | b[2];
        break;
    }
    float value;
    std::memcpy(&value, &bits, 4);
    return processor_ == C3dProcessor::kDec ? value / 4.0f : value;
  }

 private:
  std::string_view bytes_;
  C3dProcessor processor_;
};

struct Parameter {
  std::string group;  // Upper case; "#<id>" when the group record is missing.
  std::string name;   // Upper case.
  int type = 0;       // -1 char, 1 byte, 2 int16, 4 float.
  std::vector<int> dims;
  std::uint64_t data_offset = 0;  // File offset of the values.
  std::uint64_t count = 0;        // Number of values (product of dims; 1 for a scalar).
  std::uint64_t record_offset = 0;
};

std::string Upper(std::string_view s) {
  std::string out(s);
  for (char& c : out) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return out;
}

// A name from the file, safe to put in a one-line message.
std::string Printable(std::string_view s) {
  std::string out;
  for (char c : s.substr(0, 32)) out += std::isprint(static_cast<unsigned char>(c)) ? c : '?';
  return out;
}

std::string Trim(std::string_view s) {
  const auto blank = [](char c) { return c == ' ' || c == '\0' || c == '\t' || c == '\r' || c == '\n'; };
  size_t begin = 0, end = s.size();
  while (begin < end && blank(s[begin])) ++begin;
  while (end > begin && blank(s[end - 1])) --end;
  return std::string(s.substr(begin, end - begin));
}

class C3dParser {
 public:
  C3dParser(std::string_view bytes, const std::string& file_name, const C3dReadOptions& options)
      : bytes_(bytes), file_(file_name), options_(options), decoder_(bytes, C3dProcessor::kIntel) {}

  Status Parse(MarkerTrajectories* trajectories, C3dFileInfo* info);

 private:
  struct FrameLayout {
    std::int64_t first = 0, last = 0, count = 0;
    int analog_values = 0, analog_channels = 0;
  };
  // The header's key byte and parameter block, and the processor type the parameter
  // section names (which decodes every number after it).
  Status ParseHeader(int* parameter_block, C3dProcessor* processor) const;
  // One point's x, y, z and residual word (as int16; negative = invalid) at `offset`.
  void DecodePoint(std::uint64_t offset, bool float_storage, double scale, Eigen::Vector3d* position,
                   int* residual_word) const;
  Status FrameRate(double* rate) const;
  Status DataStart(int parameter_block, std::uint64_t* block, std::uint64_t* offset) const;
  Status ParseFrameLayout(int num_points, bool float_storage, std::uint64_t data_offset,
                          std::uint64_t data_start_block, FrameLayout* layout) const;
  Status Error(const std::string& where, const std::string& what) const {
    return Status::Error(file_ + ": " + where + ": " + what);
  }
  Status ParseParameters(std::uint64_t section_offset);
  const Parameter* Find(const std::string& group, const std::string& name) const;
  // First value of a numeric parameter; int16 read as unsigned when is_count.
  bool Number(const Parameter* p, bool is_count, double* value) const;
  // A count parameter (POINT:USED, POINT:DATA_START, ANALOG:USED): *present tells whether
  // the file has it. A float one can hold anything, so it must be a whole number 0..65535
  // (what the 16-bit integer form holds); anything else is an error naming it.
  Status Count(const std::string& group, const std::string& name, bool* present,
               double* value) const;
  std::vector<std::string> Strings(const Parameter* p) const;
  // A string list that may go on in NAME2, NAME3, ... (POINT:LABELS, POINT:ANGLES);
  // *present tells whether NAME exists.
  std::vector<std::string> StringChunks(const std::string& group, const std::string& name,
                                        bool* present = nullptr) const;
  // The labels (blank ones named "*<n>") and the point selection of c3d_points.h.
  Status SelectPoints(int num_points, C3dPointSelection* selection) const;

  std::string_view bytes_;
  std::string file_;
  C3dReadOptions options_;
  Decoder decoder_;
  std::vector<Parameter> parameters_;
};

Status C3dParser::ParseParameters(std::uint64_t section_offset) {
  const std::uint64_t size = bytes_.size();
  std::vector<std::pair<int, std::string>> groups;  // id -> name
  std::vector<int> group_ids;                         // Parallel to parameters_.
  std::uint64_t p = section_offset + 4;
  while (true) {
    const std::string where = "parameter record at offset " + std::to_string(p);
    if (p + 2 > size) return Error(where, "parameter section runs past the end of the file");
    const int name_length = std::abs(static_cast<int>(static_cast<std::int8_t>(bytes_[p])));
    const int group_id = static_cast<std::int8_t>(bytes_[p + 1]);
    if (name_length == 0) break;  // End of the section.
    const std::uint64_t link = p + 2 + name_length;  // The 16-bit offset to the next record.
    if (link + 2 > size) return Error(where, "record runs past the end of the file");
    const std::string name = Upper(std::string_view(bytes_.data() + p + 2, name_length));
    const std::string shown = Printable(name);
    const int next = decoder_.I16(link);
    const std::uint64_t body = link + 2;
    if (group_id < 0) {
      groups.emplace_back(-group_id, name);
    } else if (group_id > 0) {
      if (body + 2 > size) return Error(where, "parameter " + QuoteToken(shown) + " runs past the end of the file");
      Parameter parameter;
      parameter.name = name;
      parameter.record_offset = p;
      parameter.type = static_cast<std::int8_t>(bytes_[body]);
      const int num_dims = static_cast<unsigned char>(bytes_[body + 1]);
      if (parameter.type != -1 && parameter.type != 1 && parameter.type != 2 && parameter.type != 4) {
        return Error(where, "parameter " + QuoteToken(shown) + " has data type " +
                                std::to_string(parameter.type) + ", expected -1, 1, 2 or 4");
      }
      if (body + 2 + num_dims > size) return Error(where, "parameter " + QuoteToken(shown) + " runs past the end of the file");
      parameter.count = 1;
      for (int d = 0; d < num_dims; ++d) {
        const int dim = static_cast<unsigned char>(bytes_[body + 2 + d]);
        parameter.dims.push_back(dim);
        parameter.count *= dim;  // At most 255^255 in theory: checked against size below.
        if (parameter.count > size) break;
      }
      parameter.data_offset = body + 2 + num_dims;
      const std::uint64_t data_bytes = parameter.count * std::abs(parameter.type);
      if (parameter.count > size || parameter.data_offset + data_bytes > size) {
        return Error(where, "parameter " + QuoteToken(shown) + " values run past the end of the file");
      }
      parameters_.push_back(std::move(parameter));
      group_ids.push_back(group_id);
    }
    if (next == 0) break;  // Last record.
    if (next < 0) {
      return Error(where, "next-record offset " + std::to_string(next) + " points backwards");
    }
    p = link + next;  // Strictly forward, so the loop ends.
  }
  for (size_t i = 0; i < parameters_.size(); ++i) {
    parameters_[i].group = "#" + std::to_string(group_ids[i]);
    for (const auto& [id, name] : groups) {
      if (id == group_ids[i]) parameters_[i].group = name;
    }
  }
  return Status::Ok();
}

const Parameter* C3dParser::Find(const std::string& group, const std::string& name) const {
  for (const Parameter& p : parameters_) {
    if (p.group == group && p.name == name) return &p;
  }
  return nullptr;
}

// A parameter's number as written: whole numbers without a fraction, others to 6 digits.
std::string NumberText(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", value);
  return text;
}

bool C3dParser::Number(const Parameter* p, bool is_count, double* value) const {
  if (p == nullptr || p->count == 0) return false;
  switch (p->type) {
    case 1: *value = static_cast<unsigned char>(bytes_[p->data_offset]); return true;
    case 2:
      *value = is_count ? decoder_.U16(p->data_offset) : decoder_.I16(p->data_offset);
      return true;
    case 4: *value = decoder_.F32(p->data_offset); return std::isfinite(*value);
    default: return false;
  }
}

Status C3dParser::Count(const std::string& group, const std::string& name, bool* present,
                        double* value) const {
  const Parameter* p = Find(group, name);
  *present = p != nullptr && p->count > 0 && (p->type == 1 || p->type == 2 || p->type == 4);
  if (!*present) return Status::Ok();
  if (p->type == 4) *value = decoder_.F32(p->data_offset);
  else Number(p, /*is_count=*/true, value);
  if (!(*value >= 0.0 && *value <= 65535.0) || *value != std::floor(*value)) {
    return Error(group + ":" + name, NumberText(*value) + " is not a count (a whole number 0-65535)");
  }
  return Status::Ok();
}

std::vector<std::string> C3dParser::Strings(const Parameter* p) const {
  std::vector<std::string> out;
  if (p == nullptr || p->type != -1) return out;
  const std::uint64_t width = p->dims.empty() ? p->count : p->dims[0];
  if (width == 0) return out;
  for (std::uint64_t i = 0; i < p->count; i += width) {
    out.push_back(Trim(bytes_.substr(p->data_offset + i, width)));
  }
  return out;
}

std::vector<std::string> C3dParser::StringChunks(const std::string& group, const std::string& name,
                                                 bool* present) const {
  std::vector<std::string> out;
  if (present != nullptr) *present = Find(group, name) != nullptr;
  for (int chunk = 1;; ++chunk) {
    const Parameter* p = Find(group, chunk == 1 ? name : name + std::to_string(chunk));
    if (p == nullptr) break;
    for (std::string& value : Strings(p)) out.push_back(std::move(value));
  }
  return out;
}

Status C3dParser::SelectPoints(int num_points, C3dPointSelection* selection) const {
  C3dPointLists lists;
  lists.labels = StringChunks("POINT", "LABELS");  // LABELS, LABELS2, ... (> 255 points).
  lists.labels.resize(num_points);
  for (int m = 0; m < num_points; ++m) {
    if (lists.labels[m].empty()) lists.labels[m] = "*" + std::to_string(m + 1);
  }
  for (std::string& prefix : Strings(Find("SUBJECTS", "LABEL_PREFIXES"))) {
    if (!prefix.empty()) lists.subject_prefixes.push_back(std::move(prefix));
  }
  lists.subject_names = Strings(Find("SUBJECTS", "NAMES"));
  for (const std::string& kind : C3dModelOutputKinds()) {
    bool present = false;
    std::vector<std::string> labels = StringChunks("POINT", kind, &present);
    if (present) lists.output_lists.emplace_back(kind, std::move(labels));
  }
  Status status = SelectC3dPoints(lists, options_.subject_prefix, options_.include_model_outputs, selection,
                                  options_.preferred_subject_prefix);
  return status.ok() ? status : Status::Error(file_ + ": " + status.message());
}

// The frame rate: POINT:RATE when present (it must then be valid itself: NaN, 0 or -120
// is an error naming it, not a silent fallback), else header words 11-12; within
// io/input_limits.h's bounds either way.
Status C3dParser::FrameRate(double* rate) const {
  double value = 0.0;
  *rate = decoder_.F32(20);
  std::string rate_field = "header words 11-12 (frame rate)";
  if (const Parameter* point_rate = Find("POINT", "RATE"); point_rate != nullptr) {
    *rate = Number(point_rate, false, &value) ? value : std::nan("");  // Number: finite only.
    rate_field = "POINT:RATE";
  }
  if (!(*rate > 0.0) || !std::isfinite(*rate)) {
    return Error(rate_field, "frame rate " + ShortNumber(*rate) + " is not a positive number");
  }
  if (Status s = CheckFrameRate(*rate, "frame rate"); !s.ok()) return Error(rate_field, s.message());
  return Status::Ok();
}

// The data start: POINT:DATA_START when present, else header word 9; after the
// parameter section and within the file. *offset is its byte offset.
Status C3dParser::DataStart(int parameter_block, std::uint64_t* block, std::uint64_t* offset) const {
  bool present = false;
  double value = 0.0;
  std::uint64_t data_start_block = decoder_.U16(16);
  std::string data_start_field = "header word 9 (data start)";
  if (Status s = Count("POINT", "DATA_START", &present, &value); !s.ok()) return s;
  if (present) {
    data_start_block = static_cast<std::uint64_t>(value);
    data_start_field = "POINT:DATA_START";
  }
  if (data_start_block <= static_cast<std::uint64_t>(parameter_block)) {
    return Error(data_start_field, "data start block " + std::to_string(data_start_block) +
                                       " is not after the parameter section (block " +
                                       std::to_string(parameter_block) + ")");
  }
  const std::uint64_t data_offset = (data_start_block - 1) * kBlockBytes;
  if (data_offset > bytes_.size()) {
    return Error(data_start_field, "data start block " + std::to_string(data_start_block) +
                                       " (byte " + std::to_string(data_offset) +
                                       ") is beyond the end of the file (" +
                                       std::to_string(bytes_.size()) + " bytes)");
  }
  *block = data_start_block;
  *offset = data_offset;
  return Status::Ok();
}

// The frames: first and last (header words 4-5, or the 32-bit TRIAL fields beyond
// 65535), their count bounded by kMaxFrames and by the bytes after the data start, and
// the analog values per frame that share those bytes.
Status C3dParser::ParseFrameLayout(int num_points, bool float_storage, std::uint64_t data_offset,
                                   std::uint64_t data_start_block, FrameLayout* layout) const {
  std::int64_t first = decoder_.U16(6), last = decoder_.U16(8);
  std::string frames_field = "header words 4-5 (first/last frame)";
  const Parameter* start_field = Find("TRIAL", "ACTUAL_START_FIELD");
  const Parameter* end_field = Find("TRIAL", "ACTUAL_END_FIELD");
  if (start_field && end_field && start_field->type == 2 && end_field->type == 2 &&
      start_field->count >= 2 && end_field->count >= 2) {
    const auto field32 = [&](const Parameter* p) {
      return std::int64_t{decoder_.U16(p->data_offset)} +
             (std::int64_t{decoder_.U16(p->data_offset + 2)} << 16);
    };
    const std::int64_t trial_first = field32(start_field), trial_last = field32(end_field);
    if (trial_first > 65535 || trial_last > 65535) {  // Beyond what the header holds.
      first = trial_first;
      last = trial_last;
      frames_field = "TRIAL:ACTUAL_START_FIELD/ACTUAL_END_FIELD";
    }
  }
  const std::int64_t num_frames = last - first + 1;
  if (num_frames < 0 || num_frames > INT_MAX) {
    return Error(frames_field, "first frame " + std::to_string(first) + ", last frame " +
                                   std::to_string(last) + " give no valid frame count");
  }
  // The data bounds the count below, unless frames take no bytes (no points, no analog):
  // then only this does, or a 1 KB file could ask for 2^31 frames.
  if (num_frames > kMaxFrames) {
    return Error(frames_field, "frames " + std::to_string(first) + ".." + std::to_string(last) + " (" +
                                   std::to_string(num_frames) + ") are more than the " +
                                   std::to_string(kMaxFrames) + " a take may have");
  }
  // Analog samples are skipped, but they set the frame size: a header count that is not
  // a whole number of samples of ANALOG:USED channels means header and parameters
  // disagree about the layout.
  const int analog_values = decoder_.U16(4);
  int analog_channels = 0;
  bool present = false;
  double value = 0.0;
  if (Status s = Count("ANALOG", "USED", &present, &value); !s.ok()) return s;
  if (present) analog_channels = static_cast<int>(value);
  if (analog_channels > 0 && analog_values % analog_channels != 0) {
    return Error("header word 3 (analog values per frame)",
                 std::to_string(analog_values) + " is not a multiple of ANALOG:USED " +
                     std::to_string(analog_channels));
  }
  const std::uint64_t word_bytes = float_storage ? 4 : 2;
  const std::uint64_t frame_bytes = (4ull * num_points + analog_values) * word_bytes;
  const std::uint64_t available = bytes_.size() - data_offset;
  if (frame_bytes > 0 && static_cast<std::uint64_t>(num_frames) > available / frame_bytes) {
    return Error(frames_field,
                 "frames " + std::to_string(first) + ".." + std::to_string(last) + " (" +
                     std::to_string(num_frames) + " x " + std::to_string(frame_bytes) +
                     " bytes) do not fit in the " + std::to_string(available) +
                     " bytes after data start block " + std::to_string(data_start_block) +
                     " (room for " + std::to_string(available / frame_bytes) + " frames)");
  }

  *layout = {first, last, num_frames, analog_values, analog_channels};
  return Status::Ok();
}

Status C3dParser::ParseHeader(int* parameter_block_out, C3dProcessor* processor) const {
  const std::uint64_t size = bytes_.size();
  if (size < kBlockBytes) {
    return Error("header", "file is " + std::to_string(size) +
                              " bytes, shorter than the 512-byte C3D header");
  }
  if (static_cast<std::uint8_t>(bytes_[1]) != kC3dKey) {
    char found[8];
    std::snprintf(found, sizeof found, "0x%02x", static_cast<unsigned>(static_cast<std::uint8_t>(bytes_[1])));
    return Error("header byte 1", std::string("not a C3D file (") + found + ", expected 0x50)");
  }
  const int parameter_block = static_cast<std::uint8_t>(bytes_[0]);
  const std::uint64_t section = (static_cast<std::uint64_t>(parameter_block) - 1) * kBlockBytes;
  if (parameter_block < 2) {
    return Error("header byte 0", "parameter section block " + std::to_string(parameter_block) +
                                      " is invalid (block 1 is the header)");
  }
  if (section + 4 > size) {
    return Error("header byte 0", "parameter section block " + std::to_string(parameter_block) +
                                      " starts beyond the end of the file (" +
                                      std::to_string(size) + " bytes)");
  }
  const int processor_byte = static_cast<std::uint8_t>(bytes_[section + 3]);
  if (processor_byte < 84 || processor_byte > 86) {
    return Error("parameter section byte " + std::to_string(section + 3) + " (processor type)",
                 std::to_string(processor_byte) +
                     " is not 84 (Intel), 85 (DEC) or 86 (SGI/MIPS)");
  }
  *parameter_block_out = parameter_block;
  *processor = static_cast<C3dProcessor>(processor_byte);
  return Status::Ok();
}

void C3dParser::DecodePoint(std::uint64_t offset, bool float_storage, double scale, Eigen::Vector3d* position,
                            int* residual_word) const {
  if (float_storage) {
    for (int k = 0; k < 3; ++k) (*position)[k] = decoder_.F32(offset + 4 * k);
    const double r = std::trunc(decoder_.F32(offset + 12));
    if (!(r >= 0.0)) {  // Negative or NaN.
      *residual_word = -1;
    } else {
      // Low 16 bits of the integer, as int16 (65535.0 -> -1).
      const auto bits = static_cast<std::uint32_t>(std::min(r, 4294967295.0));
      *residual_word = static_cast<std::int16_t>(static_cast<std::uint16_t>(bits & 0xffffu));
    }
  } else {
    for (int k = 0; k < 3; ++k) (*position)[k] = decoder_.I16(offset + 2 * k) * scale;
    *residual_word = decoder_.I16(offset + 6);
  }
}

Status C3dParser::Parse(MarkerTrajectories* trajectories, C3dFileInfo* info) {
  int parameter_block = 0;
  C3dProcessor processor;
  Status status = ParseHeader(&parameter_block, &processor);
  if (!status.ok()) return status;
  decoder_ = Decoder(bytes_, processor);
  status = ParseParameters((static_cast<std::uint64_t>(parameter_block) - 1) * kBlockBytes);
  if (!status.ok()) return status;

  // Points per frame.
  const int num_points = decoder_.U16(2);
  double value;
  bool present;
  if (Status s = Count("POINT", "USED", &present, &value); !s.ok()) return s;
  if (present && value != num_points) {
    return Error("POINT:USED", NumberText(value) + " disagrees with the header's point count " +
                                   std::to_string(num_points));
  }
  // Storage: the sign of POINT:SCALE.
  double scale = decoder_.F32(12);
  if (Number(Find("POINT", "SCALE"), false, &value)) scale = value;
  if (!std::isfinite(scale) || scale == 0.0) {
    return Error("POINT:SCALE", "scale " + ShortNumber(scale) +
                                    " is zero or not finite (its sign selects int or float storage)");
  }
  const bool float_storage = scale < 0.0;
  const double abs_scale = std::abs(scale);
  double rate = 0.0;
  if (Status s = FrameRate(&rate); !s.ok()) return s;

  std::uint64_t data_start_block = 0, data_offset = 0;
  if (Status s = DataStart(parameter_block, &data_start_block, &data_offset); !s.ok()) return s;

  FrameLayout frames;
  if (Status s = ParseFrameLayout(num_points, float_storage, data_offset, data_start_block, &frames); !s.ok()) {
    return s;
  }
  const std::int64_t first = frames.first, num_frames = frames.count;
  const int analog_values = frames.analog_values, analog_channels = frames.analog_channels;
  const std::uint64_t word_bytes = float_storage ? 4 : 2;

  // Labels and which points are markers (c3d_points.h).
  C3dPointSelection selection;
  if (Status s = SelectPoints(num_points, &selection); !s.ok()) return s;
  std::vector<std::string> marker_labels, output_labels, output_kinds;
  std::vector<std::pair<int, int>> target(num_points, {-1, -1});  // (0 marker / 1 output, column).
  for (int m = 0; m < num_points; ++m) {
    if (selection.roles[m] == C3dPointSelection::Role::kMarker) {
      target[m] = {0, static_cast<int>(marker_labels.size())};
      marker_labels.push_back(selection.labels[m]);
    } else if (selection.roles[m] == C3dPointSelection::Role::kModelOutput) {
      target[m] = {1, static_cast<int>(output_labels.size())};
      output_labels.push_back(selection.labels[m]);
      output_kinds.push_back(selection.kinds[m]);
    }
  }
  for (const auto* labels : {&marker_labels, &output_labels}) {
    if (Status status = MarkerTrajectories::CheckLabels(*labels); !status.ok()) {
      return Error("POINT:LABELS", status.message());
    }
  }
  const int read_frames = options_.header_only ? 0 : static_cast<int>(num_frames);
  MarkerTrajectories out(std::move(marker_labels), read_frames);
  MarkerTrajectories outputs(std::move(output_labels), read_frames);
  out.frame_rate = outputs.frame_rate = rate;
  out.first_frame = outputs.first_frame = static_cast<int>(std::min<std::int64_t>(first, INT_MAX));
  const std::vector<std::string> units = Strings(Find("POINT", "UNITS"));
  out.unit = outputs.unit = LengthUnitFromName(units.empty() ? "" : units[0]);
  out.subject_prefixes = std::move(selection.subject_prefixes);

  C3dFileInfo found;
  found.processor = processor;
  found.float_storage = float_storage;
  found.point_scale = scale;
  found.parameter_block = parameter_block;
  found.data_start_block = static_cast<int>(data_start_block);
  found.analog_values_per_frame = analog_values;
  found.analog_channels = analog_channels;
  found.frames = static_cast<int>(num_frames);
  found.model_output_points = selection.num_model_outputs;
  found.other_subject_points = selection.num_dropped;
  for (const std::string& warning : selection.warnings) found.warnings.push_back(file_ + ": " + warning);

  std::uint64_t offset = data_offset;
  // Without points there is nothing to decode (and the frame count may be 2^31).
  for (int f = 0; num_points > 0 && f < read_frames; ++f) {
    for (int m = 0; m < num_points; ++m, offset += 4 * word_bytes) {
      if (target[m].first < 0) continue;  // A point of another subject.
      MarkerTrajectories& into = target[m].first == 0 ? out : outputs;
      const int column = target[m].second;
      const bool is_marker = target[m].first == 0;
      Eigen::Vector3d position;
      int residual_word;  // As int16; negative = invalid.
      DecodePoint(offset, float_storage, scale, &position, &residual_word);
      if (residual_word < 0 || !position.allFinite()) {
        found.negative_residual_samples += is_marker;
        continue;  // Already missing.
      }
      if (position.cwiseAbs().maxCoeff() > MarkerTrajectories::kMaxCoordinate) {
        return Error("POINT data", "frame " + std::to_string(f + 1) + ", marker " +
                                       QuoteToken(into.label(column)) + ": coordinate " +
                                       ShortNumber(position.cwiseAbs().maxCoeff()) + " beyond +-1e9");
      }
      if (options_.zero_position_is_missing && (position.array() == 0.0).all()) {
        found.zero_position_samples += is_marker;
        continue;
      }
      into.SetSample(f, column, position, static_cast<float>((residual_word & 0xff) * abs_scale),
                     static_cast<std::uint8_t>((residual_word >> 8) & 0x7f));
    }
    offset += analog_values * word_bytes;  // Analog samples are not read.
  }
  if (outputs.num_markers() > 0) {
    auto kept = std::make_shared<ModelOutputPoints>();
    kept->kinds = std::move(output_kinds);
    kept->points = std::move(outputs);
    out.model_outputs = std::move(kept);
  }
  *trajectories = std::move(out);
  if (info != nullptr) *info = std::move(found);
  return Status::Ok();
}

}  // namespace

Status ParseC3d(std::string_view bytes, const std::string& file_name,
                MarkerTrajectories* trajectories, C3dFileInfo* info,
                const C3dReadOptions& options) {
  return C3dParser(bytes, file_name, options).Parse(trajectories, info);
}

Status ReadC3d(const std::string& path, MarkerTrajectories* trajectories, C3dFileInfo* info,
               const C3dReadOptions& options) {
  std::string bytes;
  Status status = ReadFileToString(path, &bytes);
  if (!status.ok()) return status;
  return ParseC3d(bytes, path, trajectories, info, options);
}

}  // namespace mocapsolve
