#include "io/gltf_writer.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <sstream>
#include <utility>
#include <vector>

#include <tiny_gltf.h>

#include "io/atomic_file.h"
#include "io/input_limits.h"
#include "io/gltf_scene.h"
#include "io/motion_file.h"
#include "io/motion_samples.h"
#include "kinematics/compact_motion.h"
#include "kinematics/frame_rate.h"
#include "kinematics/quote_token.h"

namespace mocapsolve {
namespace {

using gltf_internal::Similarity;

// Keeps every image as it is in the source (URI or buffer view): never re-encoded.
bool KeepImageAsIs(const std::string*, const std::string*, const tinygltf::Image*, bool, std::string*,
                   void*) {
  return false;
}

// Appends floats to buffer 0 as a new buffer view + accessor; returns the accessor index.
int AppendFloatAccessor(tinygltf::Model* model, const std::vector<float>& values, int type,
                        size_t count, bool with_min_max) {
  tinygltf::Buffer& buffer = model->buffers[0];
  while (buffer.data.size() % 4 != 0) buffer.data.push_back(0);
  tinygltf::BufferView view;
  view.buffer = 0;
  view.byteOffset = buffer.data.size();
  view.byteLength = values.size() * sizeof(float);
  const size_t old = buffer.data.size();
  buffer.data.resize(old + view.byteLength);
  if (!values.empty()) std::memcpy(buffer.data.data() + old, values.data(), view.byteLength);
  model->bufferViews.push_back(view);
  tinygltf::Accessor accessor;
  accessor.bufferView = static_cast<int>(model->bufferViews.size()) - 1;
  accessor.byteOffset = 0;
  accessor.componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
  accessor.count = count;
  accessor.type = type;
  accessor.normalized = false;
  if (with_min_max && count > 0) {
    const size_t n = values.size() / count;
    accessor.minValues.assign(values.begin(), values.begin() + n);
    accessor.maxValues = accessor.minValues;
    for (size_t e = 0; e < count; ++e) {
      for (size_t c = 0; c < n; ++c) {
        accessor.minValues[c] = std::min<double>(accessor.minValues[c], values[e * n + c]);
        accessor.maxValues[c] = std::max<double>(accessor.maxValues[c], values[e * n + c]);
      }
    }
  }
  model->accessors.push_back(accessor);
  return static_cast<int>(model->accessors.size()) - 1;
}

// Appends unit-quaternion components as normalized int16 (glTF 2.0 allows SHORT normalized
// rotation outputs: c = q / 32767); returns the accessor index.
int AppendNormalizedShortAccessor(tinygltf::Model* model, const std::vector<float>& values, int type, size_t count) {
  tinygltf::Buffer& buffer = model->buffers[0];
  while (buffer.data.size() % 4 != 0) buffer.data.push_back(0);
  std::vector<std::int16_t> shorts(values.size());
  for (size_t i = 0; i < values.size(); ++i) {
    shorts[i] = static_cast<std::int16_t>(std::lround(std::clamp(values[i], -1.0f, 1.0f) * 32767.0f));
  }
  tinygltf::BufferView view;
  view.buffer = 0;
  view.byteOffset = buffer.data.size();
  view.byteLength = shorts.size() * sizeof(std::int16_t);
  const size_t old = buffer.data.size();
  buffer.data.resize(old + view.byteLength);
  if (!shorts.empty()) std::memcpy(buffer.data.data() + old, shorts.data(), view.byteLength);
  model->bufferViews.push_back(view);
  tinygltf::Accessor accessor;
  accessor.bufferView = static_cast<int>(model->bufferViews.size()) - 1;
  accessor.byteOffset = 0;
  accessor.componentType = TINYGLTF_COMPONENT_TYPE_SHORT;
  accessor.count = count;
  accessor.type = type;
  accessor.normalized = true;
  model->accessors.push_back(accessor);
  return static_cast<int>(model->accessors.size()) - 1;
}

// The MIME type of encoded image bytes: from their signature (PNG, JPEG, WebP), else the
// type the file stated (an image's mimeType or its data: URI's), else from the URI's extension.
std::string ImageMimeType(const std::vector<unsigned char>& bytes, const std::string& stated, const std::string& uri) {
  auto starts = [&](size_t at, const char* magic) {
    const size_t n = std::strlen(magic);
    return bytes.size() >= at + n && std::memcmp(bytes.data() + at, magic, n) == 0;
  };
  if (starts(0, "\x89PNG")) return "image/png";
  if (starts(0, "\xff\xd8\xff")) return "image/jpeg";
  if (starts(0, "RIFF") && starts(8, "WEBP")) return "image/webp";
  if (stated.rfind("image/", 0) == 0) return stated;
  const std::string ext = FileExtension(uri);
  if (ext == ".png") return "image/png";
  if (ext == ".jpg" || ext == ".jpeg") return "image/jpeg";
  if (ext == ".webp") return "image/webp";
  if (ext == ".ktx2") return "image/ktx2";
  return "application/octet-stream";
}

// Makes `model` self-contained: every buffer's bytes go into buffer 0 (each started at a
// multiple of 4 bytes, which keeps every accessor's alignment) with the buffer views
// re-pointed, and every image given by a URI (an external file or a data: URI, whose
// bytes the reader kept) moves into a buffer view of its own with its MIME type. Buffer
// 0 then has no URI: a .glb's BIN chunk.
Status EmbedBuffersAndImages(const std::string& file, tinygltf::Model* model) {
  tinygltf::Buffer merged;
  if (!model->buffers.empty()) merged.name = model->buffers[0].name;
  std::vector<size_t> start(model->buffers.size());
  for (size_t b = 0; b < model->buffers.size(); ++b) {
    while (merged.data.size() % 4 != 0) merged.data.push_back(0);
    start[b] = merged.data.size();
    const std::vector<unsigned char>& data = model->buffers[b].data;
    merged.data.insert(merged.data.end(), data.begin(), data.end());
  }
  for (size_t v = 0; v < model->bufferViews.size(); ++v) {
    tinygltf::BufferView& view = model->bufferViews[v];
    if (view.buffer < 0 || static_cast<size_t>(view.buffer) >= start.size()) {
      return Status::Error(file + ": bufferView " + std::to_string(v) + ": buffer " + std::to_string(view.buffer) +
                           " does not exist");
    }
    view.byteOffset += start[view.buffer];
    view.buffer = 0;
  }
  for (size_t i = 0; i < model->images.size(); ++i) {
    tinygltf::Image& image = model->images[i];
    if (image.bufferView >= 0) {  // Already in a buffer view (re-pointed above).
      image.image.clear();
      continue;
    }
    if (image.image.empty()) {
      return Status::Error(file + ": image " + std::to_string(i) +
                           (image.uri.empty() ? ": has no data" : " (" + QuoteToken(image.uri) + "): could not be read"));
    }
    while (merged.data.size() % 4 != 0) merged.data.push_back(0);
    tinygltf::BufferView view;
    view.buffer = 0;
    view.byteOffset = merged.data.size();
    view.byteLength = image.image.size();
    merged.data.insert(merged.data.end(), image.image.begin(), image.image.end());
    model->bufferViews.push_back(view);
    image.bufferView = static_cast<int>(model->bufferViews.size()) - 1;
    image.mimeType = ImageMimeType(image.image, image.mimeType, image.uri);
    image.uri.clear();
    image.image.clear();
  }
  model->buffers.clear();
  if (!merged.data.empty()) model->buffers.push_back(std::move(merged));
  return Status::Ok();
}

// The model's bytes: .glb if `binary`, else .gltf JSON (buffers as data: URIs).
// A stream buffer that appends to a string: the file is written once, into *bytes, not
// into an ostringstream's own buffer (grown by doubling) and then copied out of it (for
// a long take's GLB, three to four times its keys at once).
class StringAppendBuffer : public std::streambuf {
 public:
  explicit StringAppendBuffer(std::string* out) : out_(out) {}

