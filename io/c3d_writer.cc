#include "io/c3d_writer.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <utility>
#include <vector>

#include "io/atomic_file.h"
#include "io/c3d_points.h"
#include "io/input_limits.h"

namespace mocapsolve {
namespace {

constexpr size_t kBlockBytes = 512;
constexpr std::uint8_t kC3dKey = 0x50;
constexpr std::uint8_t kIntelProcessor = 84;
// Keeps every parameter record's 16-bit next-record offset (signed) in range.
constexpr size_t kMaxParameterDataBytes = 32000;

void PutU16(std::string* out, size_t offset, std::uint16_t value) {
  (*out)[offset] = static_cast<char>(value & 0xff);
  (*out)[offset + 1] = static_cast<char>(value >> 8);
}

void PutFloat(std::string* out, size_t offset, float value) {
  std::uint32_t bits;
  std::memcpy(&bits, &value, 4);
  for (int i = 0; i < 4; ++i) (*out)[offset + i] = static_cast<char>((bits >> (8 * i)) & 0xff);
}

void AppendU16(std::string* out, std::uint16_t value) {
  out->push_back(static_cast<char>(value & 0xff));
  out->push_back(static_cast<char>(value >> 8));
}

void AppendFloat(std::string* out, float value) {
  out->append(4, '\0');
  PutFloat(out, out->size() - 4, value);
}

// Builds the parameter section: records linked by 16-bit offsets, the last one 0.
class ParameterSection {
 public:
  void Group(int id, const std::string& name) {
    Begin(-id, name);
    bytes_.push_back('\0');  // Empty description.
  }
  // An int16 scalar; values up to 65535 are stored as their unsigned bit pattern, as
  // C3D does for counts.
  void Int16(int group, const std::string& name, std::uint16_t value) {
    Begin(group, name);
    bytes_.push_back(2);
    bytes_.push_back(0);  // Scalar.
    AppendU16(&bytes_, value);
    bytes_.push_back('\0');
  }
  void Int16Array(int group, const std::string& name, const std::vector<std::uint16_t>& values) {
    Begin(group, name);
    bytes_.push_back(2);
    bytes_.push_back(1);
    bytes_.push_back(static_cast<char>(values.size()));
    for (std::uint16_t v : values) AppendU16(&bytes_, v);
    bytes_.push_back('\0');
  }
  void Float(int group, const std::string& name, float value) {
    Begin(group, name);
    bytes_.push_back(4);
    bytes_.push_back(0);
    AppendFloat(&bytes_, value);
    bytes_.push_back('\0');
  }
  // dims [width, count]; count <= 255, width * count <= kMaxParameterDataBytes.
  void Strings(int group, const std::string& name, const std::vector<std::string>& values,
               size_t begin, size_t end, size_t width) {
    Begin(group, name);
    bytes_.push_back(static_cast<char>(-1));
    bytes_.push_back(2);
    bytes_.push_back(static_cast<char>(width));
    bytes_.push_back(static_cast<char>(end - begin));
    for (size_t i = begin; i < end; ++i) {
      std::string padded = values[i];
      padded.resize(width, ' ');
      bytes_ += padded;
    }
    bytes_.push_back('\0');
  }
  // One string parameter (dims [length]).
  void String(int group, const std::string& name, const std::string& value) {
    Begin(group, name);
    bytes_.push_back(static_cast<char>(-1));
    bytes_.push_back(1);
    bytes_.push_back(static_cast<char>(value.size()));
    bytes_ += value;
    bytes_.push_back('\0');
  }

  // The section padded to whole blocks, with its 4-byte header.
  std::string Finish() {
    Link();
    if (last_link_ != std::string::npos) PutU16(&bytes_, last_link_, 0);
    std::string section;
    section.push_back(1);  // First parameter block (relative), by convention.
    section.push_back(static_cast<char>(kC3dKey));
    const size_t blocks = (4 + bytes_.size() + kBlockBytes - 1) / kBlockBytes;
    section.push_back(static_cast<char>(blocks));
    section.push_back(static_cast<char>(kIntelProcessor));
    section += bytes_;
    section.resize(blocks * kBlockBytes, '\0');
    return section;
  }

