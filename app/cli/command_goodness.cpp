// SPDX-License-Identifier: GPL-3.0-or-later
// `sonargrid-cli goodness`: map quality without a reference (paper 002 §5; docs/cli.md,
// docs/metrics.md): VSDNS, derivative noise and map entropy (Martin & Moravec 1996) of one run, and
// the two-run comparison when a second log of the same place is given.

#include <iostream>
#include <nlohmann/json.hpp>

#include "commands.h"
#include "map_options.h"
#include "sonargrid/metrics/derivative_noise.h"
#include "sonargrid/metrics/map_entropy.h"
#include "sonargrid/metrics/two_run_comparison.h"
#include "sonargrid/metrics/vsdns.h"
#include "sonargrid/sweep/sweep_grid.h"

namespace sg::cli {
namespace {

nlohmann::ordered_json orNull(const std::optional<double>& v) {
  return v ? nlohmann::ordered_json(*v) : nlohmann::ordered_json(nullptr);
}

}  // namespace

int runGoodness(Arguments& args) {
  const MapOptions o = parseMapOptions(args);
  const std::optional<std::string> secondLog = args.value("--second-log");
  const bool json = args.flag("--json");
  args.finish();

  const Dataset first = loadLog(o.log, o.read);
  std::optional<Dataset> second;
  if (secondLog) second = loadLog(*secondLog, o.read);
  GridSpec grid = fittingGridOf(first, o, o.log);
  if (second) {
    const GridSpec other = fittingGridOf(*second, o, *secondLog);
    try {
      grid = gridOverRuns(grid, other);
    } catch (const GridLimitError& e) {
      throw e.inFile(o.log + " and " + *secondLog);  // each fits; the two together do not
    }
  }

  VsdnsAccumulator vsdns;
  const BuiltMap run = buildMap(first, o, o.log, grid, &vsdns);
  const VsdnsAccumulator::Result spread = vsdns.result();
  const DerivativeNoise noise = derivativeNoise(run.map);
  const MapEntropy entropy = mapEntropy(run.map);
  std::optional<TwoRunComparison> twoRuns;
  std::optional<BuiltMap> secondRun;
  if (second) {
    secondRun = buildMap(*second, o, *secondLog, grid);
    twoRuns = compareTwoRuns(run.map, secondRun->map);
  }

  if (json) {
    nlohmann::ordered_json out;
    out["vsdns"] = orNull(spread.vsdns);
    out["derivative_noise"] = noise.sum;
    out["derivative_noise_mean"] = orNull(noise.mean);
    out["entropy_bits"] = entropy.observedBits;
    out["entropy_bits_mean"] = orNull(entropy.meanBits);
    out["entropy_bits_grid"] = entropy.totalBits;
    out["two_run_positive"] =
        twoRuns ? nlohmann::ordered_json(twoRuns->positive) : nlohmann::ordered_json(nullptr);
    out["two_run_negative"] =
        twoRuns ? nlohmann::ordered_json(twoRuns->negative) : nlohmann::ordered_json(nullptr);
    std::cout << out.dump() << '\n';
    return 0;
  }
  std::cout << o.log << ": " << run.readings << " readings mapped with " << o.settings.model
            << " x " << o.settings.rule << " on " << grid.width << " x " << grid.height
            << " cells of " << grid.cellSize << " m\n";
  std::cout << "  VSDNS                 ";
  if (spread.vsdns)
    std::cout << *spread.vsdns;
  else
    std::cout << "undefined";
  std::cout << "  (mean sigma of the model's values over " << spread.cellsWithSpread
            << " cells with sigma != 0)\n";
  std::cout << "  derivative noise      " << noise.sum << "  (sum over " << noise.cellsScored
            << " fully observed 3x3 windows; mean ";
  if (noise.mean)
    std::cout << *noise.mean;
  else
    std::cout << "undefined";
  std::cout << ")\n";
  std::cout << "  map entropy           " << entropy.observedBits << " bits  (over "
            << entropy.cellsObserved << " observed cells; mean ";
  if (entropy.meanBits)
    std::cout << *entropy.meanBits;
  else
    std::cout << "undefined";
  std::cout << " bits per cell; " << entropy.totalBits << " bits over the whole grid)\n";
  if (twoRuns) {
    std::cout << "  two runs (" << *secondLog << ")  " << twoRuns->positive << " cells agree, "
              << twoRuns->negative
              << " differ (occupied when p > 0.5; cells observed in both runs)\n";
  }
  return 0;
}

}  // namespace sg::cli
