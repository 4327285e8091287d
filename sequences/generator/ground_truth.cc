#include "sequences/generator/ground_truth.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "util/atomic_file.h"

namespace sfm {
namespace {
namespace fs = std::filesystem;

// 17 significant digits: every double reads back to the same bits.
void Append(std::string* out, double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof(buffer), " %.17g", value);
  *out += buffer;
}
void Append(std::string* out, const Eigen::Vector2d& p) {
  Append(out, p.x());
  Append(out, p.y());
}
void Append(std::string* out, const Eigen::Vector3d& p) {
  Append(out, p.x());
  Append(out, p.y());
  Append(out, p.z());
}

std::string FrameFileName(int index) {
  char name[32];
  std::snprintf(name, sizeof(name), "%06d.txt", index);
  return name;
}

bool ParseSegmentEnd(const std::string& name, SegmentEnd* end) {
  for (SegmentEnd e : {SegmentEnd::kVertex, SegmentEnd::kOcclusion, SegmentEnd::kBorder}) {
    if (name == SegmentEndName(e)) {
      *end = e;
      return true;
    }
  }
  return false;
}

bool Fail(std::string* problem, const std::string& message) {
  *problem = message;
  return false;
}

// Reads the whitespace-separated fields of one line; every read must succeed and use the line up.
class LineReader {
 public:
  explicit LineReader(const std::string& line) : stream_(line) {}
  template <typename T>
  LineReader& operator>>(T& value) {
    if (!(stream_ >> value)) ok_ = false;
    return *this;
  }
  LineReader& operator>>(double& value) {
    std::string token;
    if (!(stream_ >> token)) {
      ok_ = false;
      return *this;
    }
    char* end = nullptr;
    value = std::strtod(token.c_str(), &end);
    if (end == token.c_str() || *end != '\0' || !std::isfinite(value)) ok_ = false;
    return *this;
  }
  LineReader& operator>>(Eigen::Vector2d& p) { return *this >> p.x() >> p.y(); }
  LineReader& operator>>(Eigen::Vector3d& p) { return *this >> p.x() >> p.y() >> p.z(); }
  bool Done() {
    std::string rest;
    return ok_ && !(stream_ >> rest);
  }

 private:
  std::istringstream stream_;
  bool ok_ = true;
};

// Calls `parse(keyword, line, error)` for each non-comment line of `path`.
template <typename Parse>
Status ForEachLine(const std::string& path, Parse parse) {
  std::ifstream in(path);
  if (!in) return Status::Error(path + ": cannot open");
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    const size_t first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos || line[first] == '#') continue;
    std::istringstream keyword_stream(line);
    std::string keyword;
    keyword_stream >> keyword;
    std::string problem;
    if (!parse(keyword, line.substr(line.find(keyword) + keyword.size()), &problem)) {
      return Status::Error(path + ":" + std::to_string(number) + ": " + problem);
    }
  }
  return Status::Ok();
}

Status ReadWireframe(const std::string& path, Wireframe* wireframe) {
  *wireframe = Wireframe();
  SFM_RETURN_IF_ERROR(ForEachLine(path, [&](const std::string& keyword, const std::string& rest, std::string* problem) {
    LineReader reader(rest);
    int id = -1;
    if (keyword == "vertex") {
      Eigen::Vector3d p = Eigen::Vector3d::Zero();
      reader >> id >> p;
      if (!reader.Done()) return Fail(problem, "expected 'vertex <id> <x> <y> <z>'");
      if (id != static_cast<int>(wireframe->vertices.size())) return Fail(problem, "vertex ids must count up from 0");
      wireframe->vertices.push_back(p);
      return true;
    }
    if (keyword == "edge") {
      WireEdge e;
      reader >> id >> e.vertex_a >> e.vertex_b >> e.face_a >> e.face_b;
      if (!reader.Done()) return Fail(problem, "expected 'edge <id> <vertex_a> <vertex_b> <face_a> <face_b>'");
      if (id != static_cast<int>(wireframe->edges.size())) return Fail(problem, "edge ids must count up from 0");
      const int n = static_cast<int>(wireframe->vertices.size());
      if (e.vertex_a < 0 || e.vertex_b < 0 || e.vertex_a >= n || e.vertex_b >= n) {
        return Fail(problem, "edge names a vertex not listed before it");
      }
      wireframe->edges.push_back(e);
      return true;
    }
    return Fail(problem, "unknown keyword '" + keyword + "'");
  }));
  if (wireframe->edges.empty()) return Status::Error(path + ": no edge");
  return Status::Ok();
}

