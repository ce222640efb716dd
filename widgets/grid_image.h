// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The picture of a grid: a pure function of the map, the palette, the overlays and the view
// transform (DESIGN.md, "Rendering and tests"). The raster view paints it, the OpenGL view draws
// the same cells through a palette texture and the same overlays through QPainter, the exports and
// the tests call it directly.

#include <QFlags>
#include <QImage>
#include <QPointF>
#include <QSize>
#include <memory>
#include <optional>
#include <vector>

#include "sonargrid/data/dataset.h"
#include "sonargrid/engine/occupancy_map.h"
#include "sonargrid/export/palette.h"
#include "sonargrid/reference/reference_map.h"

class QPainter;

namespace sg::ui {

// Where the view looks: the world point at the centre of the widget and the zoom. North (world +y)
// is up. A pixel (px, py) covers [px, px+1) x [py, py+1); its centre is (px + 0.5, py + 0.5).
struct ViewTransform {
  Position centre{0.0, 0.0};     // world metres at the widget's centre
  double pixelsPerMetre = 50.0;  // zoom

  QPointF toPixel(const Position& world, const QSize& size) const;
  Position toWorld(const QPointF& pixel, const QSize& size) const;

  // The transform showing the whole grid in `size` with `marginPx` pixels to spare on each side.
  static ViewTransform fitting(const GridSpec& grid, const QSize& size, int marginPx = 12);
  // The transform showing the box [low, high] (world metres) in `size`, centred.
  static ViewTransform fittingBox(const Position& low, const Position& high, const QSize& size,
                                  int marginPx = 12);
  bool operator==(const ViewTransform&) const = default;
};

enum class Overlay {
  Reference = 0x01,  // reference map lines
  Path = 0x02,       // robot path up to the current time
  Robot = 0x04,      // the robot at the current time
  Beams = 0x08,      // the current scan's beams, as cones
  Ring = 0x10,       // the sonar ring at the current pose
  Legend = 0x20,     // the 16 levels, bottom left
  Dmin = 0x40,       // filled cells coloured by their distance to the reference (dmin_overlay.h)
};
Q_DECLARE_FLAGS(Overlays, Overlay)
Q_DECLARE_OPERATORS_FOR_FLAGS(Overlays)
inline constexpr Overlays kAllOverlays{0x3f};  // the D_min tint is off until asked for

// One beam of the current scan: a cone from the transducer, `range` long (the maximum range for a
// reading without echo).
struct BeamCone {
  Pose2D sonar;  // world pose of the transducer
  double halfAngle = 0.0;
  double range = 0.0;
  bool echo = true;
  std::size_t sonarIndex = 0;  // the transducer's index in the ring
};

// Everything drawn besides the cells. World metres throughout.
struct GridScene {
  std::shared_ptr<const OccupancyMap> map;
  std::vector<std::vector<Position>>
      referenceLines;  // polylines (a closed object repeats corner 0)
  std::vector<Position> path;
  std::optional<Pose2D> robot;
  double robotRadius = 0.25;   // Pioneer 3-DX: about 0.5 m across
  std::vector<Pose2D> sonars;  // world poses of the ring's transducers at the robot's pose
  std::vector<BeamCone> beams;
  // The sonar whose beam is drawn highlighted (the one the beam-model view shows), if any.
  std::optional<std::size_t> highlightedSonar;
  // One pixel per cell (row 0 the grid's top row) drawn over the cells of a map on `dminSpec`
  // (Overlay::Dmin; dmin_overlay.h); not drawn over a map on another grid.
  std::shared_ptr<const QImage> dminTint;
  GridSpec dminSpec;
};

// The reference map as polylines in metres (a raster reference contributes none).
std::vector<std::vector<Position>> referencePolylines(const ReferenceMap& reference);

// The robot, its ring and the beams of scan `scan` of `data`, and the path up to that scan.
void placeRobot(GridScene& scene, const Dataset& data, PoseSource pose, std::size_t scan);

// Colour of the area outside the grid; none of the palette's levels is this close to it.
QColor backgroundColour();
// Colour of a never-observed cell (sg::kUnknownColour), in every rule: never that of a level.
QColor unknownColour();

// What the first view shows: where the robot went (every pose of the log, with `marginMetres`
// around it for the walls it saw) and the reference map, not the farthest phantom echo that
// stretched the grid. Empty (`low` > `high`) when there is neither.
struct FocusArea {
  Position low{1.0, 1.0};
  Position high{0.0, 0.0};
  bool empty() const { return !(low.x() <= high.x() && low.y() <= high.y()); }
};
FocusArea focusArea(const Dataset* data, PoseSource pose, const ReferenceMap* reference,
                    double marginMetres = 1.5);

// The cells alone: each pixel takes the level of the cell under its centre (nearest neighbour),
// coloured by `palette`, or unknownColour() when no reading ever wrote the cell (whatever its
// level); pixels outside the grid (or without a map) get backgroundColour().
QImage renderGridCells(const OccupancyMap* map, const LevelPalette& palette,
                       const ViewTransform& view, const QSize& size);

// Draws `cells`, one pixel per cell of `grid` (the image's top row the grid's northmost), over
// the grid's place in the view, clipped to `size` and without smoothing (a cell stays a square of
// one colour at any zoom): the vector export's cells and the D_min tint.
void drawCellImage(QPainter& painter, const QImage& cells, const GridSpec& grid,
                   const ViewTransform& view, const QSize& size);

// Draws the chosen overlays over an already painted grid (shared by every backend and the SVG
// export).
void paintOverlays(QPainter& painter, const GridScene& scene, const LevelPalette& palette,
                   Overlays overlays, const ViewTransform& view, const QSize& size);

// renderGridCells, then paintOverlays: the picture of the grid view.
QImage renderGridImage(const GridScene& scene, const LevelPalette& palette, Overlays overlays,
                       const ViewTransform& view, const QSize& size);

// The same picture as vector drawing (cells as one scaled image, overlays as paths): the SVG
// export.
void paintGridVector(QPainter& painter, const GridScene& scene, const LevelPalette& palette,
                     Overlays overlays, const ViewTransform& view, const QSize& size);

// Where the legend's swatch of `level` lies in a picture of `size` (tests read it back); level
// kLevels is the "unknown" swatch, set apart after level 15.
QRect legendSwatch(int level, const QSize& size);

// What the view reads out under the pointer.
struct CellReadout {
  Position world{0.0, 0.0};
  CellIndex cell{0, 0};
  bool inside = false;  // the point lies on the grid; the fields below are valid only then
  int level = 0;
  double probability = 0.5;
  double native = 0.0;
  bool observed = false;
};
CellReadout readCell(const OccupancyMap& map, const Position& world);
QString describeReadout(const CellReadout& r, const QString& nativeName);

}  // namespace sg::ui
