// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Occupancy grid maps from a forward sensor model, learned by expectation–maximisation over a whole
// log (Thrun, "Learning occupancy grid maps with forward sensor models", Autonomous Robots 15,
// 2003; Thrun, Burgard & Fox, Probabilistic Robotics, §9.4). docs/forward-model.md states the
// model, the EM and the choices made where the paper leaves room.
//
// Every other model of SonarGrid is an inverse model: it turns one reading into evidence for each
// cell, and a rule adds the evidence up cell by cell. The forward model says instead how a map
// produces a reading, and EM finds the map that explains all readings together: a reading through a
// doorway is then explained by the far wall only if the doorway is free, so the cone of a reading
// that saw the door frame does not close the door.
//
// The forward model (the paper's; docs/forward-model.md, "The model"). A reading z from a
// transducer of maximum range z_max meets the cells whose centres lie in its cone (aperture ω),
// ordered by their distance d_k from the transducer (ties by cell index): the order in which they
// can be detected. Each cell k is occupied with probability m_k. The reading is
//   - random, with probability p_rand: uniform over [0, z_max];
//   - a max-range failure, with probability p_max: no echo whatever the cone meets (a specular
//     wall; the beam model's max-range component, Probabilistic Robotics §6.3.1);
//   - otherwise caused by the first occupied cell of the cone, as z ~ N(d_k, σ²);
//   - otherwise, when no cell of the cone is occupied, a max-range reading (no echo).
// So, with w = 1 − p_rand − p_max, for an echo z, in range bins of width Δ (the cell size, which
// makes the no-echo event and the echoes one measure):
//   p(z | m) = Δ [ p_rand / z_max + w Σ_k m_k Π_{k'<k} (1 − m_{k'}) N(z; d_k, σ²) ]
// and for a no-echo reading
//   p(no echo | m) = p_rand Δ / z_max + p_max + w Π_k (1 − m_k).
// The Gaussian is cut at ±4σ (kCutoffSigmas; past it, below e⁻⁸ of its peak, it is 0, and it is
// scaled by 1 / erf(4/√2) to a total of 1 again), so an
// echo's cone ends at z + 4σ: a cell farther cannot cause it, and a reading caused nearer tells
// nothing of it. A no-echo reading's cone reaches z_max.
//
// EM (the paper's; docs/forward-model.md, "EM"). The hidden variable of a reading is its cause c:
// random, a max-range failure, cell k of its cone, or "nothing met". The E-step gives each cause
// its responsibility e = p(c | z, m) under the present map; the M-step maximises the expected
// log-likelihood
//   Q(m) = Σ_readings Σ_c e_c log p(z, c | m),
// which falls apart into one term per cell, A_j log m_j + B_j log(1 − m_j), with A_j the
// responsibility of cell j for the readings it may cause (its expected hits) and B_j that of the
// causes beyond it (the expected readings that passed it); so m_j = A_j / (A_j + B_j). EM never
// lowers the log-likelihood Σ log p(z | m); the trace of it is reported per iteration. The map
// starts uniform at p_init; it stops when an iteration raises the log-likelihood by less than
// kRelativeTolerance of its size, or after the iteration cap.
//
// The posterior (the paper's approximation): each cell's p(occupied) given the readings, with
// every other cell held at its EM value m*,
//   log-odds_j = log((A_j + 1) / (B_j + 1))
//                + Σ_{readings meeting j} [log p(z | m*, m_j = 1) − log p(z | m*, m_j = 0)].
// The cell's prior is the Laplace estimate of its occupancy from EM's expected hits and passes
// under m*, (A_j + 1) / (A_j + B_j + 2): where its neighbours explain the readings as well as it
// does (the cells of one wall at one range) the sum is near 0, and a uniform prior would leave the
// cell at 0.5 whatever EM found; a cell whose expected counts are near 0 (behind a wall) stays
// near 0.5. The map's layers report it: p(occ) = σ(log-odds) (unobserved cells 0.5), the 16
// levels of it, "filled" where p > 0.5, EM's occupancy m* as its native value (what
// predictRange() reads) and max(0, 2p − 1) as its evidence; so views, exports and metrics read it
// unchanged.
//
// Deterministic and threaded by the thread policy (base/concurrency.h): the readings are cut into
// chunks of a fixed size whatever the thread count; each chunk's E-step sums into arrays of its
// own, which are added up in chunk order; so the map is bit-identical at any thread count.

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "sonargrid/data/dataset.h"
#include "sonargrid/engine/grid_spec.h"
#include "sonargrid/engine/occupancy_map.h"
#include "sonargrid/params/parameters.h"

