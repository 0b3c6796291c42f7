#include "io/fbx_binary.h"

#include <cstring>
#include <limits>

#include <zlib.h>

namespace mocapsolve::fbx {
namespace {

static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__,
              "the FBX encoder copies arrays as they are in memory (little-endian)");

constexpr char kMagic[] = "Kaydara FBX Binary  \x00\x1a\x00";  // 23 bytes.
constexpr size_t kMagicSize = 23;
constexpr size_t kNullRecordSize = 13;  // FBX < 7500: three uint32 and a uint8.
constexpr size_t kCompressAbove = 128;  // Array bytes (Blender's and the FBX converter's rule).

constexpr unsigned char kFileId[16] = {0x28, 0xb3, 0x2a, 0xeb, 0xb6, 0x24, 0xcc, 0xc2,
                                       0xbf, 0xc8, 0xb0, 0x2a, 0xa9, 0x2b, 0xfc, 0xf1};
constexpr unsigned char kFooterId[16] = {0xfa, 0xbc, 0xab, 0x09, 0xd0, 0xc8, 0xd4, 0x66,
                                         0xb1, 0x76, 0xfb, 0x83, 0x1c, 0xf7, 0x26, 0x7e};
constexpr unsigned char kFooterMagic[16] = {0xf8, 0x5a, 0x8c, 0x6a, 0xde, 0xf5, 0xd9, 0x7e,
                                            0xec, 0xe9, 0x0c, 0xe3, 0x75, 0x8f, 0x29, 0x0b};
constexpr char kCreationTime[] = "1970-01-01 10:00:00:000";

template <typename T>
void Append(std::string* out, T value) {
  char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
  out->append(bytes, sizeof(T));
}

bool AlwaysClosed(const std::string& name) {  // Records the SDK closes with a null record.
  return name == "AnimationStack" || name == "AnimationLayer";
}

// Whether a null record closes `node` (see the header).
bool Closed(const Node& node, bool is_last) {
  return !node.children().empty() || (node.num_properties() == 0 && !is_last) || AlwaysClosed(node.name());
}

Status CheckNames(const Node& node) {
  if (node.name().size() > 255) return Status::Error("FBX record name over 255 bytes: " + node.name().substr(0, 40));
  for (const auto& child : node.children()) {
    if (Status s = CheckNames(*child); !s.ok()) return s;
  }
  return Status::Ok();
}

// The bytes `node` takes in the file, its children and closing null record included.
uint64_t EncodedSize(const Node& node, bool is_last) {
  uint64_t size = 13 + node.name().size() + node.properties().size();
  const auto& children = node.children();
  for (size_t c = 0; c < children.size(); ++c) size += EncodedSize(*children[c], c + 1 == children.size());
  return size + (Closed(node, is_last) ? kNullRecordSize : 0);
}

// The file's bytes handed to a sink in pieces of about a megabyte (a longer record's
// properties alone); offset() is the absolute file offset of the next byte, from which each
// record's end offset follows.
class Encoder {
 public:
  static constexpr size_t kPiece = 1 << 20;
  explicit Encoder(const ByteSink& sink) : sink_(sink) {}
  void Add(std::string_view bytes) {
    offset_ += bytes.size();
    if (bytes.size() >= kPiece) {  // A long array's record properties: handed on, not copied.
      Flush();
      if (status_.ok()) status_ = sink_(bytes);
      return;
    }
    pending_.append(bytes);
    if (pending_.size() >= kPiece) Flush();
  }
  template <typename T>
  void AddValue(T value) {
    char bytes[sizeof(T)];
    std::memcpy(bytes, &value, sizeof(T));
    Add(std::string_view(bytes, sizeof(T)));
  }
  // `node` and its children; the sizes were checked against 4 GiB before the first byte.
  void AddNode(const Node& node, bool is_last) {
    AddValue<uint32_t>(static_cast<uint32_t>(offset_ + EncodedSize(node, is_last)));
    AddValue<uint32_t>(static_cast<uint32_t>(node.num_properties()));
    AddValue<uint32_t>(static_cast<uint32_t>(node.properties().size()));
    AddValue<uint8_t>(static_cast<uint8_t>(node.name().size()));
    Add(node.name());
    Add(node.properties());
    const auto& children = node.children();
    for (size_t c = 0; c < children.size(); ++c) AddNode(*children[c], c + 1 == children.size());
    if (Closed(node, is_last)) Add(std::string(kNullRecordSize, '\0'));
  }
  uint64_t offset() const { return offset_; }
  void Flush() {
    if (status_.ok() && !pending_.empty()) status_ = sink_(pending_);
    pending_.clear();
  }
  const Status& status() const { return status_; }

 private:
  const ByteSink& sink_;
  std::string pending_;
  uint64_t offset_ = 0;
  Status status_ = Status::Ok();
};

// The footer after `end` bytes of header and records: its padding makes the bytes before
// the version a multiple of 16 (1..16 bytes: a full 16 when already aligned).
std::string Footer(uint64_t end) {
  std::string footer(reinterpret_cast<const char*>(kFooterId), sizeof kFooterId);
  footer.append(4, '\0');
  footer.append(16 - (end + footer.size()) % 16, '\0');
  Append<uint32_t>(&footer, kFbxVersion);
  footer.append(120, '\0');
  footer.append(reinterpret_cast<const char*>(kFooterMagic), sizeof kFooterMagic);
  return footer;
}

}  // namespace