 protected:
  int_type overflow(int_type c) override {
    if (!traits_type::eq_int_type(c, traits_type::eof())) out_->push_back(traits_type::to_char_type(c));
    return traits_type::not_eof(c);
  }
  std::streamsize xsputn(const char* s, std::streamsize n) override {
    out_->append(s, static_cast<size_t>(n));
    return n;
  }

 private:
  std::string* out_;
};

Status WriteModel(const std::string& file, tinygltf::Model* model, bool binary, std::string* bytes) {
  tinygltf::TinyGLTF writer;
  writer.SetImageWriter(&KeepImageAsIs, nullptr);
  size_t expected = size_t{1} << 20;  // The JSON chunk, headers and padding.
  for (const tinygltf::Buffer& buffer : model->buffers) expected += buffer.data.size();
  bytes->clear();
  bytes->reserve(expected);
  StringAppendBuffer appender(bytes);
  std::ostream stream(&appender);
  bool ok = false;
  try {
    ok = writer.WriteGltfSceneToStream(model, stream, /*prettyPrint=*/!binary, binary);
  } catch (const std::exception& e) {
    return Status::Error(file + ": glTF writer: " + e.what());
  }
  if (!ok) return Status::Error(file + ": glTF writer failed");
  return Status::Ok();
}

// Copies accessor `index` of `from` (its elements, tightly packed) into buffer 0 of `to`
// as a new buffer view + accessor (type, component type, count, normalized, min/max kept);
// `copied` maps accessors already copied. Returns the new index, or -1 with *error set.
// With first_only, just its first element (not cached).
int CopyAccessor(const tinygltf::Model& from, int index, tinygltf::Model* to, std::vector<int>* copied,
                 std::string* error, bool first_only = false) {
  if (index < 0 || index >= static_cast<int>(from.accessors.size())) {
    *error = "accessor " + std::to_string(index) + " out of range";
    return -1;
  }
  if (!first_only && (*copied)[index] >= 0) return (*copied)[index];
  const tinygltf::Accessor& a = from.accessors[index];
  const std::string name = "accessor " + std::to_string(index);
  if (a.sparse.isSparse) {
    *error = name + ": sparse accessors are not copied into an animation-only file";
    return -1;
  }
  if (a.bufferView < 0 || a.bufferView >= static_cast<int>(from.bufferViews.size())) {
    *error = name + ": has no buffer view";
    return -1;
  }
  const tinygltf::BufferView& view = from.bufferViews[a.bufferView];
  const int component_size = tinygltf::GetComponentSizeInBytes(a.componentType);
  const int components = tinygltf::GetNumComponentsInType(a.type);
  if (view.buffer < 0 || view.buffer >= static_cast<int>(from.buffers.size()) || component_size <= 0 ||
      components <= 0) {
    *error = name + ": bad buffer, component type or type";
    return -1;
  }
  const size_t element = static_cast<size_t>(component_size) * components;
  const size_t stride = view.byteStride > 0 ? view.byteStride : element;
  const std::vector<unsigned char>& data = from.buffers[view.buffer].data;
  const size_t start = view.byteOffset + a.byteOffset;
  if (a.count > 0 && (a.byteOffset + stride * (a.count - 1) + element > view.byteLength ||
                      view.byteOffset + view.byteLength > data.size())) {
    *error = name + ": runs past its buffer view or buffer";
    return -1;
  }
  const size_t count = first_only ? std::min<size_t>(a.count, 1) : a.count;
  tinygltf::Buffer& buffer = to->buffers[0];
  while (buffer.data.size() % 4 != 0) buffer.data.push_back(0);
  tinygltf::BufferView out_view;
  out_view.buffer = 0;
  out_view.byteOffset = buffer.data.size();
  out_view.byteLength = element * count;
  buffer.data.reserve(buffer.data.size() + out_view.byteLength);
  for (size_t e = 0; e < count; ++e) {
    const unsigned char* p = data.data() + start + e * stride;
    buffer.data.insert(buffer.data.end(), p, p + element);
  }
  to->bufferViews.push_back(out_view);
  tinygltf::Accessor out = a;
  out.bufferView = static_cast<int>(to->bufferViews.size()) - 1;
  out.byteOffset = 0;
  out.count = count;
  if (first_only) {  // Bounds of the whole accessor would be wrong for one element.
    out.minValues.clear();
    out.maxValues.clear();
  }
  to->accessors.push_back(out);
  const int made = static_cast<int>(to->accessors.size()) - 1;
  if (!first_only) (*copied)[index] = made;
  return made;
}

// True if every element of accessor `index` (written by this file: tightly packed) has the
// bytes of the first.
bool AllElementsEqual(const tinygltf::Model& model, int index) {
  const tinygltf::Accessor& a = model.accessors[index];
  const tinygltf::BufferView& view = model.bufferViews[a.bufferView];
  const size_t element = static_cast<size_t>(tinygltf::GetComponentSizeInBytes(a.componentType)) *
                         tinygltf::GetNumComponentsInType(a.type);
  const unsigned char* first = model.buffers[view.buffer].data.data() + view.byteOffset + a.byteOffset;
  for (size_t e = 1; e < a.count; ++e) {
    if (std::memcmp(first, first + e * element, element) != 0) return false;
  }
  return true;
}

// The animation-only model (gltf_writer.h) of `full`: the nodes of skin `skin` and their
// ancestors (`parent` per node), the skin, one scene, and the first animation of `full`
// (the new one).
Status AnimationOnlyModel(const tinygltf::Model& full, const std::vector<int>& parent, int skin,
                          const std::string& file, tinygltf::Model* out) {
  const int nn = static_cast<int>(full.nodes.size());
  if (skin < 0 || skin >= static_cast<int>(full.skins.size()) || full.animations.empty()) {
    return Status::Error(file + ": animation only: no skin " + std::to_string(skin) + " or no animation");
  }
  const tinygltf::Skin& source_skin = full.skins[skin];
  std::vector<bool> keep(nn, false);
  auto keep_with_ancestors = [&](int node) {
    for (int n = node; n >= 0 && !keep[n]; n = parent[n]) keep[n] = true;
  };
  for (int n : source_skin.joints) keep_with_ancestors(n);
  if (source_skin.skeleton >= 0) keep_with_ancestors(source_skin.skeleton);
  std::vector<int> index(nn, -1);
  tinygltf::Model model;
  model.asset = full.asset;
  model.asset.extras = tinygltf::Value();
  model.asset.extensions.clear();
  for (int n = 0; n < nn; ++n) {
    if (!keep[n]) continue;
    index[n] = static_cast<int>(model.nodes.size());
    const tinygltf::Node& from = full.nodes[n];
    tinygltf::Node node;
    node.name = from.name;
    node.translation = from.translation;
    node.rotation = from.rotation;
    node.scale = from.scale;
    node.matrix = from.matrix;
    model.nodes.push_back(node);
  }
  tinygltf::Scene scene;
  if (!full.scenes.empty()) {
    scene.name = full.scenes[full.defaultScene >= 0 && full.defaultScene < static_cast<int>(full.scenes.size())
                                 ? full.defaultScene
                                 : 0]
                     .name;
  }
  for (int n = 0; n < nn; ++n) {
    if (!keep[n]) continue;
    for (int child : full.nodes[n].children) {
      if (child >= 0 && child < nn && keep[child]) model.nodes[index[n]].children.push_back(index[child]);
    }
    if (parent[n] < 0) scene.nodes.push_back(index[n]);
  }
  model.scenes.push_back(scene);
  model.defaultScene = 0;
  model.buffers.emplace_back();
  std::vector<int> copied(full.accessors.size(), -1);
  std::string error;
  tinygltf::Skin out_skin;
  out_skin.name = source_skin.name;
  for (int n : source_skin.joints) out_skin.joints.push_back(index[n]);
  out_skin.skeleton = source_skin.skeleton >= 0 ? index[source_skin.skeleton] : -1;
  if (source_skin.inverseBindMatrices >= 0) {
    out_skin.inverseBindMatrices = CopyAccessor(full, source_skin.inverseBindMatrices, &model, &copied, &error);
    if (out_skin.inverseBindMatrices < 0) return Status::Error(file + ": skin " + std::to_string(skin) + ": " + error);
  }
  model.skins.push_back(out_skin);
  // The animation (written by this file: LINEAR samplers, tightly packed accessors). A
  // channel whose keys are all equal (fingers a skeleton-only source does not move) gets
  // one key at time 0, which glTF holds for the whole clip, unless every channel is
  // constant (the clip then keeps its length).
  const tinygltf::Animation& from = full.animations.front();
  std::vector<bool> constant(from.samplers.size());
  bool all_constant = true;
  for (size_t k = 0; k < from.samplers.size(); ++k) {
    constant[k] = AllElementsEqual(full, from.samplers[k].output);
    all_constant = all_constant && constant[k];
  }
  int single_time = -1;
  tinygltf::Animation animation;
  animation.name = from.name;
  for (size_t k = 0; k < from.samplers.size(); ++k) {
    const tinygltf::AnimationSampler& s = from.samplers[k];
    tinygltf::AnimationSampler sampler = s;
    if (constant[k] && !all_constant) {
      if (single_time < 0) single_time = AppendFloatAccessor(&model, {0.0f}, TINYGLTF_TYPE_SCALAR, 1, true);
      sampler.input = single_time;
      sampler.output = CopyAccessor(full, s.output, &model, &copied, &error, /*first_only=*/true);
    } else {
      sampler.input = CopyAccessor(full, s.input, &model, &copied, &error);
      if (sampler.input >= 0) sampler.output = CopyAccessor(full, s.output, &model, &copied, &error);
    }
    if (sampler.input < 0 || sampler.output < 0) return Status::Error(file + ": animation only: " + error);
    animation.samplers.push_back(sampler);
  }
  for (const tinygltf::AnimationChannel& c : from.channels) {
    tinygltf::AnimationChannel channel = c;
    channel.target_node = c.target_node >= 0 && c.target_node < nn ? index[c.target_node] : -1;
    if (channel.target_node < 0) {
      return Status::Error(file + ": animation only: channel on node " + std::to_string(c.target_node) +
                           ", which is not a joint of skin " + std::to_string(skin));
    }
    animation.channels.push_back(channel);
  }
  model.animations.push_back(std::move(animation));
  *out = std::move(model);
  return Status::Ok();
}

// The source's model with the new animation (see the header), to be written by WriteModel
// or WriteGlbFile.
template <class Samples>
Status ModelWithAnimation(const GltfDocument& source, const GltfCharacter& character, const Samples& motion,
                          const std::string& animation_name, bool binary, const GltfWriteOptions& options,
                          tinygltf::Model* out) {
  const bool compact = options.compact;
  if (!source.loaded()) return Status::Error("glTF writer: source document not loaded");
  const std::string& file = source.name();
  const Skeleton& skeleton = character.skeleton;
  if (animation_name.empty()) return Status::Error(file + ": the new animation needs a name");
  for (const tinygltf::Animation& a : source.model().animations) {
    if (a.name == animation_name) {
      return Status::Error(file + ": already has an animation named " + QuoteToken(animation_name));
    }
  }
  if (!(motion.frame_rate() > 0.0) || !std::isfinite(motion.frame_rate())) {
    return Status::Error(file + ": animation " + QuoteToken(animation_name) + ": frame rate must be positive");
  }
  if (motion.num_frames() == 0) return Status::Error(file + ": animation " + QuoteToken(animation_name) + " has no frames");
  Status status = motion.Validate(skeleton);
  if (!status.ok()) return Status::Error(file + ": animation " + QuoteToken(animation_name) + ": " + status.message());

  tinygltf::Model model = source.model();
  gltf_internal::NodeGraph graph;
  status = gltf_internal::BuildNodeGraph(model, file, &graph, nullptr);
  if (!status.ok()) return status;
  gltf_internal::Rig rig;
  status = gltf_internal::BuildRig(model, graph, character.skin, file, &rig);
  if (!status.ok()) return status;
  if (rig.joint_nodes != character.joint_nodes || rig.joint_nodes.size() != static_cast<size_t>(skeleton.num_joints())) {
    return Status::Error(file + ": the character was not read from this file");
  }
  const int nj = skeleton.num_joints();
  const int nf = motion.num_frames();
  if (binary) {  // Buffer 0 becomes the GLB's BIN chunk, with every buffer and image in it.
    status = EmbedBuffersAndImages(file, &model);
    if (!status.ok()) return status;
  }
  if (model.buffers.empty()) model.buffers.emplace_back();
  // At most the animation's bytes (the times; per joint a rotation and a translation
  // channel, each 4-byte aligned), reserved once: the buffer does not grow by doubling
  // (up to three times a long take's keys at a reallocation).
  model.buffers[0].data.reserve(model.buffers[0].data.size() + 4 * (static_cast<size_t>(nf) + 2) +
                                static_cast<size_t>(nj) * (28 * static_cast<size_t>(nf) + 8));

  std::vector<float> times(nf);
  const double key_rate = NominalFrameRate(motion.frame_rate());  // As the reader samples them.
  for (int f = 0; f < nf; ++f) times[f] = static_cast<float>(f / key_rate);
  const int time_accessor = AppendFloatAccessor(&model, times, TINYGLTF_TYPE_SCALAR, nf, true);

  tinygltf::Animation animation;
  animation.name = animation_name;
  int one_key_time = -1;  // compact: the time accessor [0] of the channels with one key.
  auto add_channel = [&](int node, const char* path, std::vector<float> values, int type) {
    const bool shorts = compact && type == TINYGLTF_TYPE_VEC4;
    const size_t width = type == TINYGLTF_TYPE_VEC4 ? 4 : 3;
    // The value as stored: int16 (AppendNormalizedShortAccessor's rounding) or float.
    auto stored = [shorts](float v) {
      return shorts ? static_cast<float>(std::lround(std::clamp(v, -1.0f, 1.0f) * 32767.0f)) : v;
    };
    bool constant = compact;
    for (size_t i = width; constant && i < values.size(); ++i) constant = stored(values[i]) == stored(values[i % width]);
    size_t keys = nf;
    tinygltf::AnimationSampler sampler;
    sampler.input = time_accessor;
    if (constant) {
      if (one_key_time < 0) one_key_time = AppendFloatAccessor(&model, {0.0f}, TINYGLTF_TYPE_SCALAR, 1, true);
      sampler.input = one_key_time;
      values.resize(width);
      keys = 1;
    }
    sampler.output = shorts ? AppendNormalizedShortAccessor(&model, values, type, keys)
                            : AppendFloatAccessor(&model, values, type, keys, false);
    sampler.interpolation = "LINEAR";
    animation.samplers.push_back(sampler);
    tinygltf::AnimationChannel channel;
    channel.sampler = static_cast<int>(animation.samplers.size()) - 1;
    channel.target_node = node;
    channel.target_path = path;
    animation.channels.push_back(channel);
  };
  std::vector<float> rotations(4 * nf), translations(3 * nf);
  for (int j = 0; j < nj; ++j) {
    const int node = rig.joint_nodes[j];
    if (node < 0) {  // The synthetic root must stay at rest.
      for (int f = 0; f < nf; ++f) {
        if (motion.translation(f, j).norm() > 1e-9 ||
            motion.rotation(f, j).angularDistance(Eigen::Quaterniond::Identity()) > 1e-9) {
          return Status::Error(file + ": frame " + std::to_string(f) +
                               ": moves the synthetic root 'gltf_root', which has no node to animate");
        }
      }
      continue;
    }
    tinygltf::Node& target = model.nodes[node];
    if (target.matrix.size() == 16) {
      Eigen::Matrix4d m;
      for (int k = 0; k < 16; ++k) m(k % 4, k / 4) = target.matrix[k];
      bool exact = true;
      const Similarity s = gltf_internal::SimilarityFromMatrix(m, &exact);
      if (!exact) {
        return Status::Error(file + ": node " + std::to_string(node) +
                             ": matrix is not a uniform-scale similarity; cannot animate it");
      }
      target.matrix.clear();
      target.translation = {s.translation.x(), s.translation.y(), s.translation.z()};
      target.rotation = {s.rotation.x(), s.rotation.y(), s.rotation.z(), s.rotation.w()};
      target.scale = {s.scale, s.scale, s.scale};
    }
    // A = the default transforms above j's node within its chain.
    Similarity above;
    const std::vector<int>& chain = rig.chains[j];
    for (size_t k = 0; k + 1 < chain.size(); ++k) above = above * graph.local[chain[k]];
    const int p = rig.parents[j];
    const double parent_scale = p >= 0 ? rig.rest_scales[p] : 1.0;
    const Eigen::Quaterniond above_inverse = above.rotation.conjugate();
    bool moves = p < 0 || rig.joint_nodes[p] < 0;  // Roots always get translations.
    const Eigen::Vector3d& offset = skeleton.offset(j);
    for (int f = 0; f < nf; ++f) {
      const Eigen::Quaterniond q =
          (above_inverse * skeleton.rest_rotation(j) * motion.rotation(f, j)).normalized();
      rotations[4 * f + 0] = static_cast<float>(q.x());
      rotations[4 * f + 1] = static_cast<float>(q.y());
      rotations[4 * f + 2] = static_cast<float>(q.z());
      rotations[4 * f + 3] = static_cast<float>(q.w());
      const Eigen::Vector3d translation = motion.translation(f, j);
      const Eigen::Vector3d t = above_inverse * (translation / parent_scale - above.translation) / above.scale;
      for (int c = 0; c < 3; ++c) translations[3 * f + c] = static_cast<float>(t[c]);
      if ((translation - offset).norm() > 1e-9 * (offset.norm() + 1.0)) moves = true;
    }
    add_channel(node, "rotation", rotations, TINYGLTF_TYPE_VEC4);
    if (moves) add_channel(node, "translation", translations, TINYGLTF_TYPE_VEC3);
  }
  // First: the clip a reader opens by default (the character's own clips follow).
  model.animations.insert(model.animations.begin(), std::move(animation));
  if (options.animation_only) {
    tinygltf::Model slim;
    status = AnimationOnlyModel(model, graph.parent, character.skin, file, &slim);
    if (!status.ok()) return status;
    model = std::move(slim);
  }
  *out = std::move(model);
  return Status::Ok();
}

template <class Samples>
Status SerializeWithAnimation(const GltfDocument& source, const GltfCharacter& character, const Samples& motion,
                              const std::string& animation_name, bool binary, std::string* bytes,
                              const GltfWriteOptions& options) {
  tinygltf::Model model;
  Status status = ModelWithAnimation(source, character, motion, animation_name, binary, options, &model);
  if (!status.ok()) return status;
  return WriteModel(source.name(), &model, binary, bytes);
}

void AppendWord(std::uint32_t word, std::string* out) {  // Little-endian, as the GLB's.
  for (int k = 0; k < 4; ++k) out->push_back(static_cast<char>((word >> (8 * k)) & 0xff));
}

// The samples ModelWithAnimation reads, for either kind of motion.
MotionSamples AnimationSamples(const Motion& motion) { return MotionSamples(motion); }
CompactSamples AnimationSamples(const CompactMotion& motion) { return CompactSamples(motion); }

// The .glb of `model` written straight into `path` (AtomicFileWriter): the bytes WriteModel
// makes, but buffer 0 (the BIN chunk: a long take's keys) goes from the model to the file
// as it is, not through tinygltf's copy of it and the file's bytes in memory (two more
// copies of the keys: 2.1 KB per frame of Xbot's take). The JSON chunk is tinygltf's for
// the model with buffer 0 emptied, its byteLength then set to the real one.
Status WriteGlbFile(const std::string& file, tinygltf::Model* model, const std::string& path) {
  if (model->buffers.empty() || !model->buffers[0].uri.empty()) {
    return Status::Error(file + ": glTF writer: no embedded buffer 0 for the BIN chunk");
  }
  std::vector<unsigned char> bin = std::move(model->buffers[0].data);
  model->buffers[0].data = std::vector<unsigned char>();
  std::string glb;
  Status status = WriteModel(file, model, /*binary=*/true, &glb);
  if (!status.ok()) return status;
  std::uint32_t json_length = 0;
  if (glb.size() >= 20) std::memcpy(&json_length, glb.data() + 12, 4);  // The writer's (little-endian) host order.
  if (glb.size() < 20 + static_cast<size_t>(json_length)) return Status::Error(file + ": glTF writer: short GLB");
  std::string json = glb.substr(20, json_length);
  glb = std::string();
  while (!json.empty() && json.back() == ' ') json.pop_back();  // The chunk's padding.
  const std::string key = "\"buffers\":[{\"byteLength\":0";
  const size_t at = json.find(key);
  if (at == std::string::npos || json.find(key, at + 1) != std::string::npos ||
      (json[at + key.size()] != ',' && json[at + key.size()] != '}')) {
    return Status::Error(file + ": glTF writer: buffer 0 not found in the JSON chunk");
  }
  json.replace(at, key.size(), "\"buffers\":[{\"byteLength\":" + std::to_string(bin.size()));
  while (json.size() % 4 != 0) json.push_back(' ');
  const size_t bin_padded = (bin.size() + 3) / 4 * 4;
  std::string head = "glTF";
  AppendWord(2, &head);
  AppendWord(static_cast<std::uint32_t>(12 + 8 + json.size() + (bin.empty() ? 0 : 8 + bin_padded)), &head);
  AppendWord(static_cast<std::uint32_t>(json.size()), &head);
  AppendWord(0x4E4F534A, &head);  // "JSON"
  head += json;
  json = std::string();
  if (!bin.empty()) {
    AppendWord(static_cast<std::uint32_t>(bin_padded), &head);
    AppendWord(0x004E4942, &head);  // "BIN"
  }
  AtomicFileWriter writer;
  status = writer.Open(path);
  if (status.ok()) status = writer.Append(head.data(), head.size());
  if (status.ok() && !bin.empty()) status = writer.Append(bin.data(), bin.size());
  if (status.ok() && bin_padded > bin.size()) status = writer.Append(std::string(bin_padded - bin.size(), '\0'));
  if (status.ok()) status = writer.Close();
  return status;
}

}  // namespace

Status SerializeGltfWithAnimation(const GltfDocument& source, const GltfCharacter& character,
                                  const Motion& motion, const std::string& animation_name,
                                  bool binary, std::string* bytes, const GltfWriteOptions& options) {
  return SerializeWithAnimation(source, character, MotionSamples(motion), animation_name, binary, bytes, options);
}

Status SerializeGltfWithAnimation(const GltfDocument& source, const GltfCharacter& character,
                                  const CompactMotion& motion, const std::string& animation_name,
                                  bool binary, std::string* bytes, const GltfWriteOptions& options) {
  return SerializeWithAnimation(source, character, CompactSamples(motion), animation_name, binary, bytes, options);
}

Status SerializeGltfAsGlb(const GltfDocument& source, std::string* glb) {
  if (!source.loaded()) return Status::Error("glTF writer: source document not loaded");
  tinygltf::Model model = source.model();
  Status status = EmbedBuffersAndImages(source.name(), &model);
  if (!status.ok()) return status;
  return WriteModel(source.name(), &model, /*binary=*/true, glb);
}

Status MotionForCharacter(const Skeleton& source, const Motion& motion, const GltfCharacter& character,
                          Motion* out) {
  const Skeleton& target = character.skeleton;
  const int nj = target.num_joints();
  double scale = 1.0;
  if (source.unit().known() && target.unit().known()) {
    scale = source.unit().metres_per_unit / target.unit().metres_per_unit;
  }
  double size = 0.0;
  for (int j = 0; j < nj; ++j) size = std::max(size, target.offset(j).norm());
  std::vector<int> from(nj, -1);
  for (int j = 0; j < nj; ++j) {
    from[j] = source.FindJoint(target.name(j));
    const bool synthetic = !character.joint_nodes.empty() && character.joint_nodes[j] < 0;
    if (from[j] < 0) {
      if (synthetic) continue;
      return Status::Error("joint " + QuoteToken(target.name(j)) + " of the character is missing from the motion's skeleton");
    }
    const int p = target.parent(j);
    const int sp = source.parent(from[j]);
    const std::string target_parent = p >= 0 ? target.name(p) : "";
    std::string source_parent = sp >= 0 ? source.name(sp) : "";
    if (p >= 0 && from[p] < 0 && sp < 0) source_parent = target_parent;  // Below a missing gltf_root.
    if (target_parent != source_parent) {
      return Status::Error("joint " + QuoteToken(target.name(j)) + ": parent " + QuoteToken(source_parent) + " in the motion, '" +
                           target_parent + "' in the character");
    }
    if (p >= 0 && (scale * source.offset(from[j]) - target.offset(j)).norm() > 1e-3 * size) {
      return Status::Error("joint " + QuoteToken(target.name(j)) + ": offset differs from the character's by more than "
                           "1e-3 of its size (a different skeleton or unit?)");
    }
  }
  Motion result;
  result.frame_rate = motion.frame_rate;
  result.frames.resize(motion.frames.size());
  for (size_t f = 0; f < motion.frames.size(); ++f) {
    const Pose& in = motion.frames[f];
    if (static_cast<int>(in.rotations.size()) != source.num_joints() ||
        static_cast<int>(in.translations.size()) != source.num_joints()) {
      return Status::Error("frame " + std::to_string(f) + ": pose size differs from the skeleton's");
    }
    Pose& pose = result.frames[f];
    pose.rotations.resize(nj);
    pose.translations.resize(nj);
    for (int j = 0; j < nj; ++j) {
      if (from[j] < 0) {
        pose.rotations[j] = Eigen::Quaterniond::Identity();
        pose.translations[j] = target.offset(j);
        continue;
      }
      pose.rotations[j] = (target.rest_rotation(j).conjugate() * source.rest_rotation(from[j]) *
                           in.rotations[from[j]]).normalized();
      pose.translations[j] = scale * in.translations[from[j]];
    }
  }
  MakeSignContinuous(&result);
  *out = std::move(result);
  return Status::Ok();
}

namespace {

template <class AnyMotion>
Status WriteWithAnimation(const GltfDocument& source, const GltfCharacter& character, const AnyMotion& motion,
                          const std::string& animation_name, const std::string& path,
                          const GltfWriteOptions& options) {
  const std::string ext = FileExtension(path);
  if (ext != ".glb" && ext != ".gltf") {
    return Status::Error(path + ": glTF output must end in .glb or .gltf");
  }
  if (SameFile(path, source.name())) {
    return Status::Error(path + ": refusing to overwrite the input");
  }
  if (ext == ".glb") {  // Its keys written from the model, not copied (WriteGlbFile).
    tinygltf::Model model;
    Status status = ModelWithAnimation(source, character, AnimationSamples(motion), animation_name, true, options,
                                       &model);
    if (!status.ok()) return status;
    return WriteGlbFile(source.name(), &model, path);
  }
  std::string bytes;
  Status status = SerializeGltfWithAnimation(source, character, motion, animation_name,
                                             ext == ".glb", &bytes, options);
  if (!status.ok()) return status;
  return WriteFileAtomically(path, bytes);
}

}  // namespace

Status WriteGltfWithAnimation(const GltfDocument& source, const GltfCharacter& character,
                              const Motion& motion, const std::string& animation_name,
                              const std::string& path, const GltfWriteOptions& options) {
  return WriteWithAnimation(source, character, motion, animation_name, path, options);
}

Status WriteGltfWithAnimation(const GltfDocument& source, const GltfCharacter& character,
                              const CompactMotion& motion, const std::string& animation_name,
                              const std::string& path, const GltfWriteOptions& options) {
  return WriteWithAnimation(source, character, motion, animation_name, path, options);
}

}  // namespace mocapsolve