Status ReadFrame(const std::string& path, const Wireframe& wireframe, FrameTruth* frame) {
  bool has_camera = false, has_frame = false;
  SFM_RETURN_IF_ERROR(ForEachLine(path, [&](const std::string& keyword, const std::string& rest, std::string* problem) {
    LineReader reader(rest);
    if (keyword == "frame") {
      reader >> frame->index >> frame->timestamp;
      if (!reader.Done()) return Fail(problem, "expected 'frame <index> <timestamp>'");
      has_frame = true;
      return true;
    }
    if (keyword == "camera") {
      Eigen::Vector3d t = Eigen::Vector3d::Zero();
      double qx = 0, qy = 0, qz = 0, qw = 1;
      reader >> t >> qx >> qy >> qz >> qw;
      if (!reader.Done()) return Fail(problem, "expected 'camera <tx> <ty> <tz> <qx> <qy> <qz> <qw>'");
      const Eigen::Quaterniond q(qw, qx, qy, qz);
      if (std::abs(q.norm() - 1) > 1e-6) return Fail(problem, "camera quaternion is not unit");
      frame->world_T_camera = Pose3(q.normalized(), t);
      has_camera = true;
      return true;
    }
    if (keyword == "vertex") {
      VisibleVertex v;
      reader >> v.vertex >> v.pixel >> v.pixel_distorted >> v.depth >> v.degree >> v.type;
      if (!reader.Done()) return Fail(problem, "expected 'vertex <id> <u> <v> <u_dist> <v_dist> <depth> <degree> <type>'");
      if (v.vertex < 0 || v.vertex >= static_cast<int>(wireframe.vertices.size())) {
        return Fail(problem, "unknown wireframe vertex " + std::to_string(v.vertex));
      }
      frame->vertices.push_back(v);
      return true;
    }
    if (keyword == "segment") {
      VisibleSegment s;
      std::string end0, end1;
      reader >> s.edge >> s.t[0] >> s.t[1] >> s.pixel[0] >> s.pixel[1] >> s.pixel_distorted[0] >>
          s.pixel_distorted[1] >> end0 >> end1;
      if (!reader.Done() || !ParseSegmentEnd(end0, &s.end[0]) || !ParseSegmentEnd(end1, &s.end[1])) {
        return Fail(problem, "expected 'segment <edge> <t0> <t1> <u0> <v0> <u1> <v1> <u0_dist> <v0_dist> <u1_dist> "
                          "<v1_dist> <end0> <end1>' with ends vertex, occlusion or border");
      }
      if (s.edge < 0 || s.edge >= static_cast<int>(wireframe.edges.size())) {
        return Fail(problem, "unknown wireframe edge " + std::to_string(s.edge));
      }
      frame->segments.push_back(s);
      return true;
    }
    return Fail(problem, "unknown keyword '" + keyword + "'");
  }));
  if (!has_frame || !has_camera) return Status::Error(path + ": missing 'frame' or 'camera' line");
  return Status::Ok();
}

}  // namespace

const char* SegmentEndName(SegmentEnd end) {
  switch (end) {
    case SegmentEnd::kVertex: return "vertex";
    case SegmentEnd::kOcclusion: return "occlusion";
    case SegmentEnd::kBorder: return "border";
  }
  return "?";
}

