#include "frontend/junctions/junction.h"

namespace sfm {

const char* JunctionTypeName(JunctionType type) {
  switch (type) {
    case JunctionType::kL:
      return "L";
    case JunctionType::kY:
      return "Y";
    case JunctionType::kArrow:
      return "ARROW";
    case JunctionType::kT:
      return "T";
    case JunctionType::kX:
      return "X";
    case JunctionType::kN:
      return "N";
  }
  return "N";
}

}  // namespace sfm
