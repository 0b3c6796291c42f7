// Binary FBX 7.4 encoding: a tree of node records to the bytes of a .fbx file. Knows the
// container only (records, property types, arrays, header and footer), not what the
// nodes mean; io/fbx_writer.h builds the scene. The public description of the format is
// Blender's exporter (io_scene_fbx/encode_bin.py), which this follows:
//
//   file   = "Kaydara FBX Binary  \x00\x1a\x00", uint32 version (7400),
//            top-level records, a null record, footer.
//   record = uint32 end offset (absolute, from the start of the file), uint32 number of
//            properties, uint32 bytes of the property list, uint8 name length, name,
//            properties, child records, then a null record (13 zero bytes) if the record
//            has children, or has no properties and is not the last of its siblings, or is
//            an AnimationStack/AnimationLayer (as the FBX SDK writes them).
//   property = one type byte, then: 'C' char / 'B' bool (1 byte), 'Y' int16, 'I' int32,
//            'L' int64, 'F' float, 'D' double (little-endian); 'S' string / 'R' raw bytes
//            (uint32 length + bytes, no terminator); arrays 'b' 'c' 'i' 'l' 'f' 'd':
//            uint32 count, uint32 encoding (0 = raw, 1 = zlib deflate), uint32 byte
//            length, data. Arrays over 128 bytes are compressed (zlib level 1 as Blender;
//            kept raw when that does not make them smaller).
//   footer = the 16-byte footer id, 4 zero bytes, zero padding to a multiple of 16 (1..16
//            bytes), uint32 version, 120 zero bytes, a 16-byte magic.
//
// FileId and CreationTime are fixed values (Blender's): importers check them against the
// footer id, and a fixed time keeps the output deterministic.
#ifndef MOCAPSOLVE_IO_FBX_BINARY_H_
#define MOCAPSOLVE_IO_FBX_BINARY_H_

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "kinematics/status.h"

namespace mocapsolve::fbx {

// One record: a name, its encoded properties and its children. Build with the typed
// adders (each returns *this, so calls chain).
class Node {
 public:
  explicit Node(std::string name) : name_(std::move(name)) {}
  Node(Node&&) = default;
  Node& operator=(Node&&) = default;

  Node& AddChild(std::string name);  // The new child (stable: children are held by pointer).

  Node& Char(char value);
  Node& Bool(bool value);
  Node& Int16(int16_t value);
  Node& Int32(int32_t value);
  Node& Int64(int64_t value);
  Node& Float(float value);
  Node& Double(double value);
  Node& String(std::string_view value);  // 'S'; may hold the "\x00\x01" name-class separator.
  Node& Raw(std::string_view value);     // 'R'.
  Node& Int32Array(const std::vector<int32_t>& values);
  Node& Int64Array(const std::vector<int64_t>& values);
  Node& FloatArray(const std::vector<float>& values);
  Node& DoubleArray(const std::vector<double>& values);

  const std::string& name() const { return name_; }
  int num_properties() const { return num_properties_; }
  const std::string& properties() const { return properties_; }
  const std::vector<std::unique_ptr<Node>>& children() const { return children_; }

 private:
  void AddArray(char type, const void* data, size_t count, size_t element_size);

  std::string name_;
  std::string properties_;  // Encoded, type bytes included.
  int num_properties_ = 0;
  std::vector<std::unique_ptr<Node>> children_;
};

constexpr int kFbxVersion = 7400;

// The file: the header, `top_level` records in order, the footer. Errors: a record name
// over 255 bytes, or a file over 4 GiB (32-bit offsets).
Status EncodeFbxBinary(const std::vector<const Node*>& top_level, std::string* bytes);
// The same bytes handed to `sink` in order, in pieces of about a megabyte (a record's
// properties over that in a piece of their own): a long take's file is never whole in
// memory. Every size is checked before the first piece; the sink's first error ends the
// encoding and is returned.
using ByteSink = std::function<Status(std::string_view)>;
Status EncodeFbxBinary(const std::vector<const Node*>& top_level, const ByteSink& sink);

// The FileId, CreationTime and footer id that belong together (see above).
std::string_view FileIdBytes();
std::string_view CreationTimeString();

}  // namespace mocapsolve::fbx

#endif  // MOCAPSOLVE_IO_FBX_BINARY_H_