Status WriteGroundTruth(const std::string& sequence_dir, const Scene& scene, const GroundTruth& truth) {
  const fs::path root = fs::path(sequence_dir) / "truth";
  SFM_RETURN_IF_ERROR(EnsureWritableDirectory((root / "frames").string()));
  const Wireframe& wireframe = truth.wireframe;

  std::string text =
      "# junction-sfm synthetic ground truth: the 3D wireframe, world frame, metres (docs/generator.md)\n"
      "# vertex <id> <x> <y> <z>\n"
      "# edge <id> <vertex_a> <vertex_b> <face_a> <face_b>   (faces in scene.txt; face_b -1: one face)\n";
  for (size_t v = 0; v < wireframe.vertices.size(); ++v) {
    text += "vertex " + std::to_string(v);
    Append(&text, wireframe.vertices[v]);
    text += "\n";
  }
  for (size_t e = 0; e < wireframe.edges.size(); ++e) {
    const WireEdge& edge = wireframe.edges[e];
    text += "edge " + std::to_string(e) + " " + std::to_string(edge.vertex_a) + " " + std::to_string(edge.vertex_b) +
            " " + std::to_string(edge.face_a) + " " + std::to_string(edge.face_b) + "\n";
  }
  SFM_RETURN_IF_ERROR(WriteFileAtomically((root / "wireframe.txt").string(), text));

  text = "ply\nformat ascii 1.0\ncomment junction-sfm synthetic ground truth wireframe\nelement vertex " +
         std::to_string(wireframe.vertices.size()) + "\nproperty double x\nproperty double y\nproperty double z\n" +
         "element edge " + std::to_string(wireframe.edges.size()) +
         "\nproperty int vertex1\nproperty int vertex2\nend_header\n";
  for (const Eigen::Vector3d& p : wireframe.vertices) {
    std::string line;
    Append(&line, p);
    text += line.substr(1) + "\n";
  }
  for (const WireEdge& edge : wireframe.edges) {
    text += std::to_string(edge.vertex_a) + " " + std::to_string(edge.vertex_b) + "\n";
  }
  SFM_RETURN_IF_ERROR(WriteFileAtomically((root / "wireframe.ply").string(), text));

  text =
      "# junction-sfm synthetic scene: planar convex polygons, world frame, metres (docs/generator.md)\n"
      "# face <id> <object> <kind> <albedo> <emission> <grey level> <nx> <ny> <nz> <vertex count> <x y z>...\n";
  for (size_t f = 0; f < scene.faces.size(); ++f) {
    const Face& face = scene.faces[f];
    text += "face " + std::to_string(f) + " " + std::to_string(face.object) + " " + scene.objects[face.object].kind;
    Append(&text, face.albedo);
    Append(&text, face.emission);
    Append(&text, 255.0 * scene.lighting.Shade(face));
    Append(&text, face.normal);
    text += " " + std::to_string(face.vertices.size());
    for (const Eigen::Vector3d& p : face.vertices) Append(&text, p);
    text += "\n";
  }
  SFM_RETURN_IF_ERROR(WriteFileAtomically((root / "scene.txt").string(), text));

  for (const FrameTruth& frame : truth.frames) {
    text =
        "# junction-sfm synthetic ground truth of one frame (docs/generator.md)\n"
        "# frame <index> <timestamp>\n"
        "# camera <tx> <ty> <tz> <qx> <qy> <qz> <qw>   world_T_camera\n"
        "# vertex <id> <u> <v> <u_dist> <v_dist> <depth> <degree> <type>   (u v: undistorted image)\n"
        "# segment <edge> <t0> <t1> <u0> <v0> <u1> <v1> <u0_dist> <v0_dist> <u1_dist> <v1_dist> <end0> <end1>\n";
    text += "frame " + std::to_string(frame.index);
    Append(&text, frame.timestamp);
    text += "\ncamera";
    const Eigen::Quaterniond& q = frame.world_T_camera.rotation;
    Append(&text, frame.world_T_camera.translation);
    Append(&text, Eigen::Vector3d(q.x(), q.y(), q.z()));
    Append(&text, q.w());
    text += "\n";
    for (const VisibleVertex& v : frame.vertices) {
      text += "vertex " + std::to_string(v.vertex);
      Append(&text, v.pixel);
      Append(&text, v.pixel_distorted);
      Append(&text, v.depth);
      text += " " + std::to_string(v.degree) + " " + v.type + "\n";
    }
    for (const VisibleSegment& s : frame.segments) {
      text += "segment " + std::to_string(s.edge);
      Append(&text, s.t[0]);
      Append(&text, s.t[1]);
      Append(&text, s.pixel[0]);
      Append(&text, s.pixel[1]);
      Append(&text, s.pixel_distorted[0]);
      Append(&text, s.pixel_distorted[1]);
      text += std::string(" ") + SegmentEndName(s.end[0]) + " " + SegmentEndName(s.end[1]) + "\n";
    }
    SFM_RETURN_IF_ERROR(WriteFileAtomically((root / "frames" / FrameFileName(frame.index)).string(), text));
  }
  return Status::Ok();
}

Status ReadGroundTruth(const std::string& sequence_dir, GroundTruth* truth) {
  *truth = GroundTruth();
  const fs::path root = fs::path(sequence_dir) / "truth";
  SFM_RETURN_IF_ERROR(ReadWireframe((root / "wireframe.txt").string(), &truth->wireframe));
  for (int index = 0;; ++index) {
    const fs::path path = root / "frames" / FrameFileName(index);
    if (!fs::exists(path)) break;
    FrameTruth frame;
    SFM_RETURN_IF_ERROR(ReadFrame(path.string(), truth->wireframe, &frame));
    if (frame.index != index) {
      return Status::Error(path.string() + ": 'frame' says " + std::to_string(frame.index));
    }
    truth->frames.push_back(std::move(frame));
  }
  if (truth->frames.empty()) return Status::Error((root / "frames").string() + ": no frame file (000000.txt)");
  return Status::Ok();
}

}  // namespace sfm
