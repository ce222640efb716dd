// SPDX-License-Identifier: BSD-3-Clause
#include "sonargrid/reference/reference_map.h"

#include <cmath>
#include <numbers>

namespace sg {

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

const char* surfaceName(Surface surface) {
  switch (surface) {
    case Surface::Specular:
      return "specular";
    case Surface::Diffuse:
      return "diffuse";
    case Surface::Unspecified:
      break;
  }
  return "";
}

std::optional<Surface> surfaceFromName(const std::string& name) {
  if (name == "specular") return Surface::Specular;
  if (name == "diffuse") return Surface::Diffuse;
  return std::nullopt;
}

ReferenceObject circleObject(std::string name, const ReferenceCircle& circle) {
  ReferenceObject o;
  o.name = std::move(name);
  o.closed = true;
  o.circle = circle;
  for (int k = 0; k < kCircleCorners; ++k) {
    const double a = 2.0 * std::numbers::pi * k / kCircleCorners;
    o.corners.emplace_back(circle.centre.x() + circle.radius * std::cos(a),
                           circle.centre.y() + circle.radius * std::sin(a));
  }
  return o;
}

std::string objectProblem(const ReferenceObject& object) {
  if (object.name.empty()) return "an object needs a non-empty name";
  if (object.circle) {
    const ReferenceCircle& c = *object.circle;
    if (!std::isfinite(c.centre.x()) || !std::isfinite(c.centre.y()))
      return "a circle's centre must be finite numbers";
    if (!std::isfinite(c.radius) || c.radius <= 0.0) return "a circle's radius must be above 0";
  }
  if (object.specularLimitDeg) {
    if (object.surface != Surface::Specular)
      return "specular_limit_deg needs \"surface\": \"specular\"";
    if (!(*object.specularLimitDeg > 0.0 && *object.specularLimitDeg <= 90.0))
      return "specular_limit_deg must be above 0 and at most 90 degrees";
  }
  if (object.corners.size() < 2) return "an object needs at least 2 corners";
  if (object.closed && object.corners.size() < 3) return "a closed object needs at least 3 corners";
  for (const Eigen::Vector2d& c : object.corners) {
    if (!std::isfinite(c.x()) || !std::isfinite(c.y())) return "corners must be finite numbers";
  }
  return {};
}

}  // namespace sg