namespace sg::forward {

// The name the model goes by in the CLI (`--model forward-em`), in project files and in the app.
inline constexpr const char* kModelName = "forward-em";
// What stands in the rule's place: EM is the model's own way of combining the readings.
inline constexpr const char* kRuleName = "em";
inline constexpr const char* kTitle = "Forward model learned by EM (Thrun 2003)";

// EM stops when an iteration raises the log-likelihood by less than this share of its size.
inline constexpr double kRelativeTolerance = 1e-7;
// The Gaussian is 0 past this many σ, and an echo's cone ends there (see above).
inline constexpr double kCutoffSigmas = 4.0;

class ForwardError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The model's parameters, declared once (name, symbol, unit, range, default, source) like every
// inverse model's: forwardParameterSpecs() lists them, settingsOf() reads them.
struct ForwardSettings {
  double omegaDeg = 25.0;  // cone aperture (full angle)
  double sigma = 0.05;     // m, the range's standard deviation around the cause's distance
  double pRandom = 0.05;   // share of random readings
  double pMax = 0.1;       // share of max-range failures (no echo whatever the cone meets)
  double pInit = 0.1;      // every cell's occupancy where EM starts
  int iterations = 50;     // EM's cap
};
std::vector<ParameterSpec> forwardParameterSpecs();
ParameterSet defaultForwardParameters();
// The settings `params` holds (names of forwardParameterSpecs(); others are ignored).
ForwardSettings settingsOf(const ParameterSet& params);

// One reading placed in the world, as EM sees it.
struct ForwardBeam {
  Pose2D sensor;
  double range = 0.0;  // metres, or Reading::kNoEcho (a range at or beyond maxRange is no echo)
  double maxRange = 5.0;
  bool echo() const { return range < maxRange; }
};

// Every reading's cone: the cells, ordered by distance (ties by index), and their distances.
// Reading r owns entries [first[r], first[r + 1]).
struct Cones {
  std::vector<std::uint64_t> first{0};
  std::vector<std::uint32_t> cell;
  std::vector<float> distance;
  std::vector<float> range;  // per reading: the echo's range, or +inf for none
  std::vector<float> maxRange;
  std::size_t readings() const { return first.size() - 1; }
};
// The cones of `beams` on `grid`, on the thread policy's threads (the same at any count).
Cones conesOf(const std::vector<ForwardBeam>& beams, const GridSpec& grid,
              const ForwardSettings& s);

// The readings of `data` up to time `until` as beams, with the pose of `source` (scans without it
// are left out, as the inverse models' mapper leaves them out). Throws ForwardError for a reading
// naming a sonar the ring lacks.
std::vector<ForwardBeam> beamsOf(const Dataset& data, PoseSource source,
                                 double until = std::numeric_limits<double>::infinity());

struct EmProgress {
  int iteration = 0;  // iterations done
  int cap = 0;
  double logLikelihood = 0.0;
};

struct EmResult {
  OccupancyMap map;
  std::vector<double> occupancy;  // m*, per cell (p_init where no reading met the cell)
  // log p(all readings | m) for the starting map and after each iteration: never decreasing.
  std::vector<double> logLikelihood;
  int iterations = 0;      // M-steps done
  bool converged = false;  // stopped by the tolerance, not the cap
  bool cancelled = false;  // stopped by `cancel` or `stop`: the result holds no map
  std::size_t readings = 0;
  std::size_t coneCells = 0;  // entries of all cones: what EM touches per iteration
};

// EM over `beams` on `grid`. `progress` (if any) is called after every iteration on the calling
// thread; `cancel` and `stop` (a sweep's own stop; either may be null) are read between iterations
// and between chunks. Throws ForwardError for settings out of range, a grid without cells, or a
// beam whose maximum range is not a positive finite length, whose range is negative or NaN, or
// whose pose is not finite (naming the reading).
EmResult runEm(const std::vector<ForwardBeam>& beams, const GridSpec& grid,
               const ForwardSettings& settings, const std::atomic<bool>* cancel = nullptr,
               const std::function<void(const EmProgress&)>& progress = {},
               const std::atomic<bool>* stop = nullptr);

// Whether `map` was learned by EM (its model and rule names): its native layer is then m*.
bool isForwardModelMap(const OccupancyMap& map);

// For the beam view: one reading's predicted range distribution under the map `occupancy` (per
// cell of `grid`): the density of z at each of `ranges` (per metre), and the probability of no
// echo (a failure, nothing met, or a random reading in the last bin of width Δ, as the likelihood
// counts it). What a teacher sets beside the measured range.
struct RangePrediction {
  std::vector<double> density;
  double noEcho = 0.0;
};
RangePrediction predictRange(const ForwardBeam& beam, const GridSpec& grid,
                             const std::vector<double>& occupancy, const ForwardSettings& s,
                             const std::vector<double>& ranges);

}  // namespace sg::forward
