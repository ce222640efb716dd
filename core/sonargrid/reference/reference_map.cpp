#include "sonargrid/reference/reference_map.h"

#include <cmath>

namespace sg {

const char* lengthUnitName(LengthUnit unit) {
  switch (unit) {
    case LengthUnit::Metre:
      return "m";
    case LengthUnit::Centimetre:
      return "cm";
    case LengthUnit::Millimetre:
      return "mm";
  }
  return "m";
}

std::optional<LengthUnit> lengthUnitFromName(const std::string& name) {
  if (name == "m") return LengthUnit::Metre;
  if (name == "cm") return LengthUnit::Centimetre;
  if (name == "mm") return LengthUnit::Millimetre;
  return std::nullopt;
}

double metresPerUnit(LengthUnit unit) {
  switch (unit) {
    case LengthUnit::Metre:
      return 1.0;
    case LengthUnit::Centimetre:
      return 0.01;
    case LengthUnit::Millimetre:
      return 0.001;
  }
  return 1.0;
}

std::vector<std::pair<Position, Position>> ReferenceMap::edgesMetres(
    const ReferenceObject& object) const {
  std::vector<std::pair<Position, Position>> edges;
  const std::size_t n = object.corners.size();
  if (n == 0) return edges;
  if (n == 1) {
    edges.emplace_back(cornerMetres(object, 0), cornerMetres(object, 0));
    return edges;
  }
  for (std::size_t i = 0; i + 1 < n; ++i) {
    edges.emplace_back(cornerMetres(object, i), cornerMetres(object, i + 1));
  }
  if (object.closed) edges.emplace_back(cornerMetres(object, n - 1), cornerMetres(object, 0));
  return edges;
}

std::string objectProblem(const ReferenceObject& object) {
  if (object.name.empty()) return "an object needs a non-empty name";
  if (object.corners.size() < 2) return "an object needs at least 2 corners";
  if (object.closed && object.corners.size() < 3) return "a closed object needs at least 3 corners";
  for (const Eigen::Vector2d& c : object.corners) {
    if (!std::isfinite(c.x()) || !std::isfinite(c.y())) return "corners must be finite numbers";
  }
  return {};
}

}  // namespace sg
