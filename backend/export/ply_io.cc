#include "backend/export/ply_io.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <limits>
#include <sstream>
#include <utility>
#include <vector>

#include "util/atomic_file.h"
#include "util/number_text.h"
#include "util/text_file.h"

namespace sfm {
namespace {

struct ElementHeader {
  std::string name;
  long count = 0;
  std::vector<std::string> properties;  // scalar property names, in file order
  bool has_list_property = false;
};

bool ParseFiniteDouble(const std::string& token, double* value) {
  return ParseDouble(token, value) && std::isfinite(*value);
}

bool ParseLong(const std::string& token, long* value) {
  errno = 0;
  char* end = nullptr;
  *value = std::strtol(token.c_str(), &end, 10);
  return end != token.c_str() && *end == '\0' && errno != ERANGE;
}

// Index of `name` among the element's properties, or -1.
int PropertyIndex(const ElementHeader& element, const std::string& name) {
  const auto it = std::find(element.properties.begin(), element.properties.end(), name);
  return it == element.properties.end() ? -1 : static_cast<int>(it - element.properties.begin());
}

// Reads the header up to end_header; `line_number` is left on the end_header line.
Status ReadHeader(std::istream& in, const std::string& path, int* line_number,
                  std::vector<ElementHeader>* elements) {
  std::string line;
  bool saw_format = false;
  while (std::getline(in, line)) {
    ++*line_number;
    const std::string where = path + ":" + std::to_string(*line_number) + ": ";
    const std::vector<std::string> words = SplitWords(line);
    if (*line_number == 1) {
      if (words.size() != 1 || words[0] != "ply")
        return Status::Error(where + "not a PLY file (no 'ply' line)");
      continue;
    }
    if (words.empty() || words[0] == "comment" || words[0] == "obj_info") continue;
    if (words[0] == "end_header") {
      if (!saw_format) return Status::Error(where + "header has no 'format' line");
      return Status::Ok();
    }
    if (words[0] == "format") {
      if (words.size() != 3 || words[2] != "1.0") return Status::Error(where + "malformed format line");
      if (words[1] != "ascii") {
        return Status::Error(where + "PLY format '" + words[1] + "' is not supported (ASCII only)");
      }
      saw_format = true;
    } else if (words[0] == "element") {
      ElementHeader element;
      if (words.size() != 3 || !ParseLong(words[2], &element.count) || element.count < 0) {
        return Status::Error(where + "expected 'element <name> <count>'");
      }
      element.name = words[1];
      elements->push_back(element);
    } else if (words[0] == "property") {
      if (elements->empty()) return Status::Error(where + "property before any element");
      if (words.size() == 5 && words[1] == "list") {
        elements->back().has_list_property = true;
      } else if (words.size() == 3) {
        elements->back().properties.push_back(words[2]);
      } else {
        return Status::Error(where + "expected 'property <type> <name>'");
      }
    } else {
      return Status::Error(where + "unexpected header line '" + line + "'");
    }
  }
  return Status::Error(path + ": header has no 'end_header' line");
}

}  // namespace

Status FormatPly(const ReconstructedWireframe& wireframe, std::string* text) {
  const size_t vertex_count = wireframe.vertices.size();
  std::string out = "ply\nformat ascii 1.0\n";
  out += "element vertex " + std::to_string(vertex_count) + "\n";
  out += "property double x\nproperty double y\nproperty double z\n";
  const bool with_tracks = !wireframe.track_ids.empty();
  if (with_tracks && wireframe.track_ids.size() != vertex_count) {
    return Status::Error(std::to_string(wireframe.track_ids.size()) + " track ids for " +
                         std::to_string(vertex_count) + " vertices");
  }
  if (with_tracks) out += "property int track_id\n";
  out += "element edge " + std::to_string(wireframe.edges.size()) + "\n";
  out += "property int vertex1\nproperty int vertex2\nend_header\n";
  for (size_t i = 0; i < vertex_count; ++i) {
    const Eigen::Vector3d& v = wireframe.vertices[i];
    if (!v.allFinite()) return Status::Error("vertex " + std::to_string(i) + " has a non-finite coordinate");
    out += ShortestNumberText(v.x()) + " " + ShortestNumberText(v.y()) + " " + ShortestNumberText(v.z());
    out += with_tracks ? " " + std::to_string(wireframe.track_ids[i]) + "\n" : "\n";
  }
  for (size_t i = 0; i < wireframe.edges.size(); ++i) {
    const auto [a, b] = wireframe.edges[i];
    for (const int index : {a, b}) {
      if (index < 0 || static_cast<size_t>(index) >= vertex_count) {
        return Status::Error("edge " + std::to_string(i) + " refers to vertex " + std::to_string(index) +
                             ", outside the " + std::to_string(vertex_count) + " vertices");
      }
    }
    out += std::to_string(a) + " " + std::to_string(b) + "\n";
  }
  *text = std::move(out);
  return Status::Ok();
}

Status WritePly(const std::string& path, const ReconstructedWireframe& wireframe) {
  std::string text;
  const Status formatted = FormatPly(wireframe, &text);
  if (!formatted.ok()) return Status::Error(path + ": " + formatted.message());
  return WriteFileAtomically(path, text);
}

Status ReadPly(const std::string& path, ReconstructedWireframe* wireframe) {
  wireframe->vertices.clear();
  wireframe->edges.clear();
  wireframe->track_ids.clear();
  std::ifstream in(path);
  if (!in) return Status::Error(path + ": cannot open (" + std::strerror(errno) + ")");
  int line_number = 0;
  std::vector<ElementHeader> elements;
  SFM_RETURN_IF_ERROR(ReadHeader(in, path, &line_number, &elements));

  bool saw_vertex = false;
  std::vector<std::pair<long, long>> edges;  // checked against the vertex count at the end
  for (const ElementHeader& element : elements) {
    const bool is_vertex = element.name == "vertex";
    const bool is_edge = element.name == "edge";
    const int first = PropertyIndex(element, is_vertex ? "x" : "vertex1");
    const int second = PropertyIndex(element, is_vertex ? "y" : "vertex2");
    const int third = PropertyIndex(element, "z");
    const int track = is_vertex ? PropertyIndex(element, "track_id") : -1;
    if ((is_vertex || is_edge) && element.has_list_property) {
      return Status::Error(path + ": element " + element.name + " has a list property (not supported)");
    }
    if ((is_vertex && (first < 0 || second < 0 || third < 0)) || (is_edge && (first < 0 || second < 0))) {
      return Status::Error(path + ": element " + element.name + " lacks the properties " +
                           (is_vertex ? "x y z" : "vertex1 vertex2"));
    }
    saw_vertex = saw_vertex || is_vertex;
    for (long item = 0; item < element.count; ++item) {
      std::string line;
      if (!std::getline(in, line)) {
        return Status::Error(path + ": ends after " + std::to_string(item) + " of " +
                             std::to_string(element.count) + " " + element.name + " lines");
      }
      ++line_number;
      if (!is_vertex && !is_edge) continue;
      const std::string where = path + ":" + std::to_string(line_number) + ": ";
      const std::vector<std::string> words = SplitWords(line);
      if (words.size() != element.properties.size()) {
        return Status::Error(where + "expected " + std::to_string(element.properties.size()) +
                             " numbers, found " + std::to_string(words.size()));
      }
      if (is_vertex) {
        Eigen::Vector3d v;
        if (!ParseFiniteDouble(words[first], &v.x()) || !ParseFiniteDouble(words[second], &v.y()) ||
            !ParseFiniteDouble(words[third], &v.z())) {
          return Status::Error(where + "vertex coordinates are not finite numbers");
        }
        wireframe->vertices.push_back(v);
        if (track >= 0) {
          long id = 0;
          if (!ParseLong(words[track], &id) || id < -1 || id > std::numeric_limits<int>::max()) {
            return Status::Error(where + "track_id is not an integer >= -1");
          }
          wireframe->track_ids.push_back(static_cast<int>(id));
        }
      } else {
        long a = 0, b = 0;
        if (!ParseLong(words[first], &a) || !ParseLong(words[second], &b)) {
          return Status::Error(where + "edge vertex indices are not integers");
        }
        edges.emplace_back(a, b);
      }
    }
  }
  if (!saw_vertex) return Status::Error(path + ": no 'element vertex'");
  const long vertex_count = static_cast<long>(wireframe->vertices.size());
  for (const auto& [a, b] : edges) {
    if (a < 0 || a >= vertex_count || b < 0 || b >= vertex_count) {
      return Status::Error(path + ": edge " + std::to_string(a) + " " + std::to_string(b) +
                           " refers to a vertex outside the " + std::to_string(vertex_count) + " vertices");
    }
    wireframe->edges.emplace_back(static_cast<int>(a), static_cast<int>(b));
  }
  return Status::Ok();
}

}  // namespace sfm
