// A ViewScene as one self-contained HTML page: it opens from disk (file://), offline,
// with no server, in any current browser with WebGL.
//
// The page is the template viewer/viewer.html with, inlined:
//   - viewer/viewer.css and viewer/viewer.js (embedded into the binary at build time);
//   - the three.js runtime: three.js with its OrbitControls and GLTFLoader, bundled by
//     scripts/viewer_tools.sh (esbuild) into one classic script (build/tools/viewer/
//     three.bundle.js), found by FindViewerRuntime. A classic script rather than ES
//     modules because module scripts from file:// need an importmap of data:/blob: URLs,
//     which browsers treat unevenly; a global works everywhere;
//   - the data: one JSON header (names, labels, parents, intervals, notes) and binary
//     arrays in <script type="application/octet-stream"> elements, each the base64 of
//     its gzip stream (io/gzip.h; the page inflates it with DecompressionStream):
//       positions  int16, quantized per axis: x = origin + step * q (step = the array's
//                  extent / 65534, so <= 0.15 mm for a 10 m capture volume), -32768 = NaN,
//                  stored as d[i] = q[i] - q[i - delta] (delta = one frame's values,
//                  wrapping int16 arithmetic; q[i] = d[i] in the first frame);
//       states     uint8 (MarkerState);
//       curves     float32 (little-endian), NaN = no value;
//       characters .glb bytes, given to three.js' GLTFLoader.
//     A reference in the header: {"blob": i, "encoding": "int16", "compression": "gzip",
//     "delta": 3 #M, "origin": [...], "step": [...]}. A 10,000-frame take with 53 markers
//     and a 28k-vertex character makes about 8 MB (17 MB as plain base64).
//
// The page sets window.mocapsolveView = {ready, frames, setFrame(i), ...} (viewer.js).
#ifndef MOCAPSOLVE_VIEWER_VIEW_PAGE_H_
#define MOCAPSOLVE_VIEWER_VIEW_PAGE_H_

#include <string>

#include "kinematics/status.h"
#include "viewer/view_scene.h"

namespace mocapsolve {

// The three.js bundle's path: $MOCAPSOLVE_VIEWER_TOOLS/three.bundle.js if that variable is
// set, else build/tools/viewer/three.bundle.js relative to the running binary
// (<bin>/../tools/viewer/). The error says how to install it.
Status FindViewerRuntime(std::string* path);

// The page's HTML. `runtime` is the three.js bundle's text (ReadFileToString of
// FindViewerRuntime's path). Errors: a scene with no frames and no character, a
// frame rate that is not positive.
Status BuildViewPage(const ViewScene& scene, const std::string& runtime, std::string* html);

// Finds and reads the runtime, builds the page and writes it (WriteFileAtomically: inside
// the command's FileTransaction, published with its other outputs or not at all).
Status WriteViewPage(const std::string& path, const ViewScene& scene);

// Base64 (RFC 4648, with padding) of bytes.
std::string Base64(const std::string& bytes);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_VIEWER_VIEW_PAGE_H_
