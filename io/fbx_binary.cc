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

void PutUint32(std::string* out, size_t at, uint32_t value) { std::memcpy(&(*out)[at], &value, 4); }

bool AlwaysClosed(const std::string& name) {  // Records the SDK closes with a null record.
  return name == "AnimationStack" || name == "AnimationLayer";
}

// Appends `node` (its end offset computed from out->size(), the absolute file offset).
Status EncodeNode(const Node& node, bool is_last, std::string* out) {
  if (node.name().size() > 255) return Status::Error("FBX record name over 255 bytes: " + node.name().substr(0, 40));
  const size_t start = out->size();
  Append<uint32_t>(out, 0);  // End offset, patched below.
  Append<uint32_t>(out, static_cast<uint32_t>(node.num_properties()));
  if (node.properties().size() > std::numeric_limits<uint32_t>::max()) {
    return Status::Error("FBX record '" + node.name() + "': properties over 4 GiB");
  }
  Append<uint32_t>(out, static_cast<uint32_t>(node.properties().size()));
  Append<uint8_t>(out, static_cast<uint8_t>(node.name().size()));
  out->append(node.name());
  out->append(node.properties());
  const auto& children = node.children();
  for (size_t c = 0; c < children.size(); ++c) {
    if (Status s = EncodeNode(*children[c], c + 1 == children.size(), out); !s.ok()) return s;
  }
  if (!children.empty() || (node.num_properties() == 0 && !is_last) || AlwaysClosed(node.name())) {
    out->append(kNullRecordSize, '\0');
  }
  if (out->size() > std::numeric_limits<uint32_t>::max()) {
    return Status::Error("FBX file over 4 GiB (FBX 7.4 records hold 32-bit offsets)");
  }
  PutUint32(out, start, static_cast<uint32_t>(out->size()));
  return Status::Ok();
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

Status EncodeFbxBinary(const std::vector<const Node*>& top_level, std::string* bytes) {
  std::string out(kMagic, kMagicSize);
  Append<uint32_t>(&out, kFbxVersion);
  for (size_t i = 0; i < top_level.size(); ++i) {
    // The top level is the children of an unnamed root record, which is never written:
    // its children are closed by a null record like any other record's.
    if (Status s = EncodeNode(*top_level[i], i + 1 == top_level.size(), &out); !s.ok()) return s;
  }
  out.append(kNullRecordSize, '\0');
  out.append(reinterpret_cast<const char*>(kFooterId), sizeof kFooterId);
  out.append(4, '\0');
  const size_t pad = 16 - out.size() % 16;  // 1..16: a full 16 when already aligned.
  out.append(pad, '\0');
  Append<uint32_t>(&out, kFbxVersion);
  out.append(120, '\0');
  out.append(reinterpret_cast<const char*>(kFooterMagic), sizeof kFooterMagic);
  if (out.size() > std::numeric_limits<uint32_t>::max()) {
    return Status::Error("FBX file over 4 GiB (FBX 7.4 records hold 32-bit offsets)");
  }
  *bytes = std::move(out);
  return Status::Ok();
}

}  // namespace mocapsolve::fbx
