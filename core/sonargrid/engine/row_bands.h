// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// How the mapper shares a batch's grid rows between its threads, so that each thread works on its
// own without waiting for the others (Mapper::integrateBands; with totals, for each chunk): one
// contiguous band of rows per thread, the bands of about equal work. A cone that lies inside one
// band costs only that band's thread its per-reading setup (the model's constants, the cone's
// edges and rows), where interleaved stripes made every thread pay it for nearly every reading.

#include <cstddef>
#include <span>
#include <vector>

#include "sonargrid/engine/footprint.h"
#include "sonargrid/engine/grid_spec.h"

namespace sg {

// Every kEstimateStride-th beam is looked at (estimatedRowWork): the estimate is made on one
// thread before the others start, and a quarter of a large batch's beams give the same bands to
// within a row or two, at a quarter of the cost (0.7 ms for the 100k workload's beams, all of
// them).
inline constexpr std::size_t kEstimateStride = 4;

// An estimate of the cells each grid row will be written in by `beams` (every kEstimateStride-th
// of them, from the first): a beam that reaches r
// cells (its range, or its transducer's maximum range where there is no echo and
// `writesWithoutEcho`; at most `reachCap` metres) adds r² spread evenly over the rows within r of
// its sensor. Only the shares matter: the cone's area is about r² times half its aperture, the
// same factor for every beam of one model. Rows outside the grid are left out.
std::vector<double> estimatedRowWork(std::span<const Beam> beams, const GridSpec& grid,
                                     double reachCap, bool writesWithoutEcho);

// `count` bands of consecutive rows covering [0, rowWork.size()) in order, band k ending at the
// first row where the work of the rows before it, with half of its own, reaches (k + 1) / count
// of the total (every row to the last band). Without any work, the rows are shared out evenly.
std::vector<RowWindow> balancedBands(std::span<const double> rowWork, unsigned count);

}  // namespace sg
