// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The D_min overlay: each filled cell of a built map coloured by D_min, the distance from its
// centre to the nearest cell of the reference's actual position grid (the distance IOP weighs,
// paper 000 eq 9), so the user sees where the map is wrong. Green on the reference, yellow at
// kDminYellowMm, red from kDminRedMm on; unfilled cells are not tinted.

#include <QColor>
#include <QImage>
#include <QSize>
#include <vector>

#include "sonargrid/engine/occupancy_map.h"

class QPainter;

namespace sg::ui {

struct GridScene;
struct ViewTransform;

inline constexpr double kDminYellowMm = 150.0;
inline constexpr double kDminRedMm = 300.0;

// The tint of a distance in millimetres (opaque; the overlay draws it translucent).
QColor dminColour(double mm);

// One pixel per cell, row 0 the grid's top row (world +y up): filled cells take
// dminColour(distanceCells[i] · cell size · 1000), the others are transparent. `distanceCells` is
// sg::distanceToApg() of the reference's APG on map.spec. An empty image when the sizes differ.
QImage dminTintImage(const OccupancyMap& map, const std::vector<float>& distanceCells);

// Draws scene.dminTint over the scene's map (when it is on the same grid) and a small scale at the
// top right.
void paintDminTint(QPainter& painter, const GridScene& scene, const ViewTransform& view,
                   const QSize& size);

}  // namespace sg::ui
