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

#include "sonargrid/grid_spec.h"

namespace sg {

enum class LengthUnit { Metre, Centimetre, Millimetre };

// "m", "cm", "mm": the spelling of the JSON `units` key.
const char* lengthUnitName(LengthUnit unit);
std::optional<LengthUnit> lengthUnitFromName(const std::string& name);
double metresPerUnit(LengthUnit unit);

struct ReferenceObject {
  std::string name;
  bool closed = false;  // a closed object has an edge from the last corner to the first
  std::vector<Eigen::Vector2d> corners;  // in the map's unit
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
