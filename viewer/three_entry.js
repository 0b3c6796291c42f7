// The part of three.js the viewer uses, bundled by scripts/viewer_tools.sh (esbuild) into
// one classic script that sets window.MOCAPSOLVE_THREE, so a page opened from file://
// needs no ES module loading (no importmap, no blob: or data: module URLs).
export * from 'three';
export { OrbitControls } from 'three/addons/controls/OrbitControls.js';
export { GLTFLoader } from 'three/addons/loaders/GLTFLoader.js';
