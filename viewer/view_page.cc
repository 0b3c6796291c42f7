#include "viewer/view_page.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <utility>
#include <vector>

#include "io/atomic_file.h"
#include "io/gzip.h"
#include "io/html_escape.h"
#include "io/json_writer.h"

namespace mocapsolve {

// viewer/viewer.html, .css and .js (build/generated/viewer_sources.cc, cmake/embed_files.cmake).
extern const char kViewerHtml[];
extern const char kViewerCss[];
extern const char kViewerJs[];

namespace {

// Binary arrays, each one <script type="application/octet-stream"> element: base64 of
// their gzip stream.
class Blobs {
 public:
  // Returns the JSON reference {"blob": i, "encoding": ..., "compression": "gzip"}.
  JsonObject Add(const std::string& bytes, const std::string& encoding) {
    std::string gz;
    const Status status = GzipCompress(bytes, &gz);
    if (!status.ok() && status_.ok()) status_ = status;
    blobs_.push_back(Base64(gz));
    JsonObject ref;
    ref.Add("blob", static_cast<int>(blobs_.size()) - 1).Add("encoding", encoding).Add("compression", "gzip");
    return ref;
  }
  const std::vector<std::string>& blobs() const { return blobs_; }
  // Blob i's text, taken out (the page is assembled from them one at a time: a long
  // take's blobs are not held twice).
  std::string Take(size_t i) { return std::move(blobs_[i]); }
  const Status& status() const { return status_; }  // The first failure.

