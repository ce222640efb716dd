#pragma once
// What one reading writes into the grid: the sensor model's output, which the update rule consumes
// (the model / storage split of DESIGN.md). Every model fills all three values consistently:
//   empty     pE in [0, 1], evidence that the cell is free      (paper 000 eq 1, paper 001 §2.1.1)
//   occupied  pO in [0, 1], evidence that the cell is occupied  (paper 000 eq 4, paper 001 §2.1.2)
//   probability  P(occupied | this reading) as the model's likelihood, 0.5 = no information
//                (paper 002 §3.1, P(s|Occupied)); rules that need one number read this.

#include <cmath>
#include <cstdint>
#include <vector>

#include "sonargrid/pose.h"

namespace sg {

struct CellEvidence {
  std::uint32_t cell = 0;  // linear index into the grid
  double empty = 0.0;
  double occupied = 0.0;
  double probability = 0.5;
};

struct Footprint {
  std::vector<CellEvidence> cells;
  void clear() { cells.clear(); }
};

// One reading placed in the world.
struct Beam {
  Pose2D sensor;         // world pose of the transducer
  double range = 0.0;    // metres, or Reading::kNoEcho
  double maxRange = 5.0; // of the transducer: a no-echo reading clears at most this far
  bool echo() const { return std::isfinite(range); }
};

}  // namespace sg
