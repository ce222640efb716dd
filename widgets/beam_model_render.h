// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// What the beam-model view draws, as pure functions of (settings, reading) → QImage, so it can be
// tested pixel by pixel offscreen. Every value drawn comes from SensorModel::evaluate (the same
// code the mapper's footprints go through); nothing here evaluates a model formula itself.
// Pictures after paper 002 Figs 2, 3 and 5: the 2-D map of P(occ) over the cone, the axial profile
// (α = 0) with its regions, and a 3-D surface of P over the plane.

#include <QColor>
#include <QImage>
#include <QPointF>
#include <QRect>
#include <QString>
#include <optional>
#include <vector>

#include "sonargrid/engine/mapper.h"

class QPainter;

namespace sg::ui {

struct BeamScene {
  sg::MapperSettings settings;
  double range = 2.0;     // the reading s, metres (Reading::kNoEcho for none)
  double maxRange = 5.0;  // of the transducer
};

// P(occ) in [0, 1] to colour: the 16-level certainty palette (export/palette.h) interpolated, so
// the beam view and the grid view agree.
QColor occupancyColour(double p);
// Where the model writes nothing (outside the beam, or beyond the reading).
QColor noUpdateColour();

// The plane the pictures cover: x forward along the acoustic axis from 0 to xMax, y across it in
// [−yMax, yMax], metres. Shared by both models of a comparison so they are drawn to one scale.
struct BeamExtent {
  double xMax = 1.0;
  double yMax = 1.0;
};
BeamExtent beamExtent(const std::vector<BeamScene>& scenes);

// Where a plane point (metres) lands in a map drawn into `plot` (equal scale on both axes, the
// sensor on the left, +y up).
struct ConeMapFrame {
  QRectF plot;  // the pixels the extent fills
  BeamExtent extent;
  QPointF toPixel(double x, double y) const;
  QPointF toPlane(const QPointF& pixel) const;
};
ConeMapFrame coneMapFrame(const BeamExtent& extent, const QRect& area);

// Where (r, P) lands in an axial profile drawn into `area` (r on the same scale as the map's x).
struct AxialProfileFrame {
  QRect plot;
  BeamExtent extent;
  QPointF toPixel(double r, double p) const;
};
AxialProfileFrame axialProfileFrame(const BeamExtent& extent, const QRect& area);

// One stretch of the acoustic axis in which the model puts a point in one region.
struct AxialSpan {
  double from = 0.0, to = 0.0;  // metres
  sg::BeamRegion region = sg::BeamRegion::Outside;
  QString label;  // in the model's words: "Region I" for Murphy and P1–P5, "occupied arc" for HPF
};
std::vector<AxialSpan> axialSpans(const BeamScene& scene, double xMax);

// Where each panel goes in an image of `size` holding `columns` models side by side.
struct BeamLayout {
  std::vector<QRect> title, map, profile, surface;  // one per scene
  QRect colourBar;
  bool stacked = false;  // the scenes one above the other rather than side by side
};
// The narrowest column that two scenes side by side may get; below it they stack.
inline constexpr int kMinBeamColumnWidth = 220;
// The lowest a panel (cone map, axial profile, surface) is drawn; a band lower than three of
// them drops the surface, lower than two the profile too. The panels are empty rects then.
inline constexpr int kMinBeamPanelHeight = 90;
BeamLayout beamLayout(QSize size, int columns);

// The whole picture: one column per scene (one or two; stacked rows when the columns would be
// narrower than kMinBeamColumnWidth; fewer panels in a low band), a shared colour bar.
QImage renderBeamModel(const std::vector<BeamScene>& scenes, QSize size);

// The panels, each inside `area`.
void drawConeMap(QPainter& painter, const BeamScene& scene, const BeamExtent& extent,
                 const QRect& area);
void drawAxialProfile(QPainter& painter, const BeamScene& scene, const BeamExtent& extent,
                      const QRect& area);
void drawSurface(QPainter& painter, const BeamScene& scene, const BeamExtent& extent,
                 const QRect& area);
void drawColourBar(QPainter& painter, const QRect& area);

}  // namespace sg::ui