 private:
  std::vector<std::string> blobs_;
  Status status_ = Status::Ok();
};

template <typename T>
std::string Bytes(const std::vector<T>& values) {
  return std::string(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(T));
}

// #F x #N x 3 positions as int16 per axis over the finite values' box (-32768 = NaN),
// stored as differences from the previous frame (wrapping int16 arithmetic, so lossless
// whatever the values; `delta` = 3 #N values back): a moving point's small steps
// compress to a third of the bytes of its positions.
JsonObject AddPositions(const std::vector<float>& xyz, size_t values_per_frame, Blobs* blobs) {
  double low[3], high[3];
  for (int k = 0; k < 3; ++k) low[k] = std::numeric_limits<double>::infinity(), high[k] = -low[k];
  for (size_t i = 0; i + 2 < xyz.size(); i += 3) {
    for (int k = 0; k < 3; ++k) {
      if (!std::isfinite(xyz[i + k])) continue;
      low[k] = std::min<double>(low[k], xyz[i + k]);
      high[k] = std::max<double>(high[k], xyz[i + k]);
    }
  }
  double origin[3], step[3];
  for (int k = 0; k < 3; ++k) {
    if (!(low[k] <= high[k])) low[k] = high[k] = 0.0;
    step[k] = std::max((high[k] - low[k]) / 65534.0, 1e-9);
    origin[k] = 0.5 * (low[k] + high[k]);
  }
  std::vector<std::int16_t> q(xyz.size());
  for (size_t i = 0; i < xyz.size(); ++i) {
    const int k = static_cast<int>(i % 3);
    if (!std::isfinite(xyz[i])) {
      q[i] = -32768;
      continue;
    }
    const double v = std::round((xyz[i] - origin[k]) / step[k]);
    q[i] = static_cast<std::int16_t>(std::clamp(v, -32767.0, 32767.0));
  }
  const size_t stride = std::max<size_t>(values_per_frame, 1);
  std::vector<std::uint16_t> delta(q.size());
  for (size_t i = 0; i < q.size(); ++i) {
    const std::uint16_t previous = i >= stride ? static_cast<std::uint16_t>(q[i - stride]) : 0;
    delta[i] = static_cast<std::uint16_t>(static_cast<std::uint16_t>(q[i]) - previous);
  }
  JsonObject ref = blobs->Add(Bytes(delta), "int16");
  ref.Add("delta", static_cast<int>(stride))
      .Add("origin", std::vector<JsonValue>{origin[0], origin[1], origin[2]})
      .Add("step", std::vector<JsonValue>{step[0], step[1], step[2]});
  return ref;
}

std::vector<JsonValue> Strings(const std::vector<std::string>& texts) {
  return std::vector<JsonValue>(texts.begin(), texts.end());
}

// JSON inside <script>: every '<' (in JSON text it can only stand inside a string) as the
// escape \u003c, so that no "</script" ends the element early and no "<!--" followed by
// "<script" switches the parser into the double-escaped state, which swallows the rest of
// the page into the element (a marker label, joint or file name is enough).
std::string JsonScriptSafe(const std::string& json) {
  std::string out;
  out.reserve(json.size());
  for (const char c : json) {
    if (c == '<') {
      out += "\\u003c";
    } else {
      out += c;
    }
  }
  return out;
}

// Our own JavaScript inside <script>: "</" would end the element early.
std::string ScriptSafe(std::string text) {
  for (size_t at = text.find("</"); at != std::string::npos; at = text.find("</", at + 3)) {
    text.replace(at, 2, "<\\/");
  }
  return text;
}

// Replaces each marker of the template by its text, in the template's order, each
// searched after the previous replacement (so inserted text is never searched).
std::string FillTemplate(const std::string& page, const std::vector<std::pair<std::string, std::string>>& fills) {
  std::string out;
  size_t at = 0;
  for (const auto& [marker, text] : fills) {
    const size_t found = page.find(marker, at);
    if (found == std::string::npos) continue;
    out.append(page, at, found - at);
    out += text;
    at = found + marker.size();
  }
  out.append(page, at, std::string::npos);
  return out;
}

}  // namespace

std::string Base64(const std::string& bytes) {
  static const char kAlphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  const auto* b = reinterpret_cast<const unsigned char*>(bytes.data());
  size_t i = 0;
  for (; i + 2 < bytes.size(); i += 3) {
    const std::uint32_t v = (b[i] << 16) | (b[i + 1] << 8) | b[i + 2];
    out += kAlphabet[v >> 18];
    out += kAlphabet[(v >> 12) & 63];
    out += kAlphabet[(v >> 6) & 63];
    out += kAlphabet[v & 63];
  }
  if (i < bytes.size()) {
    const std::uint32_t v = (b[i] << 16) | (i + 1 < bytes.size() ? b[i + 1] << 8 : 0);
    out += kAlphabet[v >> 18];
    out += kAlphabet[(v >> 12) & 63];
    out += i + 1 < bytes.size() ? kAlphabet[(v >> 6) & 63] : '=';
    out += '=';
  }
  return out;
}

Status FindViewerRuntime(std::string* path) {
  std::string candidate;
  if (const char* tools = std::getenv("MOCAPSOLVE_VIEWER_TOOLS"); tools != nullptr && *tools != '\0') {
    candidate = std::string(tools) + "/three.bundle.js";
  } else {
    char exe[4096];
    const ssize_t n = readlink("/proc/self/exe", exe, sizeof(exe) - 1);
    std::string dir = n > 0 ? std::string(exe, n) : std::string("./mocapsolve");
    dir = dir.substr(0, dir.rfind('/') == std::string::npos ? 0 : dir.rfind('/'));
    candidate = (dir.empty() ? "." : dir) + "/../tools/viewer/three.bundle.js";
  }
  if (access(candidate.c_str(), R_OK) != 0) {
    return Status::Error("the viewer's three.js runtime is not installed (no " + candidate +
                         "): run scripts/viewer_tools.sh (scripts/setup.sh does), or set MOCAPSOLVE_VIEWER_TOOLS");
  }
  *path = candidate;
  return Status::Ok();
}

Status BuildViewPage(const ViewScene& scene, const std::string& runtime, std::string* html) {
  if (!(scene.frame_rate > 0.0) || !std::isfinite(scene.frame_rate)) {
    return Status::Error("view: the frame rate must be positive");
  }
  if (scene.num_frames() == 0 && scene.characters.empty()) {
    return Status::Error("view: nothing to show (no markers, motion or character with frames)");
  }
  Blobs blobs;
  std::vector<JsonObject> markers;
  for (const ViewMarkers& m : scene.markers) {
    JsonObject o;
    o.Add("name", m.name).Add("labels", Strings(m.labels)).Add("frames", m.num_frames)
        .Add("positions", AddPositions(m.positions, 3 * m.labels.size(), &blobs)).Add("states", blobs.Add(Bytes(m.states), "uint8"));
    markers.push_back(o);
  }
  std::vector<JsonObject> skeletons;
  for (const ViewSkeleton& s : scene.skeletons) {
    std::vector<JsonValue> parents(s.parents.begin(), s.parents.end());
    JsonObject o;
    o.Add("name", s.name).Add("joints", Strings(s.joint_names)).Add("parents", parents).Add("frames", s.num_frames)
        .Add("ghost", s.ghost).Add("positions", AddPositions(s.positions, 3 * s.joint_names.size(), &blobs));
    skeletons.push_back(o);
  }
  std::vector<JsonObject> characters;
  for (const ViewCharacter& c : scene.characters) {
    JsonObject o;
    o.Add("name", c.name).Add("animation", c.animation).Add("glb", blobs.Add(c.glb, "glb"));
    characters.push_back(o);
  }
  std::vector<JsonValue> intervals;
  for (const ViewInterval& i : scene.intervals) {
    intervals.push_back(JsonValue::Raw("[" + std::to_string(i.marker) + "," + std::to_string(i.first) + "," +
                                       std::to_string(i.last) + "," +
                                       std::to_string(static_cast<int>(i.state)) + "]"));
  }
  std::vector<JsonObject> curves;
  for (const ViewCurve& c : scene.curves) {
    JsonObject o;
    o.Add("name", c.name).Add("unit", c.unit).Add("values", blobs.Add(Bytes(c.values), "float32"));
    curves.push_back(o);
  }
  std::vector<JsonValue> states;
  for (int s = 0; s <= static_cast<int>(MarkerState::kRepairedUnlabelled); ++s) {
    states.push_back(MarkerStateName(static_cast<MarkerState>(s)));
  }
  if (!blobs.status().ok()) return Status::Error("view: " + blobs.status().message());
  JsonObject meta;
  meta.Add("format", "mocapsolve.view").Add("version", 2).Add("title", scene.title)
      .Add("frame_rate", scene.frame_rate).Add("frames", scene.num_frames()).Add("notes", Strings(scene.notes))
      .Add("state_names", states).Add("markers", markers).Add("skeletons", skeletons)
      .Add("characters", characters).Add("intervals", intervals).Add("curves", curves);

  std::string data = "<script type=\"application/json\" id=\"mv-meta\">" + JsonScriptSafe(meta.ToString(false)) +
                     "</script>\n";
  for (size_t i = 0; i < blobs.blobs().size(); ++i) {
    data += "<script type=\"application/octet-stream\" id=\"mv-blob-" + std::to_string(i) + "\">";
    data += blobs.Take(i);
    data += "</script>\n";
  }
  // The fills built in place, the data moved in: an initializer list would copy the data
  // (the page's bulk) twice more.
  std::vector<std::pair<std::string, std::string>> fills;
  fills.emplace_back("@TITLE@", HtmlEscape(scene.title.empty() ? "mocapsolve view" : scene.title));
  fills.emplace_back("/*@CSS@*/", kViewerCss);
  fills.emplace_back("<!--@DATA@-->", std::move(data));
  fills.emplace_back("/*@THREE@*/", ScriptSafe(runtime));
  fills.emplace_back("/*@VIEWER@*/", ScriptSafe(kViewerJs));
  *html = FillTemplate(kViewerHtml, fills);
  return Status::Ok();
}

Status WriteViewPage(const std::string& path, const ViewScene& scene) {
  std::string runtime_path, runtime, html;
  Status status = FindViewerRuntime(&runtime_path);
  if (status.ok()) status = ReadFileToString(runtime_path, &runtime);
  if (status.ok()) status = BuildViewPage(scene, runtime, &html);
  if (!status.ok()) return Status::Error(path + ": " + status.message());
  return WriteFileAtomically(path, html);
}

}  // namespace mocapsolve
