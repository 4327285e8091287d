#pragma once

// The JavaScript that report.html inlines, compiled in from the files that pipeline/CMakeLists.txt
// names (null-terminated, as in the files, without leading and trailing white space).
namespace sfm::report_assets {

extern const char kThreeCore[];      // three.js: build/three.core.min.js (vendor/three/)
extern const char kThreeModule[];    // three.js: build/three.module.min.js, imports "./three.core.min.js"
extern const char kOrbitControls[];  // three.js: examples/jsm/controls/OrbitControls.js, imports "three"
extern const char kViewer[];         // report/view3d.js: the 3D view, an ES module
extern const char kThreeVersion[];   // the vendored three.js release, e.g. "0.185.1"

}  // namespace sfm::report_assets
