// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// A reference map: what the world really looks like, as a user measures it with a tape (paper 000
// §3: "the absolute coordinates of the corners comprising each object are measured"). Objects are
// named lists of corners, joined by straight edges, open (a wall run) or closed (a box, a room).
// A reference imported from a ROS map_server image has no corners: it carries an obstacle raster.
//
// Corners are kept in the unit of the file they came from, so that a reference saved again writes
// back the very numbers the user typed (docs/metrics.md, "Reference maps").

#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "sonargrid/base/length_unit.h"
#include "sonargrid/engine/grid_spec.h"

namespace sg {

// How an object's surface returns sound (docs/simulator.md). Scoring ignores it; the simulator
// reads it. Unspecified takes the simulator's default (specular, at its default limit).
enum class Surface { Unspecified, Specular, Diffuse };

// "specular", "diffuse": the spelling of the JSON `surface` key.
const char* surfaceName(Surface surface);
std::optional<Surface> surfaceFromName(const std::string& name);

// A round object (a pole), in the map's unit.
struct ReferenceCircle {
  Eigen::Vector2d centre{0.0, 0.0};
  double radius = 0.0;
};

// Corners kept for a circle, so that every metric can treat it as the polygon it draws.
inline constexpr int kCircleCorners = 16;

struct ReferenceObject {
  std::string name;
  bool closed = false;  // a closed object has an edge from the last corner to the first
  std::vector<Eigen::Vector2d> corners;  // in the map's unit
  Surface surface = Surface::Unspecified;
  std::optional<double> specularLimitDeg{};  // only with Surface::Specular; degrees in (0, 90]
  // A circle: `corners` then hold the regular kCircleCorners-gon inscribed in it (closed).
  std::optional<ReferenceCircle> circle{};
};

// A circle object with its polygon corners filled in.
ReferenceObject circleObject(std::string name, const ReferenceCircle& circle);

// Where the robot starts, in the map's unit (heading in degrees, counter-clockwise from +x).
struct StartPose {
  Eigen::Vector2d position{0.0, 0.0};
  double headingDeg = 0.0;
};

// What a reference raster says about one of its cells (ROS map_server trinary reading).
enum class RasterCell : std::uint8_t { Free = 0, Obstacle = 1, Unknown = 2 };

// Obstacle cells from an occupancy image, on the image's own grid. When it is scored against a map
// of another resolution, an obstacle cell marks every map cell it overlaps (docs/metrics.md).
struct ObstacleRaster {
  GridSpec spec;
  std::vector<RasterCell> cells;  // row-major, row 0 at the bottom (GridSpec convention)
};

struct ReferenceMap {
  LengthUnit unit = LengthUnit::Metre;
  std::vector<ReferenceObject> objects;
  std::optional<ObstacleRaster> raster;
  std::optional<StartPose> start{};

  double metresPerUnit() const { return sg::metresPerUnit(unit); }
  // A corner of an object in world metres.
  Position cornerMetres(const ReferenceObject& object, std::size_t corner) const {
    return object.corners[corner] * metresPerUnit();
  }
  // Every edge as a pair of corners in metres: consecutive corners, plus last-to-first when closed.
  std::vector<std::pair<Position, Position>> edgesMetres(const ReferenceObject& object) const;
};

// The rules every reader and the JSON writer enforce. Returns an empty string when the object is
// valid, otherwise what is wrong with it (e.g. "a closed object needs at least 3 corners").
std::string objectProblem(const ReferenceObject& object);

}  // namespace sg