Node& Node::AddChild(std::string name) {
  children_.push_back(std::make_unique<Node>(std::move(name)));
  return *children_.back();
}

Node& Node::Char(char value) {
  properties_ += 'C';
  properties_ += value;
  ++num_properties_;
  return *this;
}
Node& Node::Bool(bool value) {
  properties_ += 'B';
  properties_ += value ? '\x01' : '\x00';
  ++num_properties_;
  return *this;
}
Node& Node::Int16(int16_t value) {
  properties_ += 'Y';
  Append(&properties_, value);
  ++num_properties_;
  return *this;
}
Node& Node::Int32(int32_t value) {
  properties_ += 'I';
  Append(&properties_, value);
  ++num_properties_;
  return *this;
}
Node& Node::Int64(int64_t value) {
  properties_ += 'L';
  Append(&properties_, value);
  ++num_properties_;
  return *this;
}
Node& Node::Float(float value) {
  properties_ += 'F';
  Append(&properties_, value);
  ++num_properties_;
  return *this;
}
Node& Node::Double(double value) {
  properties_ += 'D';
  Append(&properties_, value);
  ++num_properties_;
  return *this;
}
Node& Node::String(std::string_view value) {
  properties_ += 'S';
  Append(&properties_, static_cast<uint32_t>(value.size()));
  properties_.append(value);
  ++num_properties_;
  return *this;
}
Node& Node::Raw(std::string_view value) {
  properties_ += 'R';
  Append(&properties_, static_cast<uint32_t>(value.size()));
  properties_.append(value);
  ++num_properties_;
  return *this;
}

void Node::AddArray(char type, const void* data, size_t count, size_t element_size) {
  const size_t bytes = count * element_size;
  properties_ += type;
  Append(&properties_, static_cast<uint32_t>(count));
  if (bytes > kCompressAbove) {
    uLongf packed_size = compressBound(static_cast<uLong>(bytes));
    std::string packed(packed_size, '\0');
    if (compress2(reinterpret_cast<Bytef*>(&packed[0]), &packed_size, static_cast<const Bytef*>(data),
                  static_cast<uLong>(bytes), 1) == Z_OK &&
        packed_size < bytes) {
      Append<uint32_t>(&properties_, 1);
      Append<uint32_t>(&properties_, static_cast<uint32_t>(packed_size));
      properties_.append(packed.data(), packed_size);
      ++num_properties_;
      return;
    }
  }
  Append<uint32_t>(&properties_, 0);
  Append<uint32_t>(&properties_, static_cast<uint32_t>(bytes));
  properties_.append(static_cast<const char*>(data), bytes);
  ++num_properties_;
}

Node& Node::Int32Array(const std::vector<int32_t>& values) {
  AddArray('i', values.data(), values.size(), sizeof(int32_t));
  return *this;
}
Node& Node::Int64Array(const std::vector<int64_t>& values) {
  AddArray('l', values.data(), values.size(), sizeof(int64_t));
  return *this;
}
Node& Node::FloatArray(const std::vector<float>& values) {
  AddArray('f', values.data(), values.size(), sizeof(float));
  return *this;
}
Node& Node::DoubleArray(const std::vector<double>& values) {
  AddArray('d', values.data(), values.size(), sizeof(double));
  return *this;
}

std::string_view FileIdBytes() { return {reinterpret_cast<const char*>(kFileId), sizeof kFileId}; }
std::string_view CreationTimeString() { return kCreationTime; }

Status EncodeFbxBinary(const std::vector<const Node*>& top_level, const ByteSink& sink) {
  // The top level is the children of an unnamed root record, which is never written: its
  // children are closed by a null record like any other record's.
  uint64_t end = kMagicSize + 4 + kNullRecordSize;
  for (size_t i = 0; i < top_level.size(); ++i) {
    if (Status s = CheckNames(*top_level[i]); !s.ok()) return s;
    end += EncodedSize(*top_level[i], i + 1 == top_level.size());
  }
  if (end + Footer(end).size() > std::numeric_limits<uint32_t>::max()) {
    return Status::Error("FBX file over 4 GiB (FBX 7.4 records hold 32-bit offsets)");
  }
  Encoder encoder(sink);
  encoder.Add(std::string_view(kMagic, kMagicSize));
  encoder.AddValue<uint32_t>(kFbxVersion);
  for (size_t i = 0; i < top_level.size(); ++i) encoder.AddNode(*top_level[i], i + 1 == top_level.size());
  encoder.Add(std::string(kNullRecordSize, '\0'));
  encoder.Add(Footer(encoder.offset()));
  encoder.Flush();
  return encoder.status();
}

Status EncodeFbxBinary(const std::vector<const Node*>& top_level, std::string* bytes) {
  std::string out;
  Status status = EncodeFbxBinary(top_level, [&out](std::string_view piece) {
    out.append(piece);
    return Status::Ok();
  });
  if (status.ok()) *bytes = std::move(out);
  return status;
}

}  // namespace mocapsolve::fbx