 private:
  void Begin(int group_id, const std::string& name) {
    Link();
    bytes_.push_back(static_cast<char>(name.size()));
    bytes_.push_back(static_cast<char>(static_cast<std::int8_t>(group_id)));
    bytes_ += name;
    last_link_ = bytes_.size();
    AppendU16(&bytes_, 0);  // Filled in when the next record starts.
  }
  // Points the previous record's link at the current end.
  void Link() {
    if (last_link_ != std::string::npos) {
      PutU16(&bytes_, last_link_, static_cast<std::uint16_t>(bytes_.size() - last_link_));
    }
  }

  std::string bytes_;
  size_t last_link_ = std::string::npos;
};

enum GroupId { kPoint = 1, kAnalog = 2, kTrial = 3, kSubjects = 4, kManufacturer = 5 };

void AddStrings(ParameterSection* section, int group, const std::string& base_name,
                const std::vector<std::string>& values, size_t width) {
  const size_t per_parameter = std::min<size_t>(255, kMaxParameterDataBytes / width);
  size_t begin = 0;
  int chunk = 1;
  do {
    const size_t end = std::min(values.size(), begin + per_parameter);
    section->Strings(group, chunk == 1 ? base_name : base_name + std::to_string(chunk), values,
                     begin, end, width);
    begin = end;
    ++chunk;
  } while (begin < values.size());
}

size_t MaxLength(const std::vector<std::string>& values) {
  size_t width = 1;
  for (const std::string& v : values) width = std::max(width, v.size());
  return width;
}

// The POINT parameters that list model outputs: ("ANGLES", labels), ...
using OutputLists = std::vector<std::pair<std::string, std::vector<std::string>>>;

// The markers followed by the model outputs, as one set of points; *lists gets the
// outputs' labels by kind (those of kind "" are recognised by name on reading).
MarkerTrajectories WithModelOutputs(const MarkerTrajectories& markers, OutputLists* lists) {
  const ModelOutputPoints& outputs = *markers.model_outputs;
  std::vector<std::string> labels = markers.labels();
  labels.insert(labels.end(), outputs.points.labels().begin(), outputs.points.labels().end());
  MarkerTrajectories all(std::move(labels), markers.num_frames());
  all.frame_rate = markers.frame_rate;
  all.unit = markers.unit;
  all.first_frame = markers.first_frame;
  all.subject_prefixes = markers.subject_prefixes;
  const int num_markers = markers.num_markers();
  for (int f = 0; f < markers.num_frames(); ++f) {
    for (int m = 0; m < all.num_markers(); ++m) {
      const MarkerTrajectories& from = m < num_markers ? markers : outputs.points;
      const int column = m < num_markers ? m : m - num_markers;
      if (!from.valid(f, column)) continue;
      all.SetSample(f, m, from.position(f, column), from.residual(f, column), from.camera_mask(f, column));
    }
  }
  for (const std::string& kind : C3dModelOutputKinds()) {
    std::vector<std::string> listed;
    for (size_t i = 0; i < outputs.kinds.size(); ++i) {
      if (outputs.kinds[i] == kind) listed.push_back(outputs.points.label(static_cast<int>(i)));
    }
    if (!listed.empty()) lists->emplace_back(kind, std::move(listed));
  }
  return all;
}

// With a sink, the bytes go to it in pieces of about 4 MB as they are made (a long take's
// file is not held whole); *bytes is then left empty.
Status EncodePoints(const MarkerTrajectories& trajectories, const OutputLists& output_lists,
                    const std::string& file_name, std::string* bytes, AtomicFileWriter* sink = nullptr) {
  const auto error = [&](const std::string& what) { return Status::Error(file_name + ": " + what); };
  const int num_markers = trajectories.num_markers();
  const int num_frames = trajectories.num_frames();
  if (num_markers > 65535) {
    return error(std::to_string(num_markers) + " markers; C3D holds at most 65535 points");
  }
  // What the readers accept (io/input_limits.h): a rate of 1e308 was stored as a float
  // inf (read back NaN), one of 1e-310 as 0.
  if (Status s = CheckMarkerBounds(trajectories); !s.ok()) return error(s.message());
  if (trajectories.first_frame < 0) {
    return error("first frame " + std::to_string(trajectories.first_frame) + " is negative");
  }
  for (const std::string& label : trajectories.labels()) {
    if (label.size() > 255) return error("label '" + label.substr(0, 32) + "...' is longer than 255 characters");
  }
  for (const std::string& prefix : trajectories.subject_prefixes) {
    if (prefix.size() > 255) return error("subject prefix longer than 255 characters");
  }
  const std::int64_t first = trajectories.first_frame;
  const std::int64_t last = first + num_frames - 1;
  if (last > 0xffffffffll) return error("last frame number does not fit in 32 bits");

  // Scale: see the header; the float value is what readers will use.
  double max_coordinate = 0.0, max_residual = 0.0;
  for (int f = 0; f < num_frames; ++f) {
    for (int m = 0; m < num_markers; ++m) {
      if (!trajectories.valid(f, m)) continue;
      const Eigen::Vector3d p = trajectories.position(f, m);
      max_coordinate = std::max(max_coordinate, p.cwiseAbs().maxCoeff());
      max_residual = std::max(max_residual, static_cast<double>(trajectories.residual(f, m)));
    }
  }
  double abs_scale = std::max(max_coordinate / 32000.0, max_residual / 255.0);
  if (!(abs_scale > 0.0)) abs_scale = 1.0;
  const float scale = -static_cast<float>(abs_scale);
  const double stored_abs_scale = -static_cast<double>(scale);

  ParameterSection parameters;
  parameters.Group(kPoint, "POINT");
  parameters.Int16(kPoint, "USED", static_cast<std::uint16_t>(num_markers));
  if (num_frames <= 65535) {
    parameters.Int16(kPoint, "FRAMES", static_cast<std::uint16_t>(num_frames));
  } else {
    parameters.Float(kPoint, "FRAMES", static_cast<float>(num_frames));
  }
  // DATA_START is filled in below, once the section size is known; reserve its slot by
  // building the section twice (the size does not depend on the value).
  const auto build = [&](std::uint16_t data_start) {
    ParameterSection p = parameters;
    p.Int16(kPoint, "DATA_START", data_start);
    p.Float(kPoint, "SCALE", scale);
    p.Float(kPoint, "RATE", static_cast<float>(trajectories.frame_rate));
    if (trajectories.unit.name != "unknown" && !trajectories.unit.name.empty()) {
      p.String(kPoint, "UNITS", trajectories.unit.name.substr(0, 255));
    }
    AddStrings(&p, kPoint, "LABELS", trajectories.labels(), MaxLength(trajectories.labels()));
    for (const auto& [kind, labels] : output_lists) AddStrings(&p, kPoint, kind, labels, MaxLength(labels));
    p.Group(kAnalog, "ANALOG");
    p.Int16(kAnalog, "USED", 0);
    p.Float(kAnalog, "RATE", static_cast<float>(trajectories.frame_rate));
    p.Group(kTrial, "TRIAL");
    p.Int16Array(kTrial, "ACTUAL_START_FIELD",
                 {static_cast<std::uint16_t>(first & 0xffff), static_cast<std::uint16_t>(first >> 16)});
    p.Int16Array(kTrial, "ACTUAL_END_FIELD",
                 {static_cast<std::uint16_t>(std::max<std::int64_t>(last, 0) & 0xffff),
                  static_cast<std::uint16_t>(std::max<std::int64_t>(last, 0) >> 16)});
    p.Float(kTrial, "CAMERA_RATE", static_cast<float>(trajectories.frame_rate));
    std::vector<std::string> prefixes, names;
    for (const std::string& prefix : trajectories.subject_prefixes) {
      if (prefix.empty()) continue;
      prefixes.push_back(prefix);
      names.push_back(prefix.back() == ':' ? prefix.substr(0, prefix.size() - 1) : prefix);
    }
    if (!prefixes.empty()) {
      p.Group(kSubjects, "SUBJECTS");
      p.Int16(kSubjects, "USES_PREFIXES", 1);
      p.Int16(kSubjects, "USED", static_cast<std::uint16_t>(prefixes.size()));
      AddStrings(&p, kSubjects, "LABEL_PREFIXES", prefixes, MaxLength(prefixes));
      AddStrings(&p, kSubjects, "NAMES", names, MaxLength(names));
    }
    p.Group(kManufacturer, "MANUFACTURER");
    p.String(kManufacturer, "SOFTWARE", "mocapsolve");
    return p.Finish();
  };
  std::string section = build(0);
  const size_t parameter_blocks = section.size() / kBlockBytes;
  if (parameter_blocks > 255) return error("parameter section exceeds 255 blocks");
  const size_t data_start = 2 + parameter_blocks;
  if (data_start > 65535) return error("data start block does not fit in 16 bits");
  section = build(static_cast<std::uint16_t>(data_start));

  std::string out(kBlockBytes, '\0');
  out[0] = 2;  // Parameter section starts at block 2.
  out[1] = static_cast<char>(kC3dKey);
  PutU16(&out, 2, static_cast<std::uint16_t>(num_markers));
  PutU16(&out, 4, 0);  // No analog data.
  // Header frame numbers are 16-bit; TRIAL:ACTUAL_*_FIELD hold the full values.
  const std::int64_t header_first = num_frames == 0 ? std::max<std::int64_t>(first, 1) : first;
  PutU16(&out, 6, static_cast<std::uint16_t>(std::min<std::int64_t>(header_first, 65535)));
  PutU16(&out, 8, static_cast<std::uint16_t>(std::clamp<std::int64_t>(header_first + num_frames - 1, 0, 65535)));
  PutU16(&out, 10, 0);  // Max interpolation gap.
  PutFloat(&out, 12, scale);
  PutU16(&out, 16, static_cast<std::uint16_t>(data_start));
  PutU16(&out, 18, 0);  // Analog samples per frame.
  PutFloat(&out, 20, static_cast<float>(trajectories.frame_rate));
  PutU16(&out, 298, 12345);  // Word 150: supports 4-character event labels; 0 events.
  out += section;

  constexpr size_t kPiece = size_t{1} << 22;
  if (sink == nullptr) out.reserve(out.size() + static_cast<size_t>(num_frames) * num_markers * 16 + kBlockBytes);
  size_t sent = 0;  // Bytes given to the sink.
  for (int f = 0; f < num_frames; ++f) {
    if (sink != nullptr && out.size() >= kPiece) {
      if (Status status = sink->Append(out); !status.ok()) return status;
      sent += out.size();
      out.clear();
    }
    for (int m = 0; m < num_markers; ++m) {
      if (!trajectories.valid(f, m)) {
        for (int k = 0; k < 3; ++k) AppendFloat(&out, 0.0f);
        AppendFloat(&out, -1.0f);
        continue;
      }
      const Eigen::Vector3d p = trajectories.position(f, m);
      for (int k = 0; k < 3; ++k) AppendFloat(&out, static_cast<float>(p[k]));
      const double residual_units = std::round(trajectories.residual(f, m) / stored_abs_scale);
      const int residual_byte = static_cast<int>(std::clamp(residual_units, 0.0, 255.0));
      const int word = (trajectories.camera_mask(f, m) & 0x7f) << 8 | residual_byte;
      AppendFloat(&out, static_cast<float>(word));
    }
  }
  const size_t total = sent + out.size();
  out.resize(out.size() + (total + kBlockBytes - 1) / kBlockBytes * kBlockBytes - total, '\0');
  if (sink != nullptr) {
    bytes->clear();
    return sink->Append(out);
  }
  *bytes = std::move(out);
  return Status::Ok();
}

// EncodeC3d, into the sink when given (see EncodePoints).
Status Encode(const MarkerTrajectories& trajectories, const std::string& file_name, std::string* bytes,
              AtomicFileWriter* sink) {
  const ModelOutputPoints* outputs = trajectories.model_outputs.get();
  if (outputs == nullptr || outputs->points.num_markers() == 0 ||
      outputs->points.num_frames() != trajectories.num_frames()) {
    return EncodePoints(trajectories, {}, file_name, bytes, sink);
  }
  OutputLists lists;
  const MarkerTrajectories all = WithModelOutputs(trajectories, &lists);
  return EncodePoints(all, lists, file_name, bytes, sink);
}

}  // namespace

Status EncodeC3d(const MarkerTrajectories& trajectories, const std::string& file_name,
                 std::string* bytes) {
  return Encode(trajectories, file_name, bytes, nullptr);
}

Status WriteC3d(const std::string& path, const MarkerTrajectories& trajectories) {
  // Written in pieces as it is encoded (AtomicFileWriter): the same bytes, not held whole.
  AtomicFileWriter writer;
  Status status = writer.Open(path);
  std::string none;
  if (status.ok()) status = Encode(trajectories, path, &none, &writer);
  if (status.ok()) status = writer.Close();
  return status;
}

}  // namespace mocapsolve
